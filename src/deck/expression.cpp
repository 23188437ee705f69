// The APDL expression grammar (APDL_SCRIPTING §A.3) and the built-in functions (§A.4).
#include "deck/expression.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "core/text.h"
#include "deck/lexer.h"

namespace impactfe::deck {

namespace {

double require_number(const Value& v, const char* where) {
  if (is_text(v))
    throw ExpressionError(
        fmt::format("text '{}' used {} (a number is needed)", std::get<std::string>(v), where));
  return std::get<double>(v);
}

double finite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw ExpressionError(what + " gives no finite number");
  return v;
}

int subscript(double v, const std::string& name) {
  if (!std::isfinite(v) || std::fabs(v) > 1e9)
    throw ExpressionError(fmt::format("bad subscript of {}", name));
  return static_cast<int>(std::lround(v));
}

/// Built-in functions (§A.4): name, argument count (-1: two or more), evaluation.
double call_builtin(const std::string& f, const std::vector<double>& a, const Parameters& p,
                    bool& known) {
  known = true;
  auto need = [&](std::size_t n) {
    if (a.size() != n)
      throw ExpressionError(
          fmt::format("{} takes {} argument{}, {} given", f, n, n == 1 ? "" : "s", a.size()));
  };
  const double to_rad = p.degrees ? std::numbers::pi / 180.0 : 1.0;
  const double from_rad = 1.0 / to_rad;
  if (f == "MIN" || f == "MAX") {  // program extension (S3)
    if (a.empty()) throw ExpressionError(f + " needs at least one argument");
    double v = a[0];
    for (double x : a) v = f == "MIN" ? std::min(v, x) : std::max(v, x);
    return v;
  }
  if (f == "MOD") {
    need(2);
    if (a[1] == 0.0) throw ExpressionError("MOD by zero");
    return std::fmod(a[0], a[1]);  // Fortran: x - y*int(x/y), sign of x
  }
  if (f == "SIGN") {
    need(2);
    return a[1] >= 0.0 ? std::fabs(a[0]) : -std::fabs(a[0]);
  }
  if (f == "ATAN2") {
    need(2);
    return std::atan2(a[0], a[1]) * from_rad;
  }
  if (f == "CXABS") {
    need(2);
    return std::hypot(a[0], a[1]);
  }
  if (f == "RAND") {
    need(2);
    return std::uniform_real_distribution<double>(a[0], a[1])(p.random);
  }
  if (f == "GDIS") {
    need(2);
    if (a[1] < 0.0) throw ExpressionError("GDIS: negative standard deviation");
    if (a[1] == 0.0) return a[0];
    return std::normal_distribution<double>(a[0], a[1])(p.random);
  }
  static const char* const one_arg[] = {"ABS",  "SQRT", "EXP",  "LOG",  "LOG10",
                                        "SIN",  "COS",  "TAN",  "ASIN", "ACOS",
                                        "ATAN", "SINH", "COSH", "TANH", "NINT"};
  bool unary = false;
  for (const char* n : one_arg) unary = unary || f == n;
  if (!unary) {
    known = false;
    return 0.0;
  }
  need(1);
  const double x = a[0];
  if (f == "ABS") return std::fabs(x);
  if (f == "SQRT") {
    if (x < 0.0) throw ExpressionError("SQRT of a negative number");
    return std::sqrt(x);
  }
  if (f == "EXP") return finite(std::exp(x), "EXP");
  if (f == "LOG" || f == "LOG10") {
    if (x <= 0.0) throw ExpressionError(f + " of a non-positive number");
    return f == "LOG" ? std::log(x) : std::log10(x);
  }
  if (f == "SIN") return std::sin(x * to_rad);
  if (f == "COS") return std::cos(x * to_rad);
  if (f == "TAN") return finite(std::tan(x * to_rad), "TAN");
  if (f == "ASIN" || f == "ACOS") {
    if (std::fabs(x) > 1.0) throw ExpressionError(f + " of a number outside [-1, 1]");
    return (f == "ASIN" ? std::asin(x) : std::acos(x)) * from_rad;
  }
  if (f == "ATAN") return std::atan(x) * from_rad;
  if (f == "SINH") return finite(std::sinh(x), "SINH");
  if (f == "COSH") return finite(std::cosh(x), "COSH");
  if (f == "TANH") return std::tanh(x);
  return std::round(x);  // NINT: halves away from zero (Fortran)
}

/// Recursive-descent parser of the MAPDL order of operations (APDL Programmer's Guide §3.7,
/// "Parametric Expressions"; APDL_SCRIPTING §A.3): parentheses, `**` right to left, `*` `/` left
/// to right, unary `+` `-`, binary `+` `-` left to right, then `<` `>` left to right.
///   cond := additive {(<|>) additive};  additive := signed_term {(+|-) signed_term};
///   signed_term := (+|-) signed_term | term;  term := factor {(*|/) factor};
///   factor := (+|-) factor | power;  power := primary [** exponent];
///   exponent := (+|-) exponent | power.
/// A unary sign at the head of a term applies to the whole term (`-A*B = -(A*B)`,
/// `-2**2 = -4`); a sign right after `*`, `/` or `**` (`A*-B`, `2**-1`, an extension: MAPDL
/// documents no two adjacent operators) applies to the one operand that follows it, never to the
/// rest of the term (`A/-B*C = (A/(-B))*C`, `I**2*3 = (I**2)*3`).
class Parser {
 public:
  Parser(std::string_view text, const Parameters& params, const FunctionHost* host)
      : s_(text), p_(params), host_(host) {}

