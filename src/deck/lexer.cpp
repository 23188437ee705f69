#include "deck/lexer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace impactfe::deck {

std::string_view trim_view(std::string_view text) {
  std::size_t b = 0;
  std::size_t e = text.size();
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (b < e && blank(text[b])) ++b;
  while (e > b && blank(text[e - 1])) --e;
  return text.substr(b, e - b);
}

std::string trim(std::string_view text) {
  return std::string(trim_view(text));
}

std::optional<double> parse_fortran_number(std::string_view text) {
  // The common form (1.2345E+002, -0.5) read directly; D exponents, a sign-only exponent
  // (1.0-003) and a leading '+' take the general path below.
  if (!text.empty() && text.front() != '+') {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc() && end == text.data() + text.size() && std::isfinite(value) &&
        text.find_first_not_of("0123456789.eE+-") == std::string_view::npos)
      return value;
  }
  std::size_t i = 0;
  const std::size_t n = text.size();
  std::string normal;
  if (i < n && (text[i] == '+' || text[i] == '-')) normal += text[i++];
  int digits = 0;
  while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) {
    normal += text[i++];
    ++digits;
  }
  if (i < n && text[i] == '.') {
    normal += text[i++];
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) {
      normal += text[i++];
      ++digits;
    }
  }
  if (digits == 0) return std::nullopt;
  if (i < n && (text[i] == 'e' || text[i] == 'E' || text[i] == 'd' || text[i] == 'D')) {
    normal += 'E';
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) normal += text[i++];
    int exp_digits = 0;
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) {
      normal += text[i++];
      ++exp_digits;
    }
    if (exp_digits == 0) return std::nullopt;
  }
  if (i != n) return std::nullopt;
  // A lone "-." or "." was excluded by digits == 0; strtod accepts "-2." and ".06".
  return std::strtod(normal.c_str(), nullptr);
}

namespace {

/// Removes a `!` comment that is not inside a single-quoted string.
std::string_view strip_comment(std::string_view text) {
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\'') quoted = !quoted;
    if (text[i] == '!' && !quoted) return text.substr(0, i);
  }
  return text;
}

}  // namespace

std::vector<std::string> split_fields(std::string_view text) {
  std::vector<std::string> out;
  std::string current;
  bool quoted = false;
  int depth = 0;
  for (char c : text) {
    if (c == '\'') quoted = !quoted;
    if (!quoted && c == '(') ++depth;
    if (!quoted && c == ')' && depth > 0) --depth;
    if (c == ',' && !quoted && depth == 0) {
      out.push_back(trim(current));
      current.clear();
    } else {
      current += c;
    }
  }
  out.push_back(trim(current));
  return out;
}

