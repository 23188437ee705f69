// TEMPORARY stand-in for the language branch (see language_standin.h): deleted at merge.
#include "deck/language_standin.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "deck/post_state.h"

namespace impactfe::deck {

namespace {

struct Array {
  bool character = false;
  int dims[3] = {1, 1, 1};
  std::vector<double> numbers;
  std::vector<std::string> texts;
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>((i - 1) + dims[0] * ((j - 1) + dims[1] * (k - 1)));
  }
};

struct Standin {
  std::map<std::string, Array> arrays;
  std::map<std::string, std::string> texts;
  std::ofstream cf;
};

Standin& standin(DeckReader& r) {
  if (!r.post) r.post = std::make_shared<PostState>();
  if (!r.post->language_standin) r.post->language_standin = std::make_shared<Standin>();
  return *std::static_pointer_cast<Standin>(r.post->language_standin);
}

struct Target {
  std::string name;
  std::vector<int> subscripts;
};

Target parse_target(DeckReader& r, const Command& c, const std::string& text) {
  Target t;
  const auto open = text.find('(');
  t.name = to_upper(trim(text.substr(0, open)));
  if (open == std::string::npos) return t;
  const auto close = text.rfind(')');
  if (close == std::string::npos || close < open)
    r.fail(c, fmt::format("bad subscript in '{}'", text));
  std::string inner = text.substr(open + 1, close - open - 1);
  std::size_t start = 0;
  while (true) {
    const auto comma = inner.find(',', start);
    const std::string part = trim(inner.substr(start, comma - start));
    try {
      t.subscripts.push_back(static_cast<int>(std::lround(evaluate(part, r.params))));
    } catch (const ExpressionError& e) {
      r.fail(c, fmt::format("bad subscript '{}' ({})", part, e.what()));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return t;
}

Array& array_of(DeckReader& r, const Command& c, const Target& t) {
  auto& arrays = standin(r).arrays;
  const auto it = arrays.find(t.name);
  if (it == arrays.end()) r.fail(c, fmt::format("array '{}' is not dimensioned (*DIM)", t.name));
  return it->second;
}

std::size_t element_index(DeckReader& r, const Command& c, const Target& t, const Array& a) {
  int s[3] = {1, 1, 1};
  for (std::size_t k = 0; k < t.subscripts.size() && k < 3; ++k) s[k] = t.subscripts[k];
  for (int k = 0; k < 3; ++k)
    if (s[k] < 1 || s[k] > a.dims[k])
      r.fail(c, fmt::format("subscript {} of {} out of range 1..{}", s[k], t.name, a.dims[k]));
  return a.index(s[0], s[1], s[2]);
}

/// Fortran-style E format: 0.ddddE+xx with d digits in width w.
std::string fortran_e(double v, int w, int d) {
  if (v == 0.0) return fmt::format("{:>{}}", fmt::format("0.{}E+00", std::string(d, '0')), w);
  int e = static_cast<int>(std::floor(std::log10(std::fabs(v)))) + 1;
  double m = std::fabs(v) / std::pow(10.0, e);
  long digits = std::lround(m * std::pow(10.0, d));
  if (digits >= static_cast<long>(std::pow(10.0, d))) {
    digits /= 10;
    ++e;
  }
  return fmt::format("{:>{}}",
                     fmt::format("{}0.{:0{}d}E{}{:02d}", v < 0 ? "-" : "", digits, d,
                                 e < 0 ? '-' : '+', std::abs(e)),
                     w);
}

struct FormatItem {
  char kind;  // X A F E G I ' /
  int w = 0, d = 0;
  std::string text;
};

std::vector<FormatItem> parse_format(DeckReader& r, const Command& c, const std::string& f) {
  std::string s = trim(f);
  if (s.size() < 2 || s.front() != '(' || s.back() != ')')
    r.fail(c, fmt::format("format line '{}' is not a Fortran format (...)", f));
  s = s.substr(1, s.size() - 2);
  std::vector<FormatItem> out;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == ',' || s[i] == ' ') {
      ++i;
      continue;
    }
    if (s[i] == '\'') {
      const auto j = s.find('\'', i + 1);
      out.push_back({'\'', 0, 0, s.substr(i + 1, j - i - 1)});
      i = j + 1;
      continue;
    }
    if (s[i] == '/') {
      out.push_back({'/'});
      ++i;
      continue;
    }
    int repeat = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
      repeat = 10 * repeat + (s[i++] - '0');
    const char kind = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i++])));
    int w = 0, d = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
      w = 10 * w + (s[i++] - '0');
    if (i < s.size() && s[i] == '.') {
      ++i;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
        d = 10 * d + (s[i++] - '0');
    }
    if (kind == 'X') {
      out.push_back({'X', std::max(repeat, 1)});
      continue;
    }
    if (std::string("AFEGI").find(kind) == std::string::npos)
      r.fail(c, fmt::format("format descriptor '{}' not supported by the stand-in", kind));
    for (int k = 0; k < std::max(repeat, 1); ++k) out.push_back({kind, w, d});
  }
  return out;
}

