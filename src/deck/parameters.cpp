#include "deck/parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <utility>

#include "core/text.h"

namespace impactfe::deck {

const char* param_type_name(ParamType type) {
  switch (type) {
    case ParamType::Number:
      return "SCALAR";
    case ParamType::Text:
      return "CHARACTER";
    case ParamType::Array:
      return "ARRAY";
    case ParamType::CharArray:
      return "CHAR";
    case ParamType::Table:
      return "TABLE";
    case ParamType::StringArray:
      return "STRING";
  }
  return "?";
}

// ---- Param ---------------------------------------------------------------------------------

std::size_t Param::offset(int i, int j, int k) const {
  if (type == ParamType::StringArray)
    return static_cast<std::size_t>(j - 1) +
           static_cast<std::size_t>(jmax) * static_cast<std::size_t>(k - 1);
  if (type == ParamType::Table) {
    const auto ni = static_cast<std::size_t>(imax + 1);
    const auto nj = static_cast<std::size_t>(jmax + 1);
    return static_cast<std::size_t>(i) +
           ni * (static_cast<std::size_t>(j) + nj * static_cast<std::size_t>(k));
  }
  const auto ni = static_cast<std::size_t>(imax);
  const auto nj = static_cast<std::size_t>(jmax);
  return static_cast<std::size_t>(i - 1) +
         ni * (static_cast<std::size_t>(j - 1) + nj * static_cast<std::size_t>(k - 1));
}

Value Param::entry(int i, int j, int k) const {
  if (type == ParamType::CharArray) return texts[offset(i, j, k)];
  if (type == ParamType::StringArray) {
    const std::string& t = texts[offset(i, j, k)];
    const auto from = static_cast<std::size_t>(i - 1);
    return from < t.size() ? t.substr(from) : std::string();
  }
  return values[offset(i, j, k)];
}

Param Param::scalar(double v) {
  Param p;
  p.type = ParamType::Number;
  p.number = v;
  return p;
}

Param Param::character(std::string t) {
  Param p;
  p.type = ParamType::Text;
  p.text = std::move(t);
  return p;
}

Param Param::array(ParamType type, int imax, int jmax, int kmax) {
  Param p;
  p.type = type;
  p.imax = imax;
  p.jmax = jmax;
  p.kmax = kmax;
  if (type == ParamType::CharArray) {
    p.texts.assign(static_cast<std::size_t>(imax) * jmax * kmax, std::string());
  } else if (type == ParamType::StringArray) {
    p.texts.assign(static_cast<std::size_t>(jmax) * kmax, std::string());
  } else if (type == ParamType::Table) {
    p.values.assign(static_cast<std::size_t>(imax + 1) * (jmax + 1) * (kmax + 1), 0.0);
    p.variables = {"ROW", "COLUMN", "PLANE"};
  } else {
    p.values.assign(static_cast<std::size_t>(imax) * jmax * kmax, 0.0);
  }
  return p;
}

namespace {

/// Bracket of x in the ascending index values idx[1..n]: lower position and weight of the
/// upper one; outside the range the end value (weight 0 at the nearest end).
void bracket(const std::vector<double>& idx, double x, int& lo, double& w) {
  const int n = static_cast<int>(idx.size()) - 1;  // idx[0] unused
  if (n <= 1 || x <= idx[1]) {
    lo = 1;
    w = 0.0;
    return;
  }
  if (x >= idx[static_cast<std::size_t>(n)]) {
    lo = n;
    w = 0.0;
    return;
  }
  for (int i = 1; i < n; ++i) {
    const double a = idx[static_cast<std::size_t>(i)];
    const double b = idx[static_cast<std::size_t>(i + 1)];
    if (x >= a && x <= b) {
      lo = i;
      w = b > a ? (x - a) / (b - a) : 0.0;
      return;
    }
  }
  lo = n;
  w = 0.0;
}

}  // namespace

double table_lookup(const Param& t, double x, double y, double z) {
  std::vector<double> rows(static_cast<std::size_t>(t.imax) + 1);
  std::vector<double> cols(static_cast<std::size_t>(t.jmax) + 1);
  std::vector<double> planes(static_cast<std::size_t>(t.kmax) + 1);
  const int k0 = t.kmax >= 1 ? 1 : 0;
  for (int i = 1; i <= t.imax; ++i)
    rows[static_cast<std::size_t>(i)] = t.values[t.offset(i, 0, k0)];
  for (int j = 1; j <= t.jmax; ++j)
    cols[static_cast<std::size_t>(j)] = t.values[t.offset(0, j, k0)];
  for (int k = 1; k <= t.kmax; ++k)
    planes[static_cast<std::size_t>(k)] = t.values[t.offset(0, 0, k)];
  int i = 1, j = 1, k = 1;
  double wi = 0.0, wj = 0.0, wk = 0.0;
  bracket(rows, x, i, wi);
  bracket(cols, y, j, wj);
  bracket(planes, z, k, wk);
  double sum = 0.0;
  for (int di = 0; di <= 1; ++di)
    for (int dj = 0; dj <= 1; ++dj)
      for (int dk = 0; dk <= 1; ++dk) {
        const double w = (di ? wi : 1.0 - wi) * (dj ? wj : 1.0 - wj) * (dk ? wk : 1.0 - wk);
        if (w == 0.0) continue;
        sum += w * t.values[t.offset(i + di, j + dj, k + dk)];
      }
  return sum;
}

bool is_local_name(std::string_view n) {
  auto digits = [](std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
      return std::isdigit(static_cast<unsigned char>(c));
    });
  };
  if (n.size() == 4 && n.substr(0, 3) == "ARG") return n[3] >= '1' && n[3] <= '9';
  if (n.size() == 4 && n.substr(0, 2) == "AR" && digits(n.substr(2))) return n[2] != '0';
  return false;
}