namespace {

bool is_identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

/// Splits on `$` outside quotes (modern dialect only).
std::vector<std::string_view> split_dollar(std::string_view text) {
  std::vector<std::string_view> out;
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\'') quoted = !quoted;
    if (text[i] == '$' && !quoted) {
      out.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  out.push_back(text.substr(start));
  return out;
}

/// Lexes one command (no `$`). Returns false for an empty/comment segment.
/// The position of a `*` that follows a blank outside quotes (a comment in MAPDL, APDL
/// Programmer's Guide §3.7), or npos.
std::size_t star_comment_at(std::string_view text) {
  bool quoted = false;
  for (std::size_t i = 1; i < text.size(); ++i) {
    if (text[i] == '\'') quoted = !quoted;
    if (!quoted && text[i] == '*' && (text[i - 1] == ' ' || text[i - 1] == '\t')) return i;
  }
  return std::string_view::npos;
}

bool lex_segment(std::string_view raw, const std::shared_ptr<const std::string>& file, int line,
                 RawCommand& cmd) {
  std::string text = trim(raw);
  if (text.empty()) return false;
  const std::size_t star = star_comment_at(text);
  if (star != std::string::npos) text = trim(std::string_view(text).substr(0, star));
  cmd = RawCommand{};
  cmd.star_comment = star != std::string::npos;
  cmd.file = file;
  cmd.line = line;
  if (text[0] == ',') {
    cmd.repeat = true;
    cmd.rest = text.substr(1);
    cmd.fields = split_fields(std::string_view(text).substr(1));
    return true;
  }
  const std::size_t comma = text.find(',');
  const std::size_t equal = text.find('=');
  if (equal != std::string::npos && text[0] != '*' && text[0] != '/') {
    // `Par = expr` or `A(i,j) = v1,v2,...`: the left side is a name, optionally subscripted.
    const std::string lhs = trim(std::string_view(text).substr(0, equal));
    const std::size_t paren = lhs.find('(');
    const std::string base = trim(std::string_view(lhs).substr(0, paren));
    const bool subscripted = paren != std::string::npos && lhs.back() == ')';
    if (is_identifier(base) &&
        (paren == std::string::npos ? comma == std::string::npos || equal < comma : subscripted)) {
      cmd.name = "*SET";
      cmd.assignment = true;
      cmd.fields = {lhs, trim(std::string_view(text).substr(equal + 1))};
      return true;
    }
  }
  cmd.name = to_upper(trim(std::string_view(text).substr(0, comma)));
  if (comma != std::string::npos) {
    cmd.rest = trim(std::string_view(text).substr(comma + 1));
    cmd.fields = split_fields(std::string_view(text).substr(comma + 1));
  }
  return true;
}

bool starts_with_upper(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  return to_upper(text.substr(0, prefix.size())) == prefix;
}

std::vector<RawCommand> lex_line_of(std::string_view text,
                                    const std::shared_ptr<const std::string>& file, int line,
                                    Dialect dialect) {
  std::vector<RawCommand> out;
  const std::string stripped = trim(text);
  if (stripped.empty()) return out;
  if (starts_with_upper(stripped, "C***")) return out;  // 4x comment line
  // /TITLE and /COM keep the rest of the line verbatim (commas, case, '$' and '!'). Their name
  // ends at the first character that is no letter or digit: `/COM REF: TEXT, MORE` is a comment
  // as `/COM,REF...` is, and so is `/COM------ RESULTS` (VM264, VMR049-CR2-185).
  if (starts_with_upper(stripped, "/TIT") || starts_with_upper(stripped, "/COM")) {
    RawCommand cmd;
    cmd.file = file;
    cmd.line = line;
    std::size_t end = 1;
    while (end < stripped.size() && std::isalnum(static_cast<unsigned char>(stripped[end]))) ++end;
    if (end == stripped.size()) end = std::string::npos;
    cmd.name = to_upper(trim(std::string_view(stripped).substr(0, end)));
    if (end != std::string::npos) {
      std::string_view rest = std::string_view(stripped).substr(end);
      rest = rest.substr(std::min(rest.find_first_not_of(" \t"), rest.size()));
      if (!rest.empty() && rest.front() == ',') rest.remove_prefix(1);
      cmd.rest = trim(rest);
    }
    cmd.fields = {cmd.rest};
    out.push_back(std::move(cmd));
    return out;
  }
  const std::string_view code = strip_comment(stripped);
  std::vector<std::string_view> segments;
  if (dialect == Dialect::Modern)
    segments = split_dollar(code);
  else
    segments = {code};
  for (std::string_view segment : segments) {
    RawCommand cmd;
    if (lex_segment(segment, file, line, cmd)) out.push_back(std::move(cmd));
  }
  return out;
}

}  // namespace

std::vector<RawCommand> lex_line(std::string_view text, const std::string& file, int line,
                                 Dialect dialect) {
  return lex_line_of(text, std::make_shared<const std::string>(file), line, dialect);
}

bool takes_format_line(std::string_view n) {
  return n.substr(0, 5) == "*VWRI" || n == "*MSG" || n.substr(0, 5) == "*MWRI";
}

bool takes_block(std::string_view n) {
  return n == "NBLOCK" || n == "EBLOCK" || n == "CMBLOCK" || n == "RLBLOCK";
}

bool takes_value_record(const RawCommand& cmd) {
  return cmd.name == "SFE" && cmd.fields.size() >= 5 && to_upper(trim(cmd.fields[4])) == "R5.0";
}