void cmd_dim(DeckReader& r, const Command& c) {
  const std::string name = r.label(c, 1);
  const std::string type = r.label(c, 2).empty() ? "ARRAY" : r.label(c, 2);
  if (type != "ARRAY" && type != "CHAR") r.fail(c, "stand-in: ARRAY or CHAR only");
  Array a;
  a.character = type == "CHAR";
  for (int k = 0; k < 3; ++k) a.dims[k] = std::max(1, r.integer(c, 3 + k, 1));
  const std::size_t n = static_cast<std::size_t>(a.dims[0] * a.dims[1] * a.dims[2]);
  a.numbers.assign(n, 0.0);
  a.texts.assign(n, "");
  standin(r).arrays[name] = std::move(a);
}

void cmd_vfill(DeckReader& r, const Command& c) {
  const Target t = parse_target(r, c, c.text(1));
  const std::string func = r.label(c, 2);
  std::vector<double> values;
  if (func == "DATA") {
    for (int f = 3; f <= c.n_fields(); ++f) values.push_back(r.real(c, f, 0.0));
  } else if (func == "RAMP") {
    Array& a = array_of(r, c, t);
    const int n = a.dims[0] - (t.subscripts.empty() ? 1 : t.subscripts[0]) + 1;
    for (int k = 0; k < n; ++k) values.push_back(r.real(c, 3, 0.0) + k * r.real(c, 4, 0.0));
  } else {
    r.fail(c, "stand-in: DATA or RAMP only");
  }
  assign_vector(r, c, c.text(1), values);
}

void cmd_voper(DeckReader& r, const Command& c) {
  // *VOPER,ParR,Par1,Oper,Par2 over the rest of ParR's column.
  const Target tr = parse_target(r, c, c.text(1));
  Array& ar = array_of(r, c, tr);
  const int start = tr.subscripts.empty() ? 1 : tr.subscripts[0];
  const int n = ar.dims[0] - start + 1;
  const auto a = read_vector(r, c, c.text(2), n);
  const auto b = read_vector(r, c, c.text(4), n);
  const std::string op = r.label(c, 3);
  std::vector<double> out(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (op == "ADD")
      out[k] = a[k] + b[k];
    else if (op == "SUB")
      out[k] = a[k] - b[k];
    else if (op == "MULT")
      out[k] = a[k] * b[k];
    else if (op == "DIV")
      out[k] = b[k] != 0.0 ? a[k] / b[k] : 0.0;
    else
      r.fail(c, "stand-in: ADD, SUB, MULT or DIV only");
  }
  assign_vector(r, c, c.text(1), out);
}

void cmd_cfopen(DeckReader& r, const Command& c) {
  Standin& s = standin(r);
  if (s.cf.is_open()) s.cf.close();
  const std::string path = (c.blank(1) ? r.model.jobname : c.text(1)) + "." +
                           (c.blank(2) ? std::string("cmd") : c.text(2));
  s.cf.open(path, r.label(c, 4) == "APPEND" ? std::ios::app : std::ios::trunc);
  if (!s.cf) r.fail(c, fmt::format("cannot open '{}'", path));
}

void cmd_cfclos(DeckReader& r, const Command&) {
  Standin& s = standin(r);
  if (s.cf.is_open()) s.cf.close();
}

}  // namespace

void assign_parameter(DeckReader& r, const Command& c, const std::string& target, double value) {
  const Target t = parse_target(r, c, target);
  if (t.subscripts.empty()) {
    if (!is_parameter_name(t.name)) r.fail(c, fmt::format("'{}' is not a parameter name", target));
    standin(r).texts.erase(t.name);
    r.params.set(t.name, value);
    return;
  }
  Array& a = array_of(r, c, t);
  a.numbers[element_index(r, c, t, a)] = value;
}

void assign_text_parameter(DeckReader& r, const Command& c, const std::string& target,
                           const std::string& value) {
  const Target t = parse_target(r, c, target);
  if (t.subscripts.empty()) {
    r.params.erase(t.name);
    standin(r).texts[t.name] = value;
    return;
  }
  Array& a = array_of(r, c, t);
  a.texts[element_index(r, c, t, a)] = value;
}

void assign_vector(DeckReader& r, const Command& c, const std::string& target,
                   const std::vector<double>& values) {
  Target t = parse_target(r, c, target);
  auto& arrays = standin(r).arrays;
  if (arrays.count(t.name) == 0) {
    Array a;
    a.dims[0] = static_cast<int>(values.size()) + (t.subscripts.empty() ? 0 : t.subscripts[0] - 1);
    a.numbers.assign(static_cast<std::size_t>(a.dims[0]), 0.0);
    a.texts.assign(a.numbers.size(), "");
    arrays[t.name] = std::move(a);
  }
  Array& a = arrays.at(t.name);
  if (t.subscripts.empty()) t.subscripts = {1};
  int row = t.subscripts[0];
  for (double v : values) {
    if (row > a.dims[0]) break;
    Target e = t;
    e.subscripts[0] = row++;
    a.numbers[element_index(r, c, e, a)] = v;
  }
}

