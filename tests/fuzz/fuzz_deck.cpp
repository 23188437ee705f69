// libFuzzer harness over the deck reader and the model builder (issue 12; scripts/fuzz.sh).
//
// Every input is read as a deck with read_deck_text and no solution host: the lexer, the
// expressions, the command handlers and the model checks run, and the only acceptable outcomes
// are a Job or a user error that names the deck (InputError & co., LocatedError). Anything else
// is a finding: InternalError, a library exception in its own words, a sanitizer report, a
// crash, or an input that takes more than a second (run with -timeout=1).
//
// When the deck builds a small model, the cheapest solve runs too: the deck is read again with
// a JobSession in a temporary directory, so the element factories, the structure checks, the
// drivers and the results writer see the fuzzed model. Bounds keep every input fast: at most
// kMaxSolveNodes nodes and elements, kMaxSolveSubsteps substeps, kMaxSolveIterations
// equilibrium iterations per substep and kMaxSolveElementSubsteps elements x substeps (the
// costliest seed, a 20-element co-rotational beam over 41 substeps, takes 0.66 s under the
// sanitizers); an explicit run stops, as on Ctrl-C, past kMaxSolveElementCycles. Decks that
// name files the solve would write (/FILNAME, SEOPT) are not solved, so that no input can write
// outside the temporary directory.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "analysis/job_session.h"
#include "analysis/progress.h"
#include "core/errors.h"
#include "core/interruption.h"
#include "core/log.h"
#include "deck/deck_reader.h"

namespace fs = std::filesystem;
using namespace impactfe;

namespace {

constexpr std::size_t kMaxInput = 16384;  // bytes of deck text
// Model size limits of the read. Commands that pass over the whole model cost time in proportion
// to it: with 20 000, nine SAVEs of 14 400 meshed shells took 2 s under the sanitizers
// (tests/fuzz/regressions/, which scripts/fuzz.sh runs first). Reader bugs show on small models.
constexpr std::size_t kMaxReadNodes = 2000;
// Interpreted work of the read (commands and loop trips): 10⁷ `N,1` take 2.7 s in the Release
// build, over 10 s under the sanitizers; 10⁵ stay well inside the one-second limit.
constexpr long long kMaxReadCommands = 100'000;
constexpr std::size_t kMaxSolveNodes = 40;   // model size of an input that is solved
constexpr double kMaxSolveSubsteps = 200.0;  // substeps over all load steps
constexpr int kMaxSolveIterations = 30;      // NEQIT
constexpr int kMaxSolveModes = 20;           // MODOPT
constexpr double kMaxSolveElementSubsteps = 400.0;
// An explicit run's cycles are known only once it runs (the stable step follows from the
// mesh): its progress reports (every kProgressCycles cycles) stop it past this many
// element-cycles. A 20-element BEAM161 bar turned through 5.6·10³ cycles took 2.6 s under the
// sanitizers, about 2·10⁴ element-cycles per second.
constexpr long long kMaxSolveElementCycles = 4000;

fs::path work_directory;

/// A finding: print what happened and abort, so that libFuzzer saves the input.
[[noreturn]] void finding(const char* what, const std::string& message) {
  std::fprintf(stderr, "\n==== fuzz_deck finding: %s: %s\n", what, message.c_str());
  std::fflush(stderr);
  std::abort();
}

bool contains_upper(const std::string& text, const char* word) {
  std::string upper(text);
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper.find(word) != std::string::npos;
}

/// Substeps the job would run, over every load step (an upper estimate; huge when unknown).
double substeps_of(const Job& job) {
  double total = 0.0;
  for (const auto& step : job.steps) {
    if (step.expansion) total += 1.0;
    if (!step.analysis) continue;
    const AnalysisOptions& o = step.analysis->options;
    if (o.convergence.max_iterations > kMaxSolveIterations) return 1e300;
    if (o.modal.n_modes > kMaxSolveModes || o.msup_modes > kMaxSolveModes) return 1e300;
    double t_prev = 0.0;
    double reduced_dt = 0.0;
    for (const LoadStep& ls : step.analysis->load_steps) {
      const double t_end = ls.time_end.value_or(t_prev + 1.0);
      const double span = std::abs(t_end - t_prev);
      double n = ls.n_substeps ? std::max(1, *ls.n_substeps) : 1.0;
      if (ls.dt && *ls.dt > 0.0) {
        n = span / *ls.dt;
        if (reduced_dt == 0.0) reduced_dt = *ls.dt;
      } else if (reduced_dt > 0.0) {
        n = std::max(n, span / reduced_dt);  // reduced / MSUP keep the first DTIME
      }
      if (!std::isfinite(n)) return 1e300;
      total += n + 1.0;
      t_prev = t_end;
    }
  }
  return total;
}

std::size_t most_elements_of(const Job& job) {
  std::size_t most = 1;
  for (const auto& step : job.steps) most = std::max(most, step.model_snapshot->elements.size());
  return most;
}

bool small_enough_to_solve(const Job& job, const std::string& text) {
  if (job.steps.empty()) return false;
  if (contains_upper(text, "FILN") || contains_upper(text, "SEOP")) return false;
  std::size_t most_elements = 1;
  for (const auto& step : job.steps) {
    const Model& m = *step.model_snapshot;
    if (m.nodes.size() > kMaxSolveNodes || m.elements.size() > kMaxSolveNodes) return false;
    most_elements = std::max(most_elements, m.elements.size());
  }
  const double substeps = substeps_of(job);
  return substeps <= kMaxSolveSubsteps &&
         substeps * static_cast<double>(most_elements) <= kMaxSolveElementSubsteps;
}

/// Stops an explicit run past its element-cycle budget, as Ctrl-C would (RunInterrupted).
class CycleBudget : public ProgressObserver {
 public:
  explicit CycleBudget(std::size_t elements) : elements_(static_cast<long long>(elements)) {}
  void substep_done(const ProgressEvent& event) override {
    if (event.cycles > 0 && event.cycles * elements_ > kMaxSolveElementCycles)
      throw RunInterrupted(0, "fuzz harness: element-cycle budget spent");
  }

