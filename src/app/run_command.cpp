/// `impactfe run`: the deck run from the command line, its log, its summary; on MPI ranks, one
/// exit status for all.
#include "app/run_command.h"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "analysis/job_session.h"
#include "app/exit_status.h"
#include "app/interrupt_handlers.h"
#include "app/rank_output.h"
#include "app/terminal_progress.h"
#include "core/errors.h"
#include "core/files.h"
#include "core/interruption.h"
#include "core/job_lock.h"
#include "core/log.h"
#include "core/memory_budget.h"
#include "core/thread_pool.h"
#include "deck/deck_reader.h"
#include "linalg/parallel_backend.h"
#include "results/results_file.h"

namespace fs = std::filesystem;

namespace impactfe::app {

namespace {

/// The run summary, printed and written to the log (energy balance included).
void print_summary(const std::string& jobname, const RunStatistics& stats, double wall) {
  std::string text = fmt::format("impactfe: job {}\n", jobname);
  for (const auto& a : stats.analyses) {
    text += fmt::format(
        "  {}: {} DOFs, {} load steps, {} substeps, {} iterations, {} stored, "
        "{} factorizations ({} symbolic), {} solves, {} status changes, {:.3f} s\n",
        a.description, a.n_dofs, a.n_load_steps, a.n_substeps, a.n_iterations, a.n_stored,
        a.n_factorizations, a.n_analyses, a.n_solves, a.n_status_changes, a.wall_seconds);
    if (a.factor_nonzeros > 0)
      text += fmt::format(
          "    linear solver: nnz(K) {}, nnz(L) {}, factor {:.6g} MB, analyze {:.6f} s, "
          "factorize {:.6f} s, solve {:.6f} s\n",
          a.matrix_nonzeros, a.factor_nonzeros, a.factor_bytes / 1.0e6, a.analyze_seconds,
          a.factorize_seconds, a.solve_seconds);
    if (a.stepping_seconds > 0.0 && a.n_substeps > 0)
      text +=
          fmt::format("    stepping: {:.3f} s, {:.4f} ms per substep (factorizations included)\n",
                      a.stepping_seconds, 1e3 * a.stepping_seconds / a.n_substeps);
    if (a.line_search)
      text += fmt::format("    line search (LNSRCH): {} of {} corrections shortened\n",
                          a.n_line_searches, a.n_iterations);
    for (const auto& note : a.notes) text += "    " + note + "\n";
  }
  if (!Log::warnings().empty())
    text += fmt::format("  {} warning(s), see {}.log\n", Log::warnings().size(), jobname);
  text += fmt::format("  wall time {:.3f} s\n", wall);
  std::cout << text;
  Log::info("run summary:\n{}", text);
}

/// --skip-unknown: what was skipped and how often, in the summary and the log.
void print_skipped(const Job& job) {
  if (job.skipped_unknown.empty()) return;
  int total = 0;
  for (const auto& s : job.skipped_unknown) total += s.count;
  const std::string head = fmt::format("  {} unknown command(s) skipped (--skip-unknown):", total);
  std::cout << head << "\n";
  Log::warn("{}", head.substr(2));
  for (const auto& s : job.skipped_unknown) {
    const std::string line =
        fmt::format("{:<16} {:>6} x   first at {}:{}", s.name, s.count, s.first.file, s.first.line);
    std::cout << "    " << line << "\n";
    Log::info("skipped: {}", line);
  }
}

/// The output directory exists (or is created) and becomes the working directory, and the log
/// file opens there. Else the run could not keep its results: exit status 2, like a full disk.
/// The job is claimed (core/job_lock.h) before its log is opened: a second run of the same job in
/// the same directory is refused at once (exit status 1) and truncates nothing of the first.
std::optional<int> enter_output_directory(const RunArgs& args, const std::string& jobname,
                                          std::ofstream& log_file, std::shared_ptr<JobLock>& lock) {
  std::error_code ec;
  fs::create_directories(args.out_dir, ec);
  if (!ec) fs::current_path(args.out_dir, ec);
  if (ec) {
    std::cerr << fmt::format("error: cannot use the output directory '{}': {}\n", args.out_dir,
                             ec.message());
    return kExitSolution;
  }
  try {
    lock = JobLock::acquire(jobname + ".h5");
  } catch (const JobLockedError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const std::runtime_error& e) {
    std::cerr << fmt::format("error: cannot write in the output directory '{}': {}\n", args.out_dir,
                             e.what());
    return kExitSolution;
  }
  log_file.open(jobname + ".log");
  if (!log_file) {
    std::cerr << fmt::format("error: cannot write in the output directory '{}' ({}): {}\n",
                             args.out_dir, jobname + ".log", std::strerror(errno));
    return kExitSolution;
  }
  return std::nullopt;
}

/// Log lines go to the log file; warnings also to the terminal, as they happen. Errors reach the
/// terminal once, from the command itself.
void log_to_file_and_terminal(std::ofstream& log_file, TerminalProgress& progress) {
  Log::set_sink([&log_file, &progress](LogLevel level, const std::string& message) {
    static const char* names[] = {"debug", "info", "warning", "error"};
    log_file << names[static_cast<int>(level)] << ": " << message << "\n";
    log_file.flush();
    if (level == LogLevel::Warning) {
      progress.clear();
      std::cerr << "warning: " << message << "\n";
    }
  });
}

/// The deck reader's options from the command line; nullopt (after a message) when --results
/// names no file.
std::optional<DeckOptions> deck_options(const RunArgs& args, const fs::path& start_directory) {
  DeckOptions options;
  options.skip_unknown = args.skip_unknown;
  options.jobname = args.jobname;
  if (!args.results.empty()) {
    const fs::path results = fs::absolute(start_directory / args.results);
    if (!fs::is_regular_file(results)) {
      std::cerr << "error: results file not found: " << args.results << "\n";
      return std::nullopt;
    }
    options.results_file = results.string();
  }
  options.output = &std::cout;  // the deck's listings (*VWRITE, *MSG, /COM, ...) until /OUT
  options.processes = process_count();
  if (args.dialect == "4x") options.dialect = Dialect::Classic4x;
  if (args.dialect == "modern") options.dialect = Dialect::Modern;
  return options;
}

/// Reads and runs the deck; each solution request is solved by the session when the deck
/// reaches it. Returns the exit status of a failure, nullopt on success.
std::optional<int> run_deck(const fs::path& deck, const DeckOptions& options, JobSession& session,
                            TerminalProgress& progress, Job& job) {
  try {
    job = read_deck(deck.string(), options);
    session.complete();  // under MPI: superelements generated by other ranks copied here
    progress.clear();
    return std::nullopt;
  } catch (const RunInterrupted& e) {
    // Stopped on request after a converged substep: the analysis is marked "interrupted".
    progress.clear();
    std::cerr << "impactfe: " << e.what() << "\n";
    if (!session.results_path().empty())
      std::cerr << fmt::format(
          "results up to the interruption are kept in {} (status "
          "\"interrupted\")\n",
          session.results_path());
    const int status = interrupted_exit_status(e.signal());
    Log::info("run stopped by {}: exit status {}", signal_name(e.signal()), status);
    return status;
  } catch (const SolutionError& e) {
    note_local_failure();  // under MPI: the solvers go without collective clean-up
    progress.clear();
    std::cerr << "error: " << e.what() << "\n";
    if (!session.results_path().empty())
      std::cerr << fmt::format("results up to the failure are kept in {}\n",
                               session.results_path());
    Log::write(LogLevel::Error, e.what());
    return kExitSolution;
  } catch (const InternalError& e) {
    note_local_failure();
    progress.clear();
    return report_internal_error(e);
  } catch (const std::exception& e) {
    note_local_failure();
    progress.clear();
    std::cerr << "error: " << e.what() << "\n";
    Log::write(LogLevel::Error, e.what());
    return kExitInput;
  }
}

}  // namespace

int run_command(const RunArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  if (args.threads > 0) threads::set_max_threads(args.threads);
  set_results_writer_thread(args.results_thread == "on"    ? WriterThread::On
                            : args.results_thread == "off" ? WriterThread::Off
                                                           : WriterThread::Auto);
  const fs::path deck = fs::absolute(args.deck);
  if (!file_exists(deck.string(), true)) {  // rank 0's disk under MPI (core/files.h)
    std::cerr << "error: deck not found: " << args.deck << "\n";
    return kExitInput;
  }
  const fs::path start_directory = fs::current_path();  // --results is relative to it
  std::string jobname = args.jobname.empty() ? deck.stem().string() : args.jobname;
  if (const std::string problem = jobname_problem(jobname); !problem.empty()) {
    std::cerr << "error: -j: " << problem << "\n";
    return kExitInput;
  }
  if (!args.memory.empty()) {
    const auto bytes = parse_bytes(args.memory);
    if (!bytes) {
      std::cerr << "error: --memory " << args.memory << ": not a size (e.g. 4G, 512M)\n";
      return kExitInput;
    }
    set_memory_limit(bytes);
  }
  std::shared_ptr<JobLock> job_lock;  // held to the end of the run
  std::ofstream log_file;
  if (const auto failed = enter_output_directory(args, jobname, log_file, job_lock)) return *failed;
  TerminalProgress progress;
  log_to_file_and_terminal(log_file, progress);
  if (!parallel_backend_active()) install_interrupt_handlers();  // mpirun forwards signals itself
  const std::optional<DeckOptions> options = deck_options(args, start_directory);
  if (!options) return kExitInput;

  RunSettings settings;
  settings.continue_on_nonconvergence = args.continue_on_nonconvergence;
  settings.accept_energy_error = args.accept_energy_error;
  settings.superelement_file = args.superelement;
  settings.progress = &progress;
  settings.condense = !args.no_condense;
  RunStatistics stats;
  JobSession session(jobname, settings, stats);
  DeckOptions hosted = *options;
  hosted.host = &session;
  Job job;
  if (const auto failed = run_deck(deck, hosted, session, progress, job)) return *failed;

  if (args.jobname.empty() && !job.model.jobname.empty()) jobname = job.model.jobname;
  for (const auto& ignored : job.ignored_commands) Log::info("ignored: {}", ignored);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_summary(jobname, stats, wall);
  if (parallel_backend_active()) {
    const std::string line =
        fmt::format("  sparse solver: MUMPS on {} MPI rank(s)", process_count());
    std::cout << line << "\n";
    Log::info("{}", line.substr(2));
  }
  print_skipped(job);
  for (const auto& file : session.results_files())
    std::cout << fmt::format("  results: {}\n", (fs::current_path() / file).string());
  return kExitOk;
}

/// How long a failing rank waits for the others at the exit agreement before it decides that
/// it failed alone and aborts them all. Ranks that fail together (the same deck, the same
/// matrices) arrive within the time of the work between two collective calls; a rank that
/// failed alone is waited for by the others inside a collective call, forever.
constexpr double kFailureWaitSeconds = 3.0;

/// `--solver mumps`: MPI up (the module loaded only now), the deck run on every rank, one exit
/// status for all, MPI down. A failure on one rank only ends every rank with that rank's status
/// and its message printed once (docs/scaling.md, Errors).
int run_distributed(RunArgs args) {
  if (!args.mumps_ooc_dir.empty()) args.mumps_ooc = true;  // a directory implies --mumps-ooc
  start_parallel_backend({args.mumps_ooc, args.mumps_ooc_dir, !args.mumps_no_refine});
  // One thread per rank unless --threads says otherwise: the ranks share the cores.
  if (args.threads == 0 && process_count() > 1) args.threads = 1;
  int status = kExitOk;
  std::unique_ptr<RankOutput> output;
  try {
    output = std::make_unique<RankOutput>(
        RankPaths{args.deck, args.out_dir, args.superelement, args.results});
    status = run_command(args);
  } catch (const std::exception& e) {  // the set-up of this rank (run_command catches its own)
    note_local_failure();
    std::cerr << "error: " << e.what() << "\n";
    status = kExitInput;
  }
  const std::optional<int> agreed = agree_exit_status(status, kFailureWaitSeconds);
  if (!agreed) {
    if (output) output->report_failure_alone(status);
    abort_all_ranks(status);
  }
  output.reset();
  stop_parallel_backend();
  return *agreed;
}

}  // namespace impactfe::app