std::vector<double> read_vector(DeckReader& r, const Command& c, const std::string& source,
                                int count) {
  Target t = parse_target(r, c, source);
  const auto& arrays = standin(r).arrays;
  if (arrays.count(t.name) == 0) {
    // A scalar or a constant: repeated.
    double v = 0.0;
    try {
      v = evaluate(source, r.params);
    } catch (const ExpressionError& e) {
      r.fail(c, fmt::format("'{}' is neither an array nor a value ({})", source, e.what()));
    }
    return std::vector<double>(static_cast<std::size_t>(count), v);
  }
  const Array& a = arrays.at(t.name);
  if (t.subscripts.empty()) t.subscripts = {1};
  std::vector<double> out;
  for (int k = 0; k < count; ++k) {
    Target e = t;
    e.subscripts[0] = t.subscripts[0] + k;
    out.push_back(a.numbers[element_index(r, c, e, a)]);
  }
  return out;
}

void write_output(DeckReader&, const std::string& text) {
  std::cout << text << std::flush;  // the language branch's sink replaces this (stdout or /OUT)
}

ParameterInfo parameter_info(DeckReader& r, const std::string& name_in) {
  const std::string name = to_upper(name_in);
  ParameterInfo info;
  Standin& s = standin(r);
  if (r.params.get(name)) {
    info.type = 0;
  } else if (s.texts.count(name) != 0) {
    info.type = 3;
  } else if (const auto it = s.arrays.find(name); it != s.arrays.end()) {
    info.type = it->second.character ? 4 : 1;
    for (int k = 0; k < 3; ++k) info.dims[k] = it->second.dims[k];
  }
  return info;
}

std::pair<int, int> parameter_counts(DeckReader& r) {
  Standin& s = standin(r);
  const int basic = static_cast<int>(r.params.all().size());
  return {basic + static_cast<int>(s.texts.size() + s.arrays.size()), basic};
}

void standin_vwrite(DeckReader& r, const Command& c, const std::string& format_line) {
  const auto items = parse_format(r, c, format_line);
  Standin& s = standin(r);
  int n = 1;
  bool any_array = false;
  for (int f = 1; f <= c.last_given(); ++f) {
    const Target t = parse_target(r, c, c.text(f));
    if (const auto it = s.arrays.find(t.name); it != s.arrays.end()) {
      const int rows = it->second.dims[0] - (t.subscripts.empty() ? 1 : t.subscripts[0]) + 1;
      n = any_array ? std::min(n, rows) : rows;
      any_array = true;
    }
  }
  std::string out;
  for (int row = 0; row < n; ++row) {
    std::size_t arg = 1;
    std::string line;
    for (const auto& it : items) {
      if (it.kind == 'X') {
        line += std::string(static_cast<std::size_t>(it.w), ' ');
        continue;
      }
      if (it.kind == '\'') {
        line += it.text;
        continue;
      }
      if (it.kind == '/') {
        out += line + "\n";
        line.clear();
        continue;
      }
      const std::string src = c.text(static_cast<int>(arg++));
      Target t = parse_target(r, c, src);
      const auto a = s.arrays.find(t.name);
      if (a != s.arrays.end()) {
        if (t.subscripts.empty()) t.subscripts = {1};
        t.subscripts[0] += row;
      }
      if (it.kind == 'A') {
        std::string text = a != s.arrays.end() ? a->second.texts[element_index(r, c, t, a->second)]
                                               : s.texts[t.name];
        line += fmt::format("{:<{}}", text, std::max<int>(it.w, static_cast<int>(text.size())));
        continue;
      }
      const double v = a != s.arrays.end() ? a->second.numbers[element_index(r, c, t, a->second)]
                                           : read_vector(r, c, src, 1)[0];
      std::string field;
      if (it.kind == 'F')
        field = fmt::format("{:>{}.{}f}", v, it.w, it.d);
      else if (it.kind == 'I')
        field = fmt::format("{:>{}}", std::lround(v), it.w);
      else
        field = fortran_e(v, it.w, it.d);
      if (static_cast<int>(field.size()) > it.w)
        field = std::string(static_cast<std::size_t>(it.w), '*');
      line += field;
    }
    out += line + "\n";
  }
  if (s.cf.is_open())
    s.cf << out << std::flush;
  else
    write_output(r, out);
}

void register_language_standin_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*DIM", cmd_dim, kAnywhere});
  t.push_back({"*VFILL", cmd_vfill, kAnywhere});
  t.push_back({"*VOPER", cmd_voper, kAnywhere});
  t.push_back({"*CFOPEN", cmd_cfopen, kAnywhere});
  t.push_back({"*CFCLOS", cmd_cfclos, kAnywhere});
  t.push_back({"*VWRITE", nullptr, kAnywhere});  // run by the executor with its format line
}

}  // namespace impactfe::deck
