#pragma once
/// Test support: runs a deck through the same path as `impactfe run` (read_deck + run_job) in
/// a fresh directory and opens the results file.
#include <filesystem>
#include <memory>
#include <string>

#include "analysis/job_runner.h"
#include "deck/deck_reader.h"
#include "results/results_file.h"

namespace impactfe::testing {

struct DeckRun {
  std::filesystem::path directory;
  std::string results_path;
  RunStatistics statistics;
  std::unique_ptr<ResultsReader> reader;
};

/// Runs `deck` (absolute path) with jobname = deck stem in <tmp>/impactfe_tests/<tag>.
inline DeckRun run_deck(const std::string& deck, const std::string& tag,
                        const RunSettings& settings = {}) {
  namespace fs = std::filesystem;
  DeckRun run;
  run.directory = fs::temp_directory_path() / "impactfe_tests" / tag;
  fs::remove_all(run.directory);
  fs::create_directories(run.directory);
  const fs::path previous = fs::current_path();
  fs::current_path(run.directory);
  const std::string jobname = fs::path(deck).stem().string();
  {
    const Job job = read_deck(deck);
    ResultsWriter writer(jobname + ".h5", job.model);
    run_job(job, jobname, settings, writer, run.statistics);
  }
  fs::current_path(previous);
  run.results_path = (run.directory / (jobname + ".h5")).string();
  run.reader = std::make_unique<ResultsReader>(run.results_path);
  return run;
}

/// Linear interpolation of a (time, value) series at time t (clamped to its ends).
inline double value_at(const std::vector<std::pair<double, double>>& series, double t) {
  if (t <= series.front().first) return series.front().second;
  for (std::size_t k = 1; k < series.size(); ++k)
    if (t <= series[k].first) {
      const auto& [t0, v0] = series[k - 1];
      const auto& [t1, v1] = series[k];
      return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
    }
  return series.back().second;
}

}  // namespace impactfe::testing