  Value parse() {
    Value v = cond();
    skip();
    if (i_ != s_.size())
      throw ExpressionError("unexpected '" + std::string(s_.substr(i_)) + "' in expression");
    return v;
  }

 private:
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }
  bool peek(char c) {
    skip();
    return i_ < s_.size() && s_[i_] == c;
  }
  bool accept(std::string_view tok) {
    skip();
    if (s_.substr(i_, tok.size()) == tok) {
      i_ += tok.size();
      return true;
    }
    return false;
  }
  Value cond() {
    Value v = additive();
    for (;;) {
      if (accept("<")) {
        const double a = require_number(v, "with <");
        const double b = require_number(additive(), "with <");
        v = a < b ? a : b;
      } else if (accept(">")) {
        const double a = require_number(v, "with >");
        const double b = require_number(additive(), "with >");
        v = a > b ? a : b;
      } else {
        return v;
      }
    }
  }
  Value additive() {
    Value v = signed_term();
    for (;;) {
      skip();
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) {
        const char op = s_[i_++];
        const double a = require_number(v, "in arithmetic");
        const double b = require_number(signed_term(), "in arithmetic");
        v = op == '+' ? a + b : a - b;
      } else {
        return v;
      }
    }
  }
  /// A sign that heads a term: it applies after the term's products and powers.
  Value signed_term() {
    if (accept("-")) return -require_number(signed_term(), "after a sign");
    if (accept("+")) return require_number(signed_term(), "after a sign");
    return term();
  }
  Value term() {
    Value v = factor();
    for (;;) {
      skip();
      if (s_.substr(i_, 2) == "**") return v;  // only after a factor that is not a power
      if (i_ < s_.size() && (s_[i_] == '*' || s_[i_] == '/')) {
        const char op = s_[i_++];
        const double a = require_number(v, "in arithmetic");
        const double b = require_number(factor(), "in arithmetic");
        if (op == '*') {
          v = a * b;
        } else {
          if (b == 0.0) throw ExpressionError("division by zero");
          v = a / b;
        }
      } else {
        return v;
      }
    }
  }
  /// An operand of `*` or `/`; a sign written right after the operator applies to it alone.
  Value factor() {
    if (accept("-")) return -require_number(factor(), "after a sign");
    if (accept("+")) return require_number(factor(), "after a sign");
    return power();
  }
  Value power() {
    Value base = primary();
    if (accept("**")) {
      const double a = require_number(base, "with **");
      const double b = require_number(exponent(), "with **");
      const double r = std::pow(a, b);
      if (!std::isfinite(r))
        throw ExpressionError(
            fmt::format("invalid power {}**{}", format_number(a), format_number(b)));
      return r;
    }
    return base;
  }
  /// The right operand of `**`: a power again (right to left), optionally signed.
  Value exponent() {
    if (accept("-")) return -require_number(exponent(), "after a sign");
    if (accept("+")) return require_number(exponent(), "after a sign");
    return power();
  }
  Value primary() {
    skip();
    if (i_ >= s_.size()) throw ExpressionError("expression ends unexpectedly");
    const char c = s_[i_];
    if (c == '(') {
      ++i_;
      Value v = cond();
      if (!accept(")")) throw ExpressionError("missing ')'");
      return v;
    }
    if (c == '\'') return quoted();
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    throw ExpressionError(std::string("unexpected '") + c + "' in expression");
  }
  Value quoted() {
    ++i_;
    std::string text;
    for (; i_ < s_.size(); ++i_) {
      if (s_[i_] == '\'') {
        if (i_ + 1 < s_.size() && s_[i_ + 1] == '\'') {  // '' = one quote
          text += '\'';
          ++i_;
          continue;
        }
        ++i_;
        return text;
      }
      text += s_[i_];
    }
    throw ExpressionError("unterminated quoted string");
  }
  Value name() {
    std::size_t j = i_;
    while (j < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[j])) || s_[j] == '_')) ++j;
    const std::string n = to_upper(s_.substr(i_, j - i_));
    i_ = j;
    const Param* param = p_.find(n);
    if (peek('(')) {
      ++i_;
      std::vector<Value> args;
      bool blank_argument = false;
      if (!peek(')')) {
        // A blank argument of a function is 0, as a blank numeric field is (NODE(,,,) is the
        // node nearest the origin); trailing blank arguments are not given.
        std::size_t given = 0;
        do {
          if (peek(',') || peek(')')) {
            blank_argument = true;
            args.emplace_back(0.0);
          } else {
            args.push_back(cond());
            given = args.size();
          }
        } while (accept(","));
        args.resize(std::max<std::size_t>(given, 1));
      }
      if (!accept(")")) throw ExpressionError("missing ')' after the arguments of " + n);
      if (param != nullptr && param->is_array()) {
        if (blank_argument) throw ExpressionError(fmt::format("blank subscript of {}", n));
        return element(n, *param, args);
      }
      // A scalar parameter may share its name with a get function (UZ = node UZ stored by
      // *GET, then UZ(N) the function): with parentheses the name is the function.
      std::vector<double> x;
      for (const auto& a : args) x.push_back(require_number(a, ("as an argument of " + n).c_str()));
      bool known = false;
      const double v = call_builtin(n, x, p_, known);
      if (known) return v;
      double result = 0.0;
      if (host_ != nullptr && host_->call(n, x, result)) return result;
      if (param != nullptr)
        throw ExpressionError(fmt::format("'{}' is a scalar parameter, not an array", n));
      throw ExpressionError(fmt::format("'{}' is neither an array parameter nor a function", n));
    }
    if (param == nullptr) {
      if (is_local_name(n)) return 0.0;  // unset macro argument
      throw ExpressionError("'" + n + "' is not a defined parameter");
    }
    switch (param->type) {
      case ParamType::Number:
        return param->number;
      case ParamType::Text:
        return param->text;
      default:
        throw ExpressionError(fmt::format("'{}' is an array: give subscripts, e.g. {}(1)", n, n));
    }
  }
  Value element(const std::string& n, const Param& p, const std::vector<Value>& args) {
    if (args.empty() || args.size() > 3)
      throw ExpressionError(fmt::format("{} takes 1 to 3 subscripts, {} given", n, args.size()));
    std::vector<double> x;
    for (const auto& a : args) x.push_back(require_number(a, ("as a subscript of " + n).c_str()));
    if (p.type == ParamType::Table) {
      // Subscripts are values of the primary variables (§A.7); a missing one takes the first
      // index value of its dimension.
      const int k0 = 1;
      const double y = x.size() > 1 ? x[1] : p.values[p.offset(0, 1, k0)];
      const double z = x.size() > 2 ? x[2] : p.values[p.offset(0, 0, 1)];
      return table_lookup(p, x[0], y, z);
    }
    int s[3] = {1, 1, 1};
    for (std::size_t k = 0; k < x.size(); ++k) s[k] = subscript(x[k], n);
    if (!p.in_range(s[0], s[1], s[2]))
      throw ExpressionError(
          fmt::format("subscript ({},{},{}) of {} out of range (dimensions {}x{}x{})", s[0], s[1],
                      s[2], n, p.imax, p.jmax, p.kmax));
    return p.entry(s[0], s[1], s[2]);
  }
  Value number() {
    // Mantissa, then an exponent: E/D with optional sign, or MAPDL's `123-002` form (a sign
    // followed by at least two digits starting with 0, §A.3).
    std::size_t j = i_;
    while (j < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[j])) || s_[j] == '.')) ++j;
    std::string text(s_.substr(i_, j - i_));
    if (j < s_.size() && std::strchr("eEdD", s_[j]) != nullptr) {
      std::size_t k = j + 1;
      if (k < s_.size() && (s_[k] == '+' || s_[k] == '-')) ++k;
      if (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) {
        while (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) ++k;
        text = std::string(s_.substr(i_, k - i_));
        j = k;
      }
    } else if (j + 2 < s_.size() && (s_[j] == '+' || s_[j] == '-') && s_[j + 1] == '0' &&
               std::isdigit(static_cast<unsigned char>(s_[j + 2]))) {
      std::size_t k = j + 1;
      while (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) ++k;
      text += "E" + std::string(s_.substr(j, k - j));
      j = k;
    }
    auto v = parse_fortran_number(text);
    if (!v) throw ExpressionError("bad number '" + std::string(s_.substr(i_, j - i_)) + "'");
    i_ = j;
    return *v;
  }

  std::string_view s_;
  const Parameters& p_;
  const FunctionHost* host_;
  std::size_t i_ = 0;
};

}  // namespace

bool is_builtin_function(const std::string& n) {
  static const char* const names[] = {"ABS",   "SIGN", "SQRT",  "EXP",  "LOG",  "LOG10",
                                      "SIN",   "COS",  "TAN",   "ASIN", "ACOS", "ATAN",
                                      "ATAN2", "SINH", "COSH",  "TANH", "NINT", "MOD",
                                      "MIN",   "MAX",  "CXABS", "RAND", "GDIS"};
  for (const char* f : names)
    if (n == f) return true;
  return false;
}

Value evaluate_value(std::string_view expression, const Parameters& parameters,
                     const FunctionHost* functions) {
  return Parser(expression, parameters, functions).parse();
}

double evaluate(std::string_view expression, const Parameters& parameters,
                const FunctionHost* functions) {
  const Value v = evaluate_value(expression, parameters, functions);
  if (is_text(v))
    throw ExpressionError(fmt::format("'{}' is a text, not a number", std::get<std::string>(v)));
  return std::get<double>(v);
}

}  // namespace impactfe::deck
