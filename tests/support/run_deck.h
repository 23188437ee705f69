#pragma once
/// Test support: runs a deck through the same path as `impactfe run` (read_deck + JobSession) in
/// a fresh directory and opens the results file.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "analysis/job_session.h"
#include "deck/deck_reader.h"
#include "results/results_file.h"

namespace impactfe::testing {

struct DeckRun {
  std::filesystem::path directory;
  std::string results_path;
  RunStatistics statistics;
  std::unique_ptr<ResultsReader> reader;
};

/// A fresh working directory <tmp>/impactfe_tests/<tag>_<pid>: unique per test process, since
/// ctest runs the tests of one binary in parallel processes.
inline std::filesystem::path fresh_directory(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / "impactfe_tests" / (tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Runs `deck` (absolute path) in `directory` (kept: a generation pass leaves its superelement
/// there for the use pass) with jobname = deck stem unless given.
inline DeckRun run_deck_in(const std::string& deck, const std::filesystem::path& directory,
                           const RunSettings& settings = {}, std::string jobname = {}) {
  namespace fs = std::filesystem;
  DeckRun run;
  run.directory = directory;
  const fs::path previous = fs::current_path();
  fs::current_path(run.directory);
  if (jobname.empty()) jobname = fs::path(deck).stem().string();
  try {
    // As `impactfe run`: the session solves each request when the deck reaches it.
    JobSession session(jobname, settings, run.statistics);
    DeckOptions options;
    options.jobname = jobname;
    options.host = &session;
    const Job job = read_deck(deck, options);
  } catch (...) {
    fs::current_path(previous);
    throw;
  }
  fs::current_path(previous);
  run.results_path = (run.directory / (jobname + ".h5")).string();
  run.reader = std::make_unique<ResultsReader>(run.results_path);
  return run;
}

/// Runs `deck` in a fresh directory named after `tag`.
inline DeckRun run_deck(const std::string& deck, const std::string& tag,
                        const RunSettings& settings = {}) {
  return run_deck_in(deck, fresh_directory(tag), settings);
}

/// Writes `text` as <tag>.inp into a fresh directory named after `tag` and runs it there.
inline DeckRun run_deck_text(const std::string& tag, const std::string& text,
                             const RunSettings& settings = {}) {
  const std::filesystem::path dir = fresh_directory(tag);
  const std::string deck = (dir / (tag + ".inp")).string();
  {
    std::ofstream out(deck);
    out << text;
  }
  return run_deck_in(deck, dir, settings);
}

/// The value of a (time, value) series stored at time t (within 1e-9); a test failure and NaN
/// when no point was stored there.
inline double value_stored_at(const std::vector<std::pair<double, double>>& series, double t) {
  for (const auto& [time, v] : series)
    if (std::abs(time - t) < 1e-9) return v;
  ADD_FAILURE() << "no value at t = " << t;
  return NAN;
}

/// The last stored value of a nodal quantity (ResultsReader::nodal_series); a test failure and
/// NaN when none was stored.
inline double last_nodal_value(const ResultsReader& r, int node, const std::string& lab) {
  const auto series = r.nodal_series(node, lab);
  EXPECT_FALSE(series.empty()) << "node " << node << " " << lab;
  return series.empty() ? NAN : series.back().second;
}

/// The message a deck run stops with ("" when it runs to its end).
inline std::string run_deck_error(const std::string& tag, const std::string& text) {
  try {
    run_deck_text(tag, text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
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
