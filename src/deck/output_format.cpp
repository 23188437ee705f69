// Fortran and C-style format lines of *VWRITE / *MSG (APDL_SCRIPTING §A.9). The Fortran edit
// descriptors follow the Fortran 2008 standard, §10.7 (F, E, D, ES, G, I, A) and §10.8 (X, T,
// /, :, P).
#include "deck/output_format.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace impactfe::deck {

namespace {

constexpr std::size_t kMaxEdits = 10000;

std::string stars(int w) {
  return std::string(static_cast<std::size_t>(std::max(w, 1)), '*');
}

std::string pad_left(const std::string& s, int w) {
  if (w <= 0 || static_cast<int>(s.size()) >= w) return s;
  return std::string(static_cast<std::size_t>(w) - s.size(), ' ') + s;
}

/// Fits `s` into w columns: a leading "0." loses its optional zero if needed; asterisks when it
/// still does not fit (Fortran rule).
std::string fit(std::string s, int w) {
  if (w <= 0) return s;
  if (static_cast<int>(s.size()) > w) {
    if (s.rfind("0.", 0) == 0)
      s.erase(0, 1);
    else if (s.rfind("-0.", 0) == 0)
      s.erase(1, 1);
  }
  if (static_cast<int>(s.size()) > w) return stars(w);
  return pad_left(s, w);
}

/// Significant digits of |x| rounded to `sig` digits and the decimal exponent p with
/// |x| ≈ d.ddd × 10^p.
void significant_digits(double ax, int sig, std::string& digits, int& p) {
  if (ax == 0.0) {
    digits.assign(static_cast<std::size_t>(sig), '0');
    p = -1;
    return;
  }
  // fmt sizes the text to the digits asked for: a format may ask for up to 9999 decimals
  // (E18.68 overflowed a fixed 64-byte buffer; the fuzzer found it).
  const std::string s = fmt::format("{:.{}e}", ax, sig - 1);
  const std::size_t e = s.find('e');
  digits.clear();
  for (std::size_t i = 0; i < e; ++i)
    if (s[i] != '.') digits += s[i];
  p = std::atoi(s.c_str() + e + 1);
}

std::string exponent_text(int x, int e, char letter) {
  const int ax = std::abs(x);
  const char sign = x < 0 ? '-' : '+';
  if (e > 0) {
    const std::string d = fmt::format("{:0{}d}", ax, e);
    if (static_cast<int>(d.size()) > e) return {};
    return std::string(1, letter) + sign + d;
  }
  if (ax <= 99) return fmt::format("{}{}{:02d}", letter, sign, ax);
  if (ax <= 999) return fmt::format("{}{:03d}", sign, ax);
  return {};
}

}  // namespace

std::string fortran_f(double x, int w, int d, int scale) {
  if (!std::isfinite(x)) return stars(w);
  const double v = x * std::pow(10.0, scale);
  std::string s = fmt::format("{:.{}f}", v, std::max(d, 0));
  if (d <= 0) s += '.';
  return fit(s, w);
}

std::string fortran_e(double x, int w, int d, int e, int scale, char letter) {
  if (!std::isfinite(x) || d < 0) return stars(w);
  const int k = scale;
  if (k <= -d || k >= d + 2) return stars(w);
  const int sig = k <= 0 ? d + k : d + 1;
  std::string digits;
  int p = 0;
  significant_digits(std::fabs(x), std::max(sig, 1), digits, p);
  std::string mantissa;
  if (k <= 0) {
    mantissa =
        "0." + std::string(static_cast<std::size_t>(-k), '0') + digits.substr(0, std::max(sig, 0));
  } else {
    mantissa = digits.substr(0, static_cast<std::size_t>(k)) + "." +
               digits.substr(static_cast<std::size_t>(k));
  }
  const int exponent = x == 0.0 ? 0 : p + 1 - k;
  const std::string ex = exponent_text(exponent, e, letter);
  if (ex.empty()) return stars(w);
  return fit((std::signbit(x) && x != 0.0 ? "-" : "") + mantissa + ex, w);
}