 private:
  long long elements_;
};

/// Runs `read` and checks that whatever it throws is a user error naming the deck.
template <class Read>
void expect_user_error_only(const char* phase, Read read) {
  try {
    read();
  } catch (const RunInterrupted&) {
    // The harness's own stop (CycleBudget): not a finding.
  } catch (const InternalError& e) {
    finding(phase, std::string("internal error: ") + e.what());
  } catch (const LocatedError& e) {
    // The contract: a message for the user that names the deck command that caused it.
    if (e.message().empty()) finding(phase, "empty error message");
    if (!e.where().known()) finding(phase, std::string("error without FILE:LINE: ") + e.what());
  } catch (const std::bad_alloc&) {
    finding(phase, "std::bad_alloc (a resource bound is missing)");
  } catch (const std::exception& e) {
    finding(phase, std::string("untranslated exception: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Log::set_sink([](LogLevel, const std::string&) {});
  work_directory = fs::temp_directory_path() / ("impactfe_fuzz_" + std::to_string(::getpid()));
  fs::create_directories(work_directory);
  fs::current_path(work_directory);
  std::atexit([] {
    std::error_code ec;
    fs::current_path(fs::temp_directory_path(), ec);
    fs::remove_all(work_directory, ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return -1;  // not added to the corpus
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = (work_directory / "fuzz.inp").string();
  Log::clear();

  DeckOptions options;
  options.max_nodes = kMaxReadNodes;
  options.max_elements = kMaxReadNodes;
  options.max_commands = kMaxReadCommands;
  options.jobname = "fuzz";
  Job job;
  bool built = false;
  expect_user_error_only("read", [&] {
    job = read_deck_text(text, path, options);
    built = true;
  });
  if (!built || !small_enough_to_solve(job, text)) return 0;

  // The cheapest solve: the same deck with a job session in the work directory.
  expect_user_error_only("solve", [&] {
    CycleBudget budget(most_elements_of(job));
    RunSettings settings;
    settings.progress = &budget;
    RunStatistics stats;
    JobSession session("fuzz", settings, stats);
    DeckOptions solve_options = options;
    solve_options.host = &session;
    read_deck_text(text, path, solve_options);
  });
  Log::clear();
  return 0;
}
