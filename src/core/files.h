#pragma once
/// File-name lookups that never throw: file names come from decks. The deck-level reads (the
/// deck, /INPUT and macro files, *LIST, RESUME, superelement look-ups) go through file_exists
/// and read_file, which a distributed run (docs/scaling.md) points at rank 0's disk.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

namespace impactfe {

/// Whether `path` names a regular file (`exists_only`: anything), false when the name cannot be
/// looked up at all (longer than the system allows, a component that is not a directory):
/// std::filesystem's throwing overloads would escape as a library message without FILE:LINE
/// (a fuzzing finding, issue 12: `*AAAA...` with a 300-character name looked for AAAA....mac).
bool file_exists(const std::string& path, bool exists_only = false);

/// Bounds of a read (docs/deck_reader.md, "Bounds"): at most `max_bytes` bytes in all and, when
/// `max_line` > 0, at most `max_line` bytes on any line (a file of NUL bytes such as /dev/zero
/// has no line end: it is refused after max_line bytes, not read until memory runs out).
struct ReadLimits {
  std::size_t max_bytes = static_cast<std::size_t>(-1);
  std::size_t max_line = 0;
  /// A deck, an /INPUT file or a macro file: 1 GiB, lines of 1 MiB.
  static ReadLimits text() { return {std::size_t{1} << 30, std::size_t{1} << 20}; }
  /// A file read whole but not as lines (a RESUME database, a *LIST): 1 GiB.
  static ReadLimits bytes() { return {std::size_t{1} << 30, 0}; }
};

/// A file refused by read_file for its size: `line` (1-based) is the line longer than the limit,
/// 0 when the file as a whole is larger than its limit.
class OversizedFileError : public std::runtime_error {
 public:
  OversizedFileError(const std::string& path, int line, std::size_t limit);
  int line() const { return line_; }
  std::size_t limit() const { return limit_; }

 private:
  int line_;
  std::size_t limit_;
};

/// The bytes of the file `path`; nullopt when it cannot be opened or is a directory; throws
/// OversizedFileError beyond `limits`.
std::optional<std::string> read_file(const std::string& path, const ReadLimits& limits = {});

/// Why `name` cannot be a jobname ("" when it can): a jobname names files in the output
/// directory (<jobname>.h5, .log, .lock, .rst.h5, <Sename>.sub.h5), so it may hold no path
/// separator ('/' or '\\'), no NUL and not be empty, "." or "..". Such names are refused, not
/// rewritten: -o chooses the directory.
/// `what` names the field in the message ("jobname", "Sename").
std::string jobname_problem(const std::string& name, const std::string& what = "jobname");

/// The same on this process's own disk, whatever the hooks.
bool local_file_exists(const std::string& path, bool exists_only = false);
std::optional<std::string> local_read_file(const std::string& path, const ReadLimits& limits = {});

/// Replaces the two lookups above (nullptr: this process's disk again). Set once at start-up by
/// the distributed run (linalg/parallel_backend.h, share_rank0_files), before any deck is read.
using FileExistsHook = bool (*)(const std::string& path, bool exists_only);
using ReadFileHook = std::optional<std::string> (*)(const std::string& path,
                                                    const ReadLimits& limits);
void set_file_hooks(FileExistsHook exists, ReadFileHook read);

}  // namespace impactfe