std::string fortran_es(double x, int w, int d, int e) {
  if (!std::isfinite(x) || d < 0) return stars(w);
  std::string digits;
  int p = 0;
  significant_digits(std::fabs(x), d + 1, digits, p);
  const int exponent = x == 0.0 ? 0 : p;
  const std::string ex = exponent_text(exponent, e, 'E');
  if (ex.empty()) return stars(w);
  return fit((x < 0.0 ? "-" : "") + digits.substr(0, 1) + "." + digits.substr(1) + ex, w);
}

std::string fortran_g(double x, int w, int d, int e, int scale) {
  if (!std::isfinite(x)) return stars(w);
  const int n = e > 0 ? e + 2 : 4;  // trailing blanks of the F form
  if (x == 0.0)
    return fortran_f(0.0, w - n, std::max(d - 1, 0)) +
           std::string(static_cast<std::size_t>(n), ' ');
  const double ax = std::fabs(x);
  if (ax < 0.1 - 0.5 * std::pow(10.0, -d - 1) || ax >= std::pow(10.0, d) - 0.5)
    return fortran_e(x, w, d, e, scale, 'E');
  std::string digits;
  int p = 0;
  significant_digits(ax, std::max(d, 1), digits, p);
  const int s = p + 1;  // 10^(s-1) <= N < 10^s
  return fortran_f(x, w - n, d - s) + std::string(static_cast<std::size_t>(n), ' ');
}

std::string fortran_i(double x, int w, int m) {
  if (!std::isfinite(x) || std::fabs(x) > 9.0e18) return stars(w);
  const long long v = std::llround(x);
  std::string digits = v == 0 && m == 0 ? std::string() : std::to_string(v < 0 ? -v : v);
  if (m > 0 && static_cast<int>(digits.size()) < m)
    digits.insert(0, static_cast<std::size_t>(m) - digits.size(), '0');
  const std::string s = (v < 0 ? "-" : "") + digits;
  if (w > 0 && static_cast<int>(s.size()) > w) return stars(w);
  return pad_left(s, w);
}

std::string fortran_a(const std::string& text, int w) {
  if (w < 0) return text;
  if (static_cast<int>(text.size()) >= w) return text.substr(0, static_cast<std::size_t>(w));
  return pad_left(text, w);
}

// ---- parsing ---------------------------------------------------------------------------------

namespace {

class FortranParser {
 public:
  explicit FortranParser(const std::string& s) : s_(s) {}

  void parse(std::vector<OutputFormat::Edit>& out, std::size_t& revert_at) {
    skip();
    if (!take('(')) throw FormatError("a Fortran format starts with '('");
    list(out, 0, revert_at);
    skip();
    if (i_ != s_.size())
      throw FormatError(fmt::format("text after the closing ')': '{}'", s_.substr(i_)));
  }

