#pragma once
/// Under `--solver mumps` every rank runs the deck (SPMD, docs/scaling.md); RankOutput is the one
/// place that decides which process reads inputs and writes output. Rank 0 reads the deck and
/// the files it names and writes results, log and terminal output as a one-process run does.
/// Every other rank runs in a private scratch directory, removed at the end, with its terminal
/// output kept aside (shown only if that rank fails alone), and sees no input file of its own:
/// the deck text, /INPUT and macro files (core/files.h hooks), the --se and --results files and
/// the output directory's HDF5 files (superelements and results of an earlier run) come from
/// rank 0 by broadcast, so a deck on a disk only rank 0 sees runs.
#include <filesystem>
#include <string>

namespace impactfe {

/// The run arguments RankOutput rewrites (paths of rank 0's disk → local copies).
struct RankPaths {
  std::string& deck;
  std::string& out_dir;
  std::string& superelement;  // --se ("" if not given)
  std::string& results;       // --results ("" if not given)
};

class RankOutput {
 public:
  /// Collective: every rank constructs one, at the same point, after start_parallel_backend.
  explicit RankOutput(RankPaths paths);
  ~RankOutput();
  RankOutput(const RankOutput&) = delete;
  RankOutput& operator=(const RankOutput&) = delete;

  /// This rank failed alone (the others never reached the exit agreement): prints its error
  /// message, once, on the real terminal (rank 0 has printed it already) before the abort.
  void report_failure_alone(int status) const;

 private:
  /// Rank 0's file `path` (bytes broadcast) written into the scratch directory as `name` on the
  /// other ranks; returns the path to use on this rank ("" stays "").
  std::string share_file(const std::string& path, const std::string& name);

  std::filesystem::path scratch_;
  int saved_stderr_ = -1;  // the terminal's stderr, on ranks other than 0
};

}  // namespace impactfe
