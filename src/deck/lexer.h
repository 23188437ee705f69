#pragma once
/// Lexical layer of the deck reader (APDL_SUBSET §1): splits deck text into raw commands with
/// their source location. Knows nothing about what a command means.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/model.h"
#include "core/text.h"

namespace impactfe::deck {

/// The data lines of a CDB block: a view of the text they were read from and what keeps that
/// text alive (the whole file's text, shared by the file's blocks, or a copy of the lines).
struct BlockText {
  std::shared_ptr<const std::string> owner;
  std::string_view text;
  explicit operator bool() const { return owner != nullptr; }
  std::string_view operator*() const { return text; }
  const std::string_view* operator->() const { return &text; }
};

/// One command as written in the deck: upper-cased name (empty for a 4x repeat line) and the
/// trimmed field texts, case preserved (handlers upper-case labels; file names keep their case).
struct RawCommand {
  std::string name;
  bool repeat = false;        // line started with ',' : re-issue the previous command name
  bool assignment = false;    // `Par = expr` / `A(2,3) = 1,2,3`: fields = {Par, right side}
  bool format_line = false;   // the format line after *VWRITE / *MSG / *MWRITE (`rest` = text)
  bool released = false;      // run, and its text freed (DeckReader::Program::release_before)
  bool star_comment = false;  // text after a blank and '*' dropped as a comment (lex_line)
  std::vector<std::string> fields;
  std::string rest;    // raw text after the first comma (for /TITLE and /COM)
  std::string error;   // a line the lexer refuses (too long): reported when it is reached
  std::string source;  // the physical line as written (*CREATE keeps it for *LIST)
  /// The data lines of a CDB block command (NBLOCK, EBLOCK, CMBLOCK, RLBLOCK): its Fortran
  /// format line(s) and fixed-column records, as written ('\n'-separated), read by its handler in
  /// one pass; the values line of `SFE,...,R5.0` (takes_value_record) alike. `block_line` is the
  /// line number of its first line. Null for other commands.
  BlockText block;
  int block_line = 0;
  /// The file, shared by all the commands of one lexed text (a copy per command was 32 bytes
  /// plus a heap string for a long path, on decks of 10⁵ lines: issue 11).
  std::shared_ptr<const std::string> file;
  int line = 0;
};

/// Longest input line accepted (MAPDL's limit is 640 characters); a longer line is refused
/// with a message instead of being read.
inline constexpr std::size_t kMaxLineLength = 640;

/// Strips blanks, tabs and a trailing '\r'.
std::string trim(std::string_view text);
/// `text` without leading and trailing blanks (space, tab, CR, LF), as a view of it.
std::string_view trim_view(std::string_view text);

/// Fortran free-format real: `30E6`, `.06`, `-2.`, `1.E-4`, `1.0D3`, `+5`. nullopt when `text`
/// (already trimmed) is not a complete number.
std::optional<double> parse_fortran_number(std::string_view text);

/// Lexes one physical line. `$` separates commands only in the modern dialect; `!` starts a
/// comment, and so does a `*` after a blank inside a command (MAPDL: "never include a blank space
/// before the * character because the rest of the input line ... is interpreted as a comment");
/// `C***` lines are comments in both dialects (see docs/deck_reader.md).
std::vector<RawCommand> lex_line(std::string_view text, const std::string& file, int line,
                                 Dialect dialect);

/// Splits on commas outside single quotes and parentheses; each field trimmed.
std::vector<std::string> split_fields(std::string_view text);

/// True for a command whose next physical line is its format line (*VWRITE, *MSG, *MWRITE).
bool takes_format_line(std::string_view upper_name);

/// True for the CDB block commands whose following lines are fixed-column data (takes_block).
bool takes_block(std::string_view upper_name);

/// True for a command of a CDB archive whose values are on the next line, one record of numbers:
/// the surface load `SFE,ELEM,LKEY,Lab,KVAL,R5.0` (its handler reads RawCommand::block).
bool takes_value_record(const RawCommand& cmd);

/// Lexes a whole deck text, line by line (format lines after *VWRITE / *MSG kept verbatim; the
/// data lines after a CDB block command attached to it, see RawCommand::block). When `owner`
/// holds `text`, the blocks are views of it instead of copies (a CDB archive of 10⁶ nodes is
/// read once into memory, not twice).
std::vector<RawCommand> lex_text(std::string_view text, const std::string& file, Dialect dialect,
                                 std::shared_ptr<const std::string> owner = nullptr);

}  // namespace impactfe::deck