 private:
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }
  bool take(char c) {
    skip();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  int number() {
    skip();
    int v = 0;
    std::size_t n = 0;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) {
      v = v * 10 + (s_[i_++] - '0');
      if (++n > 6) throw FormatError("number too large in the format");
    }
    return n == 0 ? -1 : v;
  }
  char upper() {
    return i_ < s_.size() ? static_cast<char>(std::toupper(static_cast<unsigned char>(s_[i_])))
                          : '\0';
  }
  void append(std::vector<OutputFormat::Edit>& out, const OutputFormat::Edit& e, int times) {
    for (int t = 0; t < times; ++t) {
      if (out.size() >= kMaxEdits) throw FormatError("format expands to too many descriptors");
      out.push_back(e);
    }
  }
  /// Items up to the matching ')'. At depth 0 `revert_at` becomes the start of the last group.
  void list(std::vector<OutputFormat::Edit>& out, int depth, std::size_t& revert_at) {
    using Edit = OutputFormat::Edit;
    for (;;) {
      skip();
      if (i_ >= s_.size()) throw FormatError("missing ')' at the end of the format");
      const char c = s_[i_];
      if (c == ')') {
        ++i_;
        return;
      }
      if (c == ',') {
        ++i_;
        continue;
      }
      if (c == '\'' || c == '"') {
        Edit e;
        e.kind = Edit::Text;
        e.text = quoted(c);
        append(out, e, 1);
        continue;
      }
      if (c == '/' || c == ':') {
        ++i_;
        Edit e;
        e.kind = c == '/' ? Edit::Slash : Edit::Colon;
        append(out, e, 1);
        continue;
      }
      bool negative = false;
      if (c == '-' || c == '+') {
        negative = c == '-';
        ++i_;
      }
      const int count = number();
      skip();
      const char d = upper();
      if (d == 'P') {
        ++i_;
        if (count < 0) throw FormatError("P needs a scale factor, e.g. 1P");
        Edit e;
        e.kind = Edit::Scale;
        e.n = negative ? -count : count;
        append(out, e, 1);
        continue;
      }
      if (negative) throw FormatError("a sign is only allowed before P");
      const int times = count < 0 ? 1 : count;
      if (count == 0) throw FormatError("repeat count 0");
      if (d == '(') {
        ++i_;
        const std::size_t start = out.size();
        std::vector<Edit> group;
        std::size_t unused = 0;
        list(group, depth + 1, unused);
        if (depth == 0) revert_at = start;
        for (int t = 0; t < times; ++t)
          for (const auto& e : group) append(out, e, 1);
        continue;
      }
      if (d == '/') {
        ++i_;
        Edit e;
        e.kind = Edit::Slash;
        append(out, e, times);
        continue;
      }
      if (d == 'X') {
        ++i_;
        Edit e;
        e.kind = Edit::Skip;
        e.n = times;
        append(out, e, 1);
        continue;
      }
      if (d == 'H') {
        ++i_;
        if (count < 1 || i_ + static_cast<std::size_t>(count) > s_.size())
          throw FormatError("bad Hollerith text nH...");
        Edit e;
        e.kind = Edit::Text;
        e.text = s_.substr(i_, static_cast<std::size_t>(count));
        i_ += static_cast<std::size_t>(count);
        append(out, e, 1);
        continue;
      }
      if (d == 'T') {
        ++i_;
        Edit e;
        e.kind = Edit::Tab;
        if (upper() == 'L' || upper() == 'R') {
          e.kind = upper() == 'L' ? Edit::TabLeft : Edit::TabRight;
          ++i_;
        }
        e.n = number();
        if (e.n < 0) throw FormatError("T, TL and TR need a column count");
        append(out, e, 1);
        continue;
      }
      if (d == 'F' || d == 'E' || d == 'D' || d == 'G' || d == 'I' || d == 'A') {
        ++i_;
        Edit e;
        e.kind = Edit::Data;
        e.code = d;
        if (d == 'E' && upper() == 'S') {
          e.code = 'S';
          ++i_;
        } else if (d == 'E' && upper() == 'N') {
          throw FormatError("EN (engineering notation) is not supported");
        }
        e.width = number();
        if (take('.')) e.digits = number();
        if ((e.code == 'E' || e.code == 'S' || e.code == 'G' || e.code == 'D') && upper() == 'E') {
          ++i_;
          e.exponent = number();
        }
        if (d != 'A' && e.width < 0)
          throw FormatError(fmt::format("{} needs a width, e.g. {}12.5", d, d));
        if ((d == 'F' || d == 'E' || d == 'D' || d == 'G') && e.digits < 0)
          throw FormatError(
              fmt::format("{}{} needs decimals, e.g. {}{}.4", d, e.width, d, e.width));
        append(out, e, times);
        continue;
      }
      if (std::isalpha(static_cast<unsigned char>(c)) || count >= 0)
        throw FormatError(fmt::format("edit descriptor '{}' is not supported", s_.substr(i_, 6)));
      throw FormatError(fmt::format("unexpected '{}' in the format", c));
    }
  }
  std::string quoted(char q) {
    ++i_;
    std::string t;
    while (i_ < s_.size()) {
      if (s_[i_] == q) {
        if (i_ + 1 < s_.size() && s_[i_ + 1] == q) {
          t += q;
          i_ += 2;
          continue;
        }
        ++i_;
        return t;
      }
      t += s_[i_++];
    }
    throw FormatError("unterminated quoted text in the format");
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

void parse_c_style(const std::string& s, std::vector<OutputFormat::Edit>& out) {
  using Edit = OutputFormat::Edit;
  std::string text;
  auto flush = [&] {
    if (!text.empty()) {
      Edit e;
      e.kind = Edit::Text;
      e.text = text;
      out.push_back(e);
      text.clear();
    }
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      text += s[i];
      continue;
    }
    if (i + 1 < s.size() && s[i + 1] == '%') {
      text += '%';
      ++i;
      continue;
    }
    if (i + 1 < s.size() && s[i + 1] == '/') {
      flush();
      Edit e;
      e.kind = Edit::Slash;
      out.push_back(e);
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    Edit e;
    e.kind = Edit::Data;
    while (j < s.size() && std::string("-+ #0").find(s[j]) != std::string::npos) e.text += s[j++];
    auto digits = [&](int& v) {
      const std::size_t start = j;
      v = 0;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) {
        v = v * 10 + (s[j++] - '0');
        if (j - start > 4) throw FormatError("width too large in the format");
      }
      if (j == start) v = -1;
    };
    digits(e.width);
    if (j < s.size() && s[j] == '.') {
      ++j;
      digits(e.digits);
      if (e.digits < 0) e.digits = 0;
    }
    if (j >= s.size()) throw FormatError("format ends inside a % conversion");
    const char conv = s[j];
    const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(conv)));
    if (u == 'I' || u == 'D')
      e.code = 'i';
    else if (u == 'F' || u == 'E' || u == 'G')
      e.code = conv;  // case kept: %G writes 1.5E-06, %g 1.5e-06
    else if (u == 'C' || u == 'S')
      e.code = 'c';
    else
      throw FormatError(
          fmt::format("conversion %{} is not supported (%I %F %E %G %C %/ %%)", conv));
    flush();
    out.push_back(e);
    i = j;
  }
  flush();
}

