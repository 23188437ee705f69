// Fortran edit descriptors of the CDB blocks (cdb_format.h).
#include "deck/cdb_format.h"

#include <cctype>
#include <stdexcept>
#include <string>

namespace impactfe::deck {

namespace {

constexpr std::size_t kMaxColumns = 1000;

int read_int(std::string_view s, std::size_t& i) {
  int v = 0;
  bool any = false;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
    v = v * 10 + (s[i++] - '0');
    if (v > 100000) throw std::invalid_argument("format: a number is too large");
    any = true;
  }
  return any ? v : -1;
}

}  // namespace

std::vector<FortranField> parse_fortran_format(std::string_view format) {
  const std::string f(format);
  const std::size_t open = f.find('('), close = f.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open)
    throw std::invalid_argument("format line '" + f + "' is not in parentheses");
  std::vector<FortranField> out;
  std::string_view s = std::string_view(f).substr(open + 1, close - open - 1);
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == ',')) ++i;
    if (i == s.size()) break;
    FortranField d;
    const int count = read_int(s, i);
    d.count = count < 0 ? 1 : count;
    if (i == s.size()) throw std::invalid_argument("format line '" + f + "': descriptor missing");
    const char k = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i++])));
    if (k == 'X') {  // nX: n blanks
      d.kind = 'X';
      d.width = d.count;
      d.count = 1;
    } else if (k == 'I' || k == 'E' || k == 'G' || k == 'F' || k == 'D' || k == 'A') {
      d.kind = k;
      d.width = read_int(s, i);
      if (d.width <= 0) throw std::invalid_argument("format line '" + f + "': width missing");
      // .d and an exponent width (e21.13e3) do not change the column.
      if (i < s.size() && s[i] == '.') {
        ++i;
        read_int(s, i);
      }
      if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        read_int(s, i);
      }
    } else {
      throw std::invalid_argument("format line '" + f + "': descriptor '" + std::string(1, k) +
                                  "' not supported (I, E, G, F, D, A, X)");
    }
    out.push_back(d);
  }
  if (out.empty()) throw std::invalid_argument("format line '" + f + "' has no descriptor");
  return out;
}

std::vector<int> field_widths(const std::vector<FortranField>& fields) {
  std::vector<int> widths;
  for (const auto& d : fields)
    for (int k = 0; k < d.count; ++k) {
      // A record of MAPDL's blocks has at most 19 columns; far more is not a block format.
      if (widths.size() == kMaxColumns)
        throw std::invalid_argument("format line with more than 1000 columns");
      widths.push_back(d.width);
    }
  return widths;
}

}  // namespace impactfe::deck
