/// impactfe command-line interface: run a deck, query a results file, export, report, Houbolt
/// spectrum.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "analysis/job_session.h"
#include "app/rank_output.h"
#include "app/terminal_progress.h"
#include "core/errors.h"
#include "core/files.h"
#include "core/log.h"
#include "core/thread_pool.h"
#include "deck/deck_reader.h"
#include "linalg/parallel_backend.h"
#include "results/post_csv.h"
#include "results/report.h"
#include "results/results_file.h"
#include "results/vtk_export.h"
#include "time/houbolt_spectrum.h"

namespace fs = std::filesystem;
using namespace impactfe;

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInput = 1;
constexpr int kExitSolution = 2;
constexpr int kExitInternal = 3;

/// glibc raises its mmap threshold to the size of every mapped block freed (up to 32 MB); from
/// then on, blocks of that size come from the heap, and a freed one below live data is not given
/// back. A run frees model-size arrays on its way to the factorization (pattern, products,
/// CHOLMOD's copies), so the peak resident memory grew by those holes: 0.73 GB for the shell
/// dome 160, 0.68 GB with a fixed threshold (docs/benchmarks.md). Setting the threshold also
/// stops its raising: blocks of 1 MB and more are mapped on their own and returned when freed.
void map_large_blocks_on_their_own() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

/// A broken internal invariant: the user's input is not to blame.
int report_internal_error(const InternalError& e) {
  std::cerr << "error: " << e.what()
            << "\nThis is a bug in impactfe, not in your input; please report it with the deck.\n";
  Log::write(LogLevel::Error, e.what());
  return kExitInternal;
}

struct RunArgs {
  std::string deck;
  std::string out_dir = ".";
  std::string jobname;
  int threads = 0;                      // 0: all cores
  std::string results_thread = "auto";  // auto | on | off
  bool skip_unknown = false;
  std::string dialect = "auto";
  std::string results;
  std::string superelement;
  bool continue_on_nonconvergence = false;
  bool no_condense = false;
  std::string solver = "cholmod";  // cholmod | mumps (MPI, docs/scaling.md)
  bool mumps_ooc = false;
  std::string mumps_ooc_dir;
  bool mumps_no_refine = false;
};

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
  // The output directory must exist (or be creatable) and take files: else the run could not
  // keep its results, which is exit status 2 like a full disk.
  std::string jobname = args.jobname.empty() ? deck.stem().string() : args.jobname;
  std::error_code ec;
  fs::create_directories(args.out_dir, ec);
  if (!ec) fs::current_path(args.out_dir, ec);
  if (ec) {
    std::cerr << fmt::format("error: cannot use the output directory '{}': {}\n", args.out_dir,
                             ec.message());
    return kExitSolution;
  }
  std::ofstream log_file(jobname + ".log");
  if (!log_file) {
    std::cerr << fmt::format("error: cannot write in the output directory '{}' ({}): {}\n",
                             args.out_dir, jobname + ".log", std::strerror(errno));
    return kExitSolution;
  }
  TerminalProgress progress;
  Log::set_sink([&log_file, &progress](LogLevel level, const std::string& message) {
    static const char* names[] = {"debug", "info", "warning", "error"};
    log_file << names[static_cast<int>(level)] << ": " << message << "\n";
    log_file.flush();
    // Errors reach the terminal once, from the command itself; warnings as they happen.
    if (level == LogLevel::Warning) {
      progress.clear();
      std::cerr << "warning: " << message << "\n";
    }
  });

  DeckOptions options;
  options.skip_unknown = args.skip_unknown;
  options.jobname = args.jobname;
  if (!args.results.empty()) {
    const fs::path results = fs::absolute(start_directory / args.results);
    if (!fs::is_regular_file(results)) {
      std::cerr << "error: results file not found: " << args.results << "\n";
      return kExitInput;
    }
    options.results_file = results.string();
  }
  options.output = &std::cout;  // the deck's listings (*VWRITE, *MSG, /COM, ...) until /OUT
  if (args.dialect == "4x") options.dialect = Dialect::Classic4x;
  if (args.dialect == "modern") options.dialect = Dialect::Modern;

  RunSettings settings;
  settings.continue_on_nonconvergence = args.continue_on_nonconvergence;
  settings.superelement_file = args.superelement;
  settings.progress = &progress;
  settings.condense = !args.no_condense;

  // The deck runs command by command: each solution request is solved by the session when the
  // deck reaches it.
  RunStatistics stats;
  JobSession session(jobname, settings, stats);
  options.host = &session;
  Job job;
  try {
    job = read_deck(deck.string(), options);
    session.complete();  // under MPI: superelements generated by other ranks copied here
    progress.clear();
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

}  // namespace

