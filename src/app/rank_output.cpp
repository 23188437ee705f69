#include "app/rank_output.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "core/files.h"
#include "linalg/parallel_backend.h"

namespace fs = std::filesystem;

namespace impactfe {

namespace {

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out)
    throw std::runtime_error(fmt::format("rank {}: cannot write '{}' in its scratch directory",
                                         process_rank(), path.string()));
}

}  // namespace

RankOutput::RankOutput(RankPaths paths) {
  const bool root = process_rank() == 0;
  // Rank 0's view of the paths (its working directory may be the only one that resolves them).
  std::string deck = root ? fs::absolute(paths.deck).string() : std::string();
  std::string out = root ? fs::absolute(paths.out_dir).string() : std::string();
  broadcast_from_rank0(deck);
  broadcast_from_rank0(out);
  paths.deck = deck;
  // A relative --se names a file of the output directory, --results one of the start directory.
  std::string se = paths.superelement;
  if (root && !se.empty() && fs::path(se).is_relative()) se = (fs::path(out) / se).string();
  std::string results = paths.results;
  if (root && !results.empty()) results = fs::absolute(results).string();
  if (!root) {
    std::string pattern =
        (fs::temp_directory_path() / fmt::format("impactfe-rank{}-XXXXXX", process_rank()))
            .string();
    if (!mkdtemp(pattern.data()))
      throw std::runtime_error(
          fmt::format("rank {}: cannot create a scratch directory", process_rank()));
    scratch_ = pattern;
    paths.out_dir = scratch_.string();
  }
  // Rank 0's input files, in the same order on every rank.
  if (!paths.superelement.empty())
    paths.superelement = share_file(se, "se-input-" + fs::path(se).filename().string());
  if (!paths.results.empty())
    paths.results = share_file(results, "results-input-" + fs::path(results).filename().string());
  // What a deck may read from its working directory: superelement files of an earlier
  // generation pass (*.sub.h5) and results files (restart, POST1/POST26 of an earlier run).
  std::string names;
  if (root) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(out, ec))
      if (entry.is_regular_file() && entry.path().extension() == ".h5")
        names += entry.path().filename().string() + "\n";
  }
  broadcast_from_rank0(names);
  std::istringstream list(names);
  for (std::string name; std::getline(list, name);)
    share_file((fs::path(out) / name).string(), name);
  // The deck, /INPUT and macro files, *LIST and RESUME: rank 0 reads them (core/files.h).
  share_rank0_files(true);
  if (root) return;
  saved_stderr_ = dup(fileno(stderr));
  if (!std::freopen("/dev/null", "w", stdout) ||
      !std::freopen((scratch_ / "terminal.txt").c_str(), "w", stderr))
    throw std::runtime_error("cannot set aside the terminal output of a rank other than 0");
}

std::string RankOutput::share_file(const std::string& path, const std::string& name) {
  const bool root = process_rank() == 0;
  std::string bytes;
  std::string found = "0";
  std::optional<std::string> text;
  if (root && (text = local_read_file(path))) found = "1";
  broadcast_from_rank0(found);
  if (found != "1") return root ? path : (scratch_ / name).string();  // fails alike on all ranks
  if (root) bytes = std::move(*text);
  broadcast_from_rank0(bytes);
  if (root) return path;
  write_bytes(scratch_ / name, bytes);
  return (scratch_ / name).string();
}

void RankOutput::report_failure_alone(int status) const {
  const std::string note =
      fmt::format("impactfe: rank {} of {} failed alone (exit status {}); stopping every rank\n",
                  process_rank(), process_count(), status);
  if (saved_stderr_ < 0) {
    std::cerr << note;
    return;
  }
  // The failing rank's own error message, from its set-aside terminal output: from the first
  // error line on (the warnings before it are rank 0's too, already shown).
  std::fflush(stderr);
  std::ifstream in(scratch_ / "terminal.txt");
  std::string text, line;
  bool error = false;
  while (std::getline(in, line)) {
    if (line.rfind("error: ", 0) == 0) error = true;
    if (error) text += line + "\n";
  }
  text += note;
  if (write(saved_stderr_, text.data(), text.size()) < 0) return;
  // The abort ends this process without destructors: the scratch directory goes now.
  std::error_code ec;
  fs::current_path(scratch_.parent_path(), ec);
  fs::remove_all(scratch_, ec);
}

RankOutput::~RankOutput() {
  share_rank0_files(false);
  if (saved_stderr_ >= 0) close(saved_stderr_);
  if (scratch_.empty()) return;
  std::error_code ec;
  fs::current_path(scratch_.parent_path(), ec);
  fs::remove_all(scratch_, ec);
}

}  // namespace impactfe
