#pragma once
/// Solution controls of automatic time stepping and restart (APDL_MODELING §9.1, §9.5;
/// docs/solution_control.md): AUTOTS with the NSUBST / DELTIM limits per load step, RESCONTROL
/// and ANTYPE,,RESTART per analysis.
///
/// Interim carrier. These values belong in LoadStep (StepControl) and AnalysisOptions (the
/// restart part) of core/model.h; they are kept here, in a table the deck fills and the full
/// driver reads, because a change of core/model.h recompiles the whole program. The deck runs
/// one command at a time and a SOLVE solves when it is read, so the table always holds the
/// entries of the load steps being solved. Fold into core/model.h at the next rebuild-all.
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include "core/errors.h"

namespace impactfe {

/// Automatic time stepping of a load step (AUTOTS; NSUBST NSBMX/NSBMN, DELTIM DTMIN/DTMAX,
/// Carry).
struct StepControl {
  std::optional<bool> automatic;         // AUTOTS ON/AUTO (true), OFF (false); unset: default
  std::optional<double> dt_min, dt_max;  // DELTIM DTMIN / DTMAX (time units)
  std::optional<int> n_max, n_min;       // NSUBST NSBMX (smallest step) / NSBMN (largest step)
  bool carry = false;                    // Carry ON: start with the last step of the previous
};

/// RESCONTROL,DEFINE: the converged substeps that keep a restart point in <jobname>.rst.h5
/// (none unless RESCONTROL was given, [A]).
/// Load steps: 0 LAST (default), n > 0 every n-th (ALL = 1), -1 NONE; substeps: 0 LAST
/// (default), n > 0 every n-th and the last, -1 NONE.
struct RestartControl {
  bool defined = false;  // RESCONTROL,DEFINE given: restart points are written
  int load_steps = 0;
  int frequency = 0;
};

/// ANTYPE,,RESTART,LDSTEP,SUBSTEP: continue from a restart point (blank: the last one saved).
struct RestartRequest {
  std::optional<int> load_step;
  std::optional<int> substep;
  SourceLocation where;  // the ANTYPE command
};

class SolutionControls {
 public:
  /// The table of the deck being run (one deck runs at a time in a process).
  static SolutionControls& instance();
  /// A new deck or /CLEAR: everything back to the defaults.
  void clear();

  /// The step options being set (like Model::current): AUTOTS, DELTIM / NSUBST limits.
  StepControl current;
  /// Records `current` for the load step closed by the command at `where` as number `number`.
  void record(const SourceLocation& where, int number);
  /// The options recorded for that load step (defaults when none was).
  StepControl step(const SourceLocation& where, int number) const;

  RestartControl restart_control;         // RESCONTROL (kept for later analyses)
  std::optional<RestartRequest> restart;  // ANTYPE,,RESTART: taken by the next analysis

 private:
  std::map<std::tuple<std::string, int, int>, StepControl> steps_;
};

}  // namespace impactfe
