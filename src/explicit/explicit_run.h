#pragma once
/// The explicit dynamics analysis (docs/explicit_dynamics.md): a transient analysis whose
/// elements are all explicit ones (SOLID164, ...) runs here instead of the implicit drivers, by
/// the central difference of central_difference.h, over the load steps of the request, and
/// writes its results into the job's results file like an implicit transient.
#include <functional>
#include <string>
#include <vector>

#include "core/model.h"
#include "results/results_file.h"

namespace impactfe {

/// Where a running explicit analysis is, for the program's progress line.
struct ExplicitProgress {
  double time = 0.0;
  double load_step_end = 0.0;  // end time of the load step being run
  double run_end = 0.0;        // end time of the last load step
  int load_step = 0;
  bool last_of_load_step = false;
  long long cycles = 0;
  double dt = 0.0;            // the step of the last cycle
  double energy_error = 0.0;  // of the last energy check (NaN before the first)
};

struct ExplicitRunOptions {
  bool accept_energy_error = false;  // --accept-energy-error: warn and go on
  /// Told every kProgressCycles cycles and at the end of every load step (empty: nobody asks).
  std::function<void(const ExplicitProgress&)> progress;
};

/// Cycles between two progress reports (the line is drawn 10 times a second at most).
inline constexpr long kProgressCycles = 64;

/// Figures of a finished run, for the run summary.
struct ExplicitRunSummary {
  long cycles = 0;
  long element_cycles = 0;
  double last_step = 0.0;
  int last_controlling_element = 0;
  double smallest_step = 0.0;
  int smallest_step_element = 0;
  double ns_per_element_cycle = 0.0;
  int stored_points = 0;
  std::size_t n_elements = 0, n_nodes = 0;
  std::vector<std::string> notes;  // lines for the run summary
};

/// The energy check's bound: the same rule as the implicit driver's (EnergyBalance::
/// kCreationBound, run_observers.h kStepsOver): the total energy off the energy put in by more
/// than 10 % of it at 3 checks in a row stops the run.
inline constexpr double kExplicitEnergyBound = 0.10;
inline constexpr int kExplicitChecksOver = 3;
/// The first cycle the check judges. A motion that starts from rest under a load growing like
/// t^p is integrated with a start-up error of about p/n² of its energies at cycle n (measured:
/// 1/n² for a linear ramp, 4/n² for a cubic one; the central difference's O(Δt²) error against
/// energies of O(t^(2p+2))), so the first cycles would stop a stable run (vme1's ramped force:
/// 11 % at cycle 3). An instability only grows and is still caught from this cycle on.
inline constexpr long kExplicitFirstJudgedCycle = 20;

/// Runs the analysis; throws InputError / NotImplementedError for what the explicit solver does
/// not carry out (at the command when known), SolutionError (exit 2) when the energy check
/// fails or an element inverts, RunInterrupted on Ctrl-C. Results written stay in the file.
ExplicitRunSummary run_explicit_analysis(const Model& model, const AnalysisRequest& request,
                                         ResultsWriter& writer, const ExplicitRunOptions& options);

}  // namespace impactfe