std::string c_number(const OutputFormat::Edit& e, double x) {
  std::string spec = "%" + e.text;
  if (e.width >= 0) spec += std::to_string(e.width);
  // Widths and precisions go up to 9999: the text is sized by a first snprintf, never cut.
  const auto print = [](const std::string& format, auto value) {
    const int n = std::snprintf(nullptr, 0, format.c_str(), value);
    std::string text(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
    std::snprintf(text.data(), text.size(), format.c_str(), value);
    text.pop_back();
    return text;
  };
  if (e.code == 'i')
    return print(spec + "lld", std::isfinite(x) && std::fabs(x) < 9e18 ? std::llround(x) : 0LL);
  if (e.digits >= 0) spec += "." + std::to_string(e.digits);
  spec += e.code;
  return print(spec, x);
}

std::string c_text(const OutputFormat::Edit& e, const std::string& t) {
  std::string s = e.digits >= 0 ? t.substr(0, static_cast<std::size_t>(e.digits)) : t;
  const bool left = e.text.find('-') != std::string::npos;
  if (e.width > static_cast<int>(s.size())) {
    const std::string blanks(static_cast<std::size_t>(e.width) - s.size(), ' ');
    s = left ? s + blanks : blanks + s;
  }
  return s;
}

}  // namespace

OutputFormat OutputFormat::parse(const std::string& line) {
  OutputFormat f;
  std::size_t b = 0;
  while (b < line.size() && (line[b] == ' ' || line[b] == '\t')) ++b;
  if (b < line.size() && line[b] == '(') {
    std::string t = line;
    while (!t.empty() && (t.back() == ' ' || t.back() == '\t' || t.back() == '\r')) t.pop_back();
    FortranParser(t).parse(f.edits_, f.revert_at_);
  } else {
    f.fortran_ = false;
    parse_c_style(line, f.edits_);
  }
  return f;
}

