#pragma once
/// The one output stream of a deck session (/OUTPUT, APDL_SCRIPTING §A.14, APDL_MODELING §10.4):
/// the terminal stream the program running the deck supplies, or the file /OUT redirected it to.
/// Every listing a deck asks for (*VWRITE without *CFOPEN, *MSG, *STATUS, *LIST, /COM, and the
/// POST1/POST26 listings PRNSOL, PRVAR, ...) is written through print().
#include <fstream>
#include <ostream>
#include <string>

namespace impactfe::deck {

class OutputSink {
 public:
  /// `terminal` null: printed lines go to the log (Log::info) — a library never writes to the
  /// terminal by itself; `impactfe run` passes std::cout.
  explicit OutputSink(std::ostream* terminal = nullptr) : terminal_(terminal) {}

  /// Writes `text` followed by a newline (text may hold several lines).
  void print(const std::string& text) { write(text + '\n'); }
  /// Writes `text` as it is (the caller supplies the newlines).
  void write(const std::string& text);
  /// /OUT,Fname,Ext,,Loc: following output goes to `path` (overwritten, or appended). Throws
  /// std::runtime_error when the file cannot be opened.
  void redirect(const std::string& path, bool append);
  /// /OUT with no file (or TERM), /CLEAR: back to the terminal stream.
  void to_terminal();
  bool redirected() const { return file_.is_open(); }
  /// The /OUT file ("" when writing to the terminal).
  const std::string& file() const { return path_; }
  /// Number of lines printed so far (all destinations).
  long long n_lines() const { return n_lines_; }

 private:
  std::ostream* terminal_;
  std::ofstream file_;
  std::string path_;
  long long n_lines_ = 0;
};

class DeckReader;
/// Writes `text` as it is (newlines included) to the deck's output: the terminal stream or the
/// /OUT file. The POST1/POST26 listings print through this.
void write_output(DeckReader& r, const std::string& text);

}  // namespace impactfe::deck
