#pragma once
/// Lexical layer of the deck reader (APDL_SUBSET §1): splits deck text into raw commands with
/// their source location. Knows nothing about what a command means.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/model.h"
#include "core/text.h"

namespace impactfe::deck {

/// One command as written in the deck: upper-cased name (empty for a 4x repeat line) and the
/// trimmed field texts, case preserved (handlers upper-case labels; file names keep their case).
struct RawCommand {
  std::string name;
  bool repeat = false;      // line started with ',' : re-issue the previous command name
  bool assignment = false;  // modern `Par = expr`: fields = {Par, expr}
  std::vector<std::string> fields;
  std::string rest;  // raw text after the first comma (for /TITLE and /COM)
  std::string file;
  int line = 0;
};

/// Strips blanks, tabs and a trailing '\r'.
std::string trim(std::string_view text);

/// Fortran free-format real: `30E6`, `.06`, `-2.`, `1.E-4`, `1.0D3`, `+5`. nullopt when `text`
/// (already trimmed) is not a complete number.
std::optional<double> parse_fortran_number(std::string_view text);

/// Lexes one physical line. `$` separates commands only in the modern dialect; `!` starts a
/// comment and `C***` lines are comments in both dialects (see docs/deck_reader.md).
std::vector<RawCommand> lex_line(std::string_view text, const std::string& file, int line,
                                 Dialect dialect);

/// Lexes a whole deck text, line by line.
std::vector<RawCommand> lex_text(std::string_view text, const std::string& file, Dialect dialect);

}  // namespace impactfe::deck
