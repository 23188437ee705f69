#include "deck/expression.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "deck/lexer.h"

namespace impactfe::deck {

void Parameters::set(const std::string& name, double value) {
  values_[to_upper(name)] = value;
}
void Parameters::erase(const std::string& name) {
  values_.erase(to_upper(name));
}
std::optional<double> Parameters::get(const std::string& name) const {
  auto it = values_.find(to_upper(name));
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

bool is_parameter_name(std::string_view name) {
  if (name.empty() || name.size() > 32 || !std::isalpha(static_cast<unsigned char>(name[0])))
    return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

namespace {

/// Recursive-descent parser:  sum := term {(+|-) term};  term := unary {(*|/) unary};
/// unary := (+|-) unary | power;  power := primary [** unary]  (right-associative).
class Parser {
 public:
  Parser(std::string_view text, const Parameters& params) : s_(text), p_(params) {}

  double parse() {
    const double v = sum();
    skip();
    if (i_ != s_.size())
      throw ExpressionError("unexpected '" + std::string(s_.substr(i_)) + "' in expression");
    return v;
  }

 private:
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }
  bool accept(std::string_view tok) {
    skip();
    if (s_.substr(i_, tok.size()) == tok) {
      i_ += tok.size();
      return true;
    }
    return false;
  }
  double sum() {
    double v = term();
    for (;;) {
      if (accept("+"))
        v += term();
      else if (accept("-"))
        v -= term();
      else
        return v;
    }
  }
  double term() {
    double v = unary();
    for (;;) {
      skip();
      if (s_.substr(i_, 2) == "**") return v;  // handled in power()
      if (accept("*")) {
        v *= unary();
      } else if (accept("/")) {
        const double d = unary();
        if (d == 0.0) throw ExpressionError("division by zero");
        v /= d;
      } else {
        return v;
      }
    }
  }
  double unary() {
    if (accept("-")) return -unary();
    if (accept("+")) return unary();
    return power();
  }
  double power() {
    const double base = primary();
    if (accept("**")) return std::pow(base, unary());
    return base;
  }
  double primary() {
    skip();
    if (i_ >= s_.size()) throw ExpressionError("expression ends unexpectedly");
    const char c = s_[i_];
    if (c == '(') {
      ++i_;
      const double v = sum();
      if (!accept(")")) throw ExpressionError("missing ')'");
      return v;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i_;
      while (j < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[j])) || s_[j] == '_'))
        ++j;
      const std::string name = to_upper(s_.substr(i_, j - i_));
      i_ = j;
      skip();
      if (i_ < s_.size() && s_[i_] == '(') {
        ++i_;
        std::vector<double> args{sum()};
        while (accept(",")) args.push_back(sum());
        if (!accept(")")) throw ExpressionError("missing ')' after arguments of " + name);
        return call(name, args);
      }
      auto v = p_.get(name);
      if (!v) throw ExpressionError("'" + name + "' is not a defined parameter");
      return *v;
    }
    throw ExpressionError(std::string("unexpected '") + c + "' in expression");
  }
  double number() {
    // Longest prefix that parses as a Fortran number (mantissa, optional exponent).
    std::size_t j = i_;
    while (j < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[j])) || s_[j] == '.')) ++j;
    if (j < s_.size() && std::strchr("eEdD", s_[j]) != nullptr) {
      std::size_t k = j + 1;
      if (k < s_.size() && (s_[k] == '+' || s_[k] == '-')) ++k;
      if (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) {
        while (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) ++k;
        j = k;
      }
    }
    auto v = parse_fortran_number(s_.substr(i_, j - i_));
    if (!v) throw ExpressionError("bad number '" + std::string(s_.substr(i_, j - i_)) + "'");
    i_ = j;
    return *v;
  }
  double call(const std::string& f, const std::vector<double>& a) {
    auto need = [&](std::size_t n) {
      if (a.size() != n) throw ExpressionError(f + " takes " + std::to_string(n) + " argument(s)");
    };
    const double to_rad = p_.degrees ? std::numbers::pi / 180.0 : 1.0;
    const double from_rad = 1.0 / to_rad;
    if (f == "MOD") {
      need(2);
      if (a[1] == 0.0) throw ExpressionError("MOD by zero");
      return std::fmod(a[0], a[1]);
    }
    need(1);
    const double x = a[0];
    if (f == "SIN") return std::sin(x * to_rad);
    if (f == "COS") return std::cos(x * to_rad);
    if (f == "TAN") return std::tan(x * to_rad);
    if (f == "ASIN") return std::asin(x) * from_rad;
    if (f == "ACOS") return std::acos(x) * from_rad;
    if (f == "ATAN") return std::atan(x) * from_rad;
    if (f == "SQRT") {
      if (x < 0.0) throw ExpressionError("SQRT of a negative number");
      return std::sqrt(x);
    }
    if (f == "ABS") return std::fabs(x);
    if (f == "EXP") return std::exp(x);
    if (f == "LOG") {
      if (x <= 0.0) throw ExpressionError("LOG of a non-positive number");
      return std::log(x);
    }
    if (f == "LOG10") {
      if (x <= 0.0) throw ExpressionError("LOG10 of a non-positive number");
      return std::log10(x);
    }
    if (f == "NINT") return std::round(x);  // Fortran NINT: halves away from zero
    throw ExpressionError("unknown function " + f);
  }

  std::string_view s_;
  const Parameters& p_;
  std::size_t i_ = 0;
};

}  // namespace

double evaluate(std::string_view expression, const Parameters& parameters) {
  return Parser(expression, parameters).parse();
}

}  // namespace impactfe::deck
