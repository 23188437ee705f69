#pragma once
/// Restart points of a static / full transient run (RESCONTROL, ANTYPE,,RESTART; APDL_MODELING
/// §9.5; docs/solution_control.md): what continuing needs at a converged substep, kept in
/// <jobname>.rst.h5 beside the results file, one group per point ("ls<L>_ss<S>").
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "core/dof.h"
#include "core/errors.h"
#include "linalg/sparse.h"
#include "time/step_control.h"

namespace impactfe {

struct RestartPoint {
  int load_step = 0;
  int substep = 0;
  double time = 0.0;
  double t_start = 0.0;           // start time of the load step
  bool last = false;              // the last substep of its load step
  bool dynamic = false;           // the step was dynamic (TIMINT on)
  double h = 0.0;                 // integrator step
  std::optional<double> last_dt;  // the step size Carry would start the next load step with
  std::vector<DofKey> dofs;       // the active DOFs the vectors are over
  VectorXd u, v, a, f_ext_old, f_int_old, f_damp_old, reactions;
  Vec3 acel = Vec3::Zero();
  std::vector<VectorXd> history;  // IntegratorHistory (empty for a static run)
  std::vector<double> energy;     // EnergyBalance::state
  std::vector<int> status_ids;    // status elements and their status codes (GapStatus)
  std::vector<int> status_codes;
  // Committed element states (Element::history_state: plastic history, slider slip, contact
  // state) of the elements that have one, by element id.
  std::map<int, std::vector<double>> element_states;
  // A point inside a load step solved with AUTOTS: the step controller's state and the span of
  // the load step it was planned for.
  std::optional<StepController::State> autots;
  double autots_t_end = 0.0;
  // Loads the next load step ramps from (KBC 0): those of this point's load step, and those
  // of the load step before it (for a point inside its load step).
  std::map<DofKey, double> step_forces, step_constraints;
  Vec3 step_acel = Vec3::Zero();
  bool has_previous = false;
  std::map<DofKey, double> previous_forces, previous_constraints;
  Vec3 previous_acel = Vec3::Zero();
};

/// "<results path without .h5>.rst.h5".
std::string restart_path(const std::string& results_path);

/// Adds a point (replacing one of the same load step and substep); `drop_earlier_load_steps`
/// removes the points of earlier load steps first (RESCONTROL Ldstep LAST). Failures are
/// SolutionError (exit 2): the run cannot keep what was asked.
void write_restart_point(const std::string& path, const RestartPoint& point,
                         bool drop_earlier_load_steps);

/// The point of the given load step / substep (blank: the last one of that load step, or the
/// last point of all). InputError at `where` when the file or the point does not exist, naming
/// the points there are.
RestartPoint read_restart_point(const std::string& path, std::optional<int> load_step,
                                std::optional<int> substep, const SourceLocation& where);

}  // namespace impactfe