// ---- Parameters ------------------------------------------------------------------------------

const Param* Parameters::find(const std::string& name) const {
  const std::string n = to_upper(name);
  const auto& table = is_local_name(n) ? locals_.back() : globals_;
  auto it = table.find(n);
  return it == table.end() ? nullptr : &it->second;
}

Param* Parameters::find(const std::string& name) {
  return const_cast<Param*>(std::as_const(*this).find(name));
}

Param& Parameters::define(const std::string& name, Param p) {
  const std::string n = to_upper(name);
  auto& table = is_local_name(n) ? locals_.back() : globals_;
  return table[n] = std::move(p);
}

void Parameters::set(const std::string& name, double value) {
  define(name, Param::scalar(value));
}

void Parameters::set_text(const std::string& name, const std::string& value) {
  define(name, Param::character(value));
}

void Parameters::erase(const std::string& name) {
  const std::string n = to_upper(name);
  (is_local_name(n) ? locals_.back() : globals_).erase(n);
}

std::optional<double> Parameters::get(const std::string& name) const {
  const Param* p = find(name);
  if (p == nullptr) {
    if (is_local_name(to_upper(name))) return 0.0;
    return std::nullopt;
  }
  if (p->type != ParamType::Number) return std::nullopt;
  return p->number;
}

void Parameters::clear() {
  // The local parameters ARG1..AR99 belong to the macro calls running, not to the database: a
  // macro that issues /CLEAR keeps its arguments (vmc5: PARSAV, /CLEAR, PARRES, ET,1,ARG1).
  globals_.clear();
  degrees = false;
  random.seed(20240611u);
}

bool is_parameter_name(std::string_view name) {
  if (name.empty() || name.size() > 32) return false;
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

std::optional<SubscriptedName> split_subscripted_name(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  const std::size_t start = i;
  while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_'))
    ++i;
  SubscriptedName out;
  out.name = to_upper(text.substr(start, i - start));
  if (!is_parameter_name(out.name)) return std::nullopt;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  if (i == text.size()) return out;
  if (text[i] != '(') return std::nullopt;
  out.has_parentheses = true;
  int depth = 0;
  bool quoted = false;
  std::string current;
  for (++i; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'') quoted = !quoted;
    if (!quoted && c == '(') ++depth;
    if (!quoted && c == ')') {
      if (depth == 0) break;
      --depth;
    }
    if (!quoted && depth == 0 && c == ',') {
      out.subscripts.push_back(current);
      current.clear();
      continue;
    }
    current += c;
  }
  if (i == text.size()) return std::nullopt;  // no closing parenthesis
  out.subscripts.push_back(current);
  for (++i; i < text.size(); ++i)
    if (text[i] != ' ' && text[i] != '\t') return std::nullopt;  // text after the ')'
  for (auto& s : out.subscripts) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    s = b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  }
  return out;
}

std::string format_number(double value) {
  if (std::isfinite(value) && std::fabs(value) < 1e15 && value == std::trunc(value))
    return fmt::format("{}", static_cast<long long>(value));
  std::string s = fmt::format("{}", value);  // shortest round-trip text
  for (char& ch : s)
    if (ch == 'e') ch = 'E';
  return s;
}

}  // namespace impactfe::deck
