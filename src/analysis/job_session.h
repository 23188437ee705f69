#pragma once
/// The job session: runs the solution requests of a deck as the deck reader meets them (MAPDL's
/// command-by-command execution), writing one results file <jobname>.h5. A static or full
/// transient analysis solves each load step when its SOLVE arrives, so *GET and POST commands
/// between SOLVEs see every step solved so far; analyses that run only as a whole (modal,
/// reduced and mode-superposition transients, substructure generation) run when they close (a
/// new analysis, FINISH before results are read, the end of the deck).
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "core/model.h"
#include "deck/solution_host.h"
#include "results/results_file.h"

namespace impactfe {

class DirectSolution;
class JobLock;
struct ReducedSolutionState;

class JobSession final : public SolutionHost {
 public:
  /// The session creates <jobname>.h5 in the working directory at the first solution (the
  /// deck's jobname then, which /FILNAME may have changed).
  JobSession(std::string jobname, const RunSettings& settings, RunStatistics& stats);
  /// The session appends to `writer` (already created with the job's results model).
  JobSession(ResultsWriter& writer, std::string jobname, const RunSettings& settings,
             RunStatistics& stats);
  ~JobSession() override;

  void solve(const Job& job, std::size_t step) override;
  void begin_new_analysis(const Job& job, std::size_t step) override;
  std::string results_for_reading(const Job& job) override;
  void finish(const Job& job) override;
  /// The end of the run: the open analysis closed, and under MPI the superelement files that
  /// other ranks generated copied here (share_generated_superelements).
  void complete();
  /// /CLEAR: closes the open analysis and the results file; the next solution starts a new
  /// results file (named after the jobname then current). A session appending to a writer it was
  /// given keeps appending to it.
  void clear(const Job& job) override;

  /// The results file of the current job (after a /CLEAR with no solution since: the previous
  /// job's; "" before the first solution).
  std::string results_path() const;
  /// Every results file written, in order (several when /CLEAR started new jobs or a new
  /// analysis after FINISH superseded the earlier ones).
  std::vector<std::string> results_files() const;

 private:
  ResultsWriter& writer_for(const Job& job, std::size_t step);
  /// A new analysis after FINISH (begin_new_analysis) of the type of the analysis before it, or
  /// on a changed model section, replaces the results file the deck reads: the file of the
  /// earlier analyses is closed and kept as <jobname>.<n>.h5 (n = 1, 2, ... per superseded
  /// file), and the next writer_for creates a new <jobname>.h5 with the model as it is now.
  void supersede_results_file(const Job& job, std::size_t step);
  /// Runs what the open step still owes and ends its results analysis.
  void close_open();
  void run_whole(const Job::Step& step, AnalysisStatistics& stats);
  /// Marks the open analysis failed (keeping every result written) and rethrows the error,
  /// naming the command being executed (`where_`) when it names no deck location itself.
  [[noreturn]] void fail(const std::exception_ptr& error);

  std::string jobname_;
  RunSettings settings_;
  RunStatistics& stats_;
  ResultsWriter* writer_ = nullptr;
  /// The claim on the files of the job being written (core/job_lock.h), taken before its
  /// results file is created or opened and released after it is closed (declared first:
  /// destroyed last).
  std::shared_ptr<JobLock> job_lock_;
  std::unique_ptr<ResultsWriter> owned_writer_;
  bool superelement_expansion_job_ = false;
  bool explicit_ = false;                  // the open analysis is an explicit dynamics run
  std::size_t job_first_analysis_ = 0;     // index in stats_.analyses of this job's first analysis
  std::vector<std::string> closed_files_;  // results files of the jobs ended by /CLEAR and
                                           // the kept files of superseded analyses
  int superseded_files_ = 0;               // <jobname>.<n>.h5 kept so far in this job
  std::optional<std::size_t> new_analysis_;  // the step begin_new_analysis announced

  // The open step: the model snapshot it shares with the job's step (held here: the job's step
  // list may reallocate, and the deck reader may drop it), the structure and, for static / full
  // transient analyses, the solution advanced load step by load step. Models are kept for the
  // session: a reduced transient's expansion state refers to its model.
  std::optional<std::size_t> open_;
  std::optional<Job::Step> open_step_;
  std::size_t load_steps_solved_ = 0;
  std::vector<std::shared_ptr<const Model>> models_;
  std::unique_ptr<Structure> structure_;
  std::unique_ptr<DirectSolution> direct_;
  std::unique_ptr<ReducedSolutionState> reduced_state_;
  std::chrono::steady_clock::time_point open_since_;
  double open_seconds_ = 0.0;  // wall time spent on the open step so far
  SourceLocation where_;       // the command being executed (SOLVE of the load step, ...)
};

/// The model whose nodes and elements the results file of a job describes when its first
/// solution is `job.steps[step]`: the deck's model, or — for a superelement expansion pass
/// (EXPASS + SEEXP), which is a job of its own in MAPDL — the generation model stored in the
/// superelement file. InputError when the files are missing.
Model results_model(const Job& job, std::size_t step = 0);

/// Runs every step of a parsed job in order (tests and tools that read a whole deck first).
/// Throws InputError / ModelError / NotImplementedError (exit 1) and SolutionError (exit 2); the
/// results written before the failure stay in the file, the failing analysis marked with the
/// error text.
void run_job(const Job& job, const std::string& jobname, const RunSettings& settings,
             ResultsWriter& writer, RunStatistics& stats);

}  // namespace impactfe