namespace {

/// A record of a CDB block: numbers in fixed columns, no comma, no letter but an exponent.
bool is_block_record(std::string_view line) {
  const std::string_view t = trim_view(line);
  if (t.empty()) return false;
  for (char ch : t)
    if (!(std::isdigit(static_cast<unsigned char>(ch)) || ch == ' ' || ch == '\t' || ch == '.' ||
          ch == '+' || ch == '-' || ch == 'E' || ch == 'e' || ch == 'D' || ch == 'd'))
      return false;
  return true;
}

/// The end marker MAPDL writes after an NBLOCK: `N,R5.3,LOC,-1,` (R5.1 alike).
bool is_nblock_end(std::string_view line) {
  const std::string_view view = trim_view(line);
  if (view.empty() || (view.front() != 'N' && view.front() != 'n')) return false;
  std::string t = to_upper(std::string(view));
  t.erase(std::remove(t.begin(), t.end(), ' '), t.end());
  return t.rfind("N,R5.", 0) == 0 && t.find(",LOC,-1") != std::string::npos;
}

/// Consumes the lines of the block after `text[pos]` (format lines, then records; the NBLOCK
/// end marker too) into `cmd.block`; returns the position after them and advances `line`. A
/// command with one value record (takes_value_record) takes that line only, no format line.
std::size_t take_block(std::string_view text, std::size_t pos, int& line, RawCommand& cmd,
                       const std::shared_ptr<const std::string>& owner) {
  cmd.block_line = line + 1;
  const std::size_t first = pos;
  const bool one_record = takes_value_record(cmd);
  bool formats = !one_record, carriage_returns = false;
  int records = 0;
  while (pos < text.size() && !(one_record && records == 1)) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view physical = text.substr(pos, end - pos);
    if (!physical.empty() && physical.back() == '\r') {
      physical.remove_suffix(1);
      carriage_returns = true;
    }
    const std::string_view t = trim_view(physical);
    const bool format = formats && !t.empty() && t.front() == '(';
    const bool end_marker = cmd.name == "NBLOCK" && is_nblock_end(physical);
    if (!format && !end_marker && !is_block_record(physical)) break;
    formats = format;
    ++line;
    ++records;
    pos = end + 1;
    if (end_marker) break;
  }
  // The block's lines ('\n'-separated): a view of the file's text when it has no CRs and the
  // caller keeps the text, a copy otherwise.
  const std::string_view span = text.substr(first, std::min(pos, text.size()) - first);
  if (!carriage_returns && owner) {
    cmd.block = BlockText{owner, span};
    return pos;
  }
  std::string block;
  block.reserve(span.size());
  for (std::size_t at = 0; at < span.size();) {
    std::size_t end = span.find('\n', at);
    if (end == std::string_view::npos) end = span.size();
    std::string_view physical = span.substr(at, end - at);
    if (!physical.empty() && physical.back() == '\r') physical.remove_suffix(1);
    block.append(physical).push_back('\n');
    at = end + 1;
  }
  auto copy = std::make_shared<const std::string>(std::move(block));
  cmd.block = BlockText{copy, *copy};
  return pos;
}

}  // namespace

std::vector<RawCommand> lex_text(std::string_view text, const std::string& file_name,
                                 Dialect dialect, std::shared_ptr<const std::string> owner) {
  // Views are taken only of text the owner holds.
  if (owner &&
      (text.data() < owner->data() || text.data() + text.size() > owner->data() + owner->size()))
    owner = nullptr;
  const auto file = std::make_shared<const std::string>(file_name);
  std::vector<RawCommand> out;
  int line = 0;
  std::size_t pos = 0;
  bool format_next = false;  // the previous line ended with *VWRITE / *MSG (or a '&' format line)
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++line;
    std::string_view physical = text.substr(pos, end - pos);
    if (!physical.empty() && physical.back() == '\r') physical.remove_suffix(1);
    if (trim(physical).size() > kMaxLineLength) {
      RawCommand bad;
      bad.file = file;
      bad.line = line;
      const std::string head = trim(physical.substr(0, std::min<std::size_t>(physical.size(), 40)));
      const std::size_t comma = head.find(',');
      bad.name =
          comma != std::string::npos && comma > 0 ? to_upper(head.substr(0, comma)) : "(line)";
      bad.error = fmt::format("line of {} characters refused (at most {} per line)",
                              physical.size(), kMaxLineLength);
      out.push_back(std::move(bad));
      format_next = false;
    } else if (format_next) {
      RawCommand f;
      f.format_line = true;
      f.file = file;
      f.line = line;
      f.rest = std::string(physical);
      f.source = f.rest;
      const std::string t = trim(physical);
      // A C-style format continues on the next line when it ends with '&' (*MSG, §A.14).
      format_next = !t.empty() && t[0] != '(' && t.back() == '&';
      if (format_next) f.rest = t.substr(0, t.size() - 1);
      out.push_back(std::move(f));
    } else {
      auto cmds = lex_line_of(physical, file, line, dialect);
      format_next = !cmds.empty() && takes_format_line(cmds.back().name);
      const bool block =
          !cmds.empty() && (takes_block(cmds.back().name) || takes_value_record(cmds.back()));
      for (auto& c : cmds) {
        c.source = std::string(physical);
        out.push_back(std::move(c));
      }
      if (block && end < text.size()) {
        pos = take_block(text, end + 1, line, out.back(), owner);
        if (pos >= text.size()) break;
        continue;
      }
    }
    if (end == text.size()) break;
    pos = end + 1;
    if (pos == text.size()) break;  // the newline ending the last line opens no further line
  }
  out.shrink_to_fit();  // kept for the whole run: up to half its size spare (issue 11)
  return out;
}

}  // namespace impactfe::deck