int OutputFormat::n_data() const {
  int n = 0;
  for (const auto& e : edits_) n += e.kind == Edit::Data ? 1 : 0;
  return n;
}

std::string OutputFormat::data_field(const Edit& e, const Value& v, int scale,
                                     std::vector<std::string>* warnings) const {
  auto warn = [&](const std::string& w) {
    if (warnings != nullptr) warnings->push_back(w);
  };
  const int blank_width = e.width >= 0 ? e.width : 8;
  const std::string blanks(static_cast<std::size_t>(std::max(e.width, 0)), ' ');
  if (!fortran_) {
    if (e.code == 'c') {
      if (is_text(v)) return c_text(e, std::get<std::string>(v));
      warn(fmt::format("number {} under %C written as blanks", format_number(std::get<double>(v))));
      return blanks;
    }
    if (is_text(v)) {
      warn(fmt::format("text '{}' under a numeric conversion written as blanks",
                       std::get<std::string>(v)));
      return blanks;
    }
    return c_number(e, std::get<double>(v));
  }
  if (e.code == 'A') {
    if (is_text(v))  // MAPDL's Fortran A fields hold at most 8 characters (§A.9).
      return fortran_a(std::get<std::string>(v).substr(0, 8), e.width);
    warn(fmt::format("number {} under A written as blanks", format_number(std::get<double>(v))));
    return std::string(static_cast<std::size_t>(blank_width), ' ');
  }
  if (is_text(v)) {
    warn(fmt::format("text '{}' under {} written as blanks", std::get<std::string>(v), e.code));
    return blanks;
  }
  const double x = std::get<double>(v);
  switch (e.code) {
    case 'F':
      return fortran_f(x, e.width, e.digits, scale);
    case 'E':
    case 'D':
      return fortran_e(x, e.width, e.digits, e.exponent, scale, e.code);
    case 'S':
      return fortran_es(x, e.width, e.digits, e.exponent);
    case 'G':
      return fortran_g(x, e.width, e.digits, e.exponent, scale);
    case 'I':
      return fortran_i(x, e.width, e.digits);
    default:
      return {};
  }
}

std::vector<std::string> OutputFormat::format(const std::vector<Value>& items,
                                              std::vector<std::string>* warnings) const {
  std::vector<std::string> lines(1);
  std::size_t k = 0;
  std::size_t pos = 0;
  int scale = 0;
  bool data_since_revert = false;
  for (;;) {
    if (pos == edits_.size()) {
      if (k == items.size() || !fortran_) break;
      if (!data_since_revert) break;  // no data descriptor: nothing more can be written
      lines.emplace_back();
      pos = revert_at_;
      data_since_revert = false;
      continue;
    }
    const Edit& e = edits_[pos++];
    std::string& line = lines.back();
    switch (e.kind) {
      case Edit::Text:
        line += e.text;
        break;
      case Edit::Skip:
        line.append(static_cast<std::size_t>(e.n), ' ');
        break;
      case Edit::Slash:
        lines.emplace_back();
        break;
      case Edit::Tab:
        line.resize(static_cast<std::size_t>(std::max(e.n - 1, 0)), ' ');
        break;
      case Edit::TabLeft:
        line.resize(line.size() > static_cast<std::size_t>(e.n) ? line.size() - e.n : 0);
        break;
      case Edit::TabRight:
        line.append(static_cast<std::size_t>(e.n), ' ');
        break;
      case Edit::Scale:
        scale = e.n;
        break;
      case Edit::Colon:
        if (k == items.size()) return lines;
        break;
      case Edit::Data:
        if (k == items.size()) return lines;
        data_since_revert = true;
        line += data_field(e, items[k++], scale, warnings);
        break;
    }
  }
  return lines;
}

}  // namespace impactfe::deck