int main(int argc, char** argv) {
  map_large_blocks_on_their_own();
  CLI::App app{"impactfe: finite elements for structural impact dynamics"};
  app.require_subcommand(1);

  RunArgs run;
  CLI::App* run_cmd = app.add_subcommand("run", "run an APDL deck (ANSYS 4.2 or modern)");
  run_cmd->add_option("deck", run.deck, "input deck")->required();
  run_cmd->add_option("-o,--output", run.out_dir, "working directory for results (default .)");
  run_cmd->add_option("-j,--jobname", run.jobname, "job name (default: deck file stem)");
  run_cmd->add_option(
      "--threads", run.threads,
      "threads for element loops, the solves and products of large models and results "
      "compression (default: all cores where the work pays for them; BLAS runs on one thread)");
  run_cmd
      ->add_option("--results-thread", run.results_thread,
                   "write the results file on a thread of its own: auto (default: when the run "
                   "may use two threads and a core is idle at the start), on or off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  run_cmd->add_flag("--skip-unknown", run.skip_unknown, "warn and skip unknown commands");
  run_cmd->add_option("--dialect", run.dialect, "4x|modern|auto")
      ->check(CLI::IsMember({"4x", "modern", "auto"}));
  run_cmd->add_option("--results", run.results,
                      "results file read by the POST1/POST26/*GET commands of a deck that "
                      "solves nothing");
  run_cmd->add_option("--se", run.superelement, "superelement file for MATRIX50 elements");
  run_cmd->add_flag("--continue-on-nonconvergence", run.continue_on_nonconvergence,
                    "accept non-converged steps with a warning");
  run_cmd->add_flag("--no-condense", run.no_condense,
                    "full Newton on all DOFs in a transient, never the condensed linear part");
  run_cmd
      ->add_option("--solver", run.solver,
                   "sparse direct solver: cholmod (default, one process) or mumps (MPI: "
                   "mpirun -n N impactfe run DECK --solver mumps)")
      ->check(CLI::IsMember({"cholmod", "mumps"}));
  run_cmd->add_flag("--mumps-ooc", run.mumps_ooc,
                    "MUMPS out-of-core: factors on disk (for factors larger than memory)");
  run_cmd->add_option("--mumps-ooc-dir", run.mumps_ooc_dir,
                      "directory of the out-of-core factor files (default $TMPDIR or /tmp)");
  run_cmd->add_flag("--mumps-no-refine", run.mumps_no_refine,
                    "MUMPS on several ranks: no double-double refinement of the solves (faster; "
                    "results then agree to round-off but are not bitwise repeatable)");

  std::string post_file;
  std::vector<std::string> nsol, esol, gapf;
  bool freq = false;
  int mode = 0;
  CLI::App* post_cmd = app.add_subcommand("post", "print time histories / modal results as CSV");
  post_cmd->add_option("results", post_file, "results file (.h5)")->required();
  post_cmd->add_option("--nsol", nsol, "NODE,LAB (UX..ROTZ, VX..VZ, AX..AZ, FX..MZ)");
  post_cmd->add_option("--esol", esol, "ELEM,ITEM (SAXL, FORC, STAT, ...)");
  post_cmd->add_option("--gapf", gapf, "GP gap-condition number");
  post_cmd->add_flag("--freq", freq, "print mode,frequency_hz");
  post_cmd->add_option("--mode", mode, "print the shape of mode N");

  std::string info_file;
  CLI::App* info_cmd = app.add_subcommand("info", "summarise a results file");
  info_cmd->add_option("results", info_file, "results file (.h5)")->required();

  std::string export_file, export_dir = ".", export_format = "vtkhdf";
  CLI::App* export_cmd = app.add_subcommand(
      "export", "write the results for ParaView: one VTKHDF file (default) or VTU files + PVD");
  export_cmd->add_option("results", export_file, "results file (.h5)")->required();
  export_cmd->add_option("-o,--output", export_dir, "output directory (default .)");
  export_cmd->add_option("--format", export_format, "vtkhdf (default) | vtu")
      ->check(CLI::IsMember({"vtkhdf", "vtu"}));

  std::string report_file, report_out;
  ReportOptions report;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "write a self-contained HTML report (summary, plots, energy, gaps, 3-D view)");
  report_cmd->add_option("results", report_file, "results file (.h5)")->required();
  report_cmd->add_option("-o,--output", report_out,
                         "HTML file (default: the results file with extension .html)");
  report_cmd->add_option("--node", report.nodes, "node of the time-history figures (repeatable)")
      ->delimiter(',');
  report_cmd->add_option("--element", report.elements, "element of the stress figure (repeatable)")
      ->delimiter(',');
  report_cmd
      ->add_option("--item", report.items,
                   "direction UX|UY|UZ and/or element item SEQV, SAXL, FORC, ... (repeatable)")
      ->delimiter(',');
  report_cmd->add_option("--max-points", report.max_points, "at most this many points per curve")
      ->check(CLI::Range(4, 10000000));
  report_cmd->add_option("--frames", report.max_frames, "at most this many frames in the 3-D view")
      ->check(CLI::Range(2, 1000000));

  std::vector<double> xi = {0.0};
  CLI::App* spectrum_cmd = app.add_subcommand(
      "houbolt-spectrum", "spectral radius of the Houbolt amplification matrix (thesis Fig. 3-4)");
  spectrum_cmd->add_option("--xi", xi, "damping ratios");

  CLI11_PARSE(app, argc, argv);

  try {
    if (*run_cmd && run.solver != "mumps" &&
        (run.mumps_ooc || !run.mumps_ooc_dir.empty() || run.mumps_no_refine)) {
      std::cerr << "error: --mumps-ooc, --mumps-ooc-dir and --mumps-no-refine need --solver "
                   "mumps\n";
      return kExitInput;
    }
    if (*run_cmd && run.solver == "mumps") return run_distributed(run);
    if (*run_cmd) return run_command(run);
    if (*post_cmd) {
      ResultsReader reader(post_file);
      if (freq) {
        if (reader.frequencies().empty())
          throw InputError(fmt::format(
              "'{}' holds no modal results (no modal analysis was run); --freq needs one",
              post_file));
        std::cout << frequencies_csv(reader);
        return kExitOk;
      }
      if (mode > 0) {
        std::cout << mode_shape_csv(reader, mode);
        return kExitOk;
      }
      std::vector<PostRequest> requests;
      for (const auto& s : nsol) requests.push_back(parse_nsol(s));
      for (const auto& s : esol) requests.push_back(parse_esol(s));
      for (const auto& s : gapf) requests.push_back(parse_gapf(s));
      if (requests.empty()) {
        std::cerr << "error: give --nsol, --esol, --gapf, --freq or --mode\n";
        return kExitInput;
      }
      std::cout << post_csv(reader, requests);
      return kExitOk;
    }
    if (*info_cmd) {
      std::cout << results_info(ResultsReader(info_file));
      return kExitOk;
    }
    if (*export_cmd) {
      ResultsReader reader(export_file);
      fs::create_directories(export_dir);
      const std::string stem = fs::path(export_file).stem().string();
      const ExportSummary s =
          export_format == "vtu"
              ? export_vtu_series(reader, export_dir, stem)
              : export_vtkhdf(reader, (fs::path(export_dir) / (stem + ".vtkhdf")).string());
      std::cout << fmt::format(
          "export: wrote {}{} ({} time points, {} points, {} cells, {:.2f} MB)\n", s.files.front(),
          s.files.size() > 1 ? fmt::format(" and {} .vtu files", s.files.size() - 1) : "", s.frames,
          s.points, s.cells, static_cast<double>(s.bytes) / 1e6);
      if (!s.skipped_elements.empty())
        std::cout << fmt::format(
            "  {} element(s) not drawn (a node is not in the model), e.g. {}\n",
            s.skipped_elements.size(), s.skipped_elements.front());
      return kExitOk;
    }
    if (*report_cmd) {
      ResultsReader reader(report_file);
      const std::string out = report_out.empty()
                                  ? fs::path(report_file).replace_extension(".html").string()
                                  : report_out;
      const auto bytes = write_report(reader, report, out);
      std::cout << fmt::format("report: wrote {} ({:.2f} MB)\n", out, bytes / 1e6);
      return kExitOk;
    }
    if (*spectrum_cmd) {
      std::vector<double> ratios;
      for (double r = 1e-3; r <= 1e3 * 1.0001; r *= std::pow(10.0, 0.1)) ratios.push_back(r);
      std::cout << houbolt_spectrum_csv(ratios, xi);
      return kExitOk;
    }
  } catch (const InternalError& e) {
    return report_internal_error(e);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  }
  return kExitOk;
}
