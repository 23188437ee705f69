#pragma once
/// The converged state of a static or full transient run over the active DOFs of its
/// discretisation: displacements, velocities, accelerations, the external, internal and damping
/// forces of the last converged step (the generalized-α residual and the trapezoidal work sums
/// need them), the reactions, the frame acceleration and the time reached.
#include "assembly/dof_map.h"
#include "core/model.h"
#include "linalg/sparse.h"
#include "time/time_integrator.h"

namespace impactfe {

struct MotionState {
  VectorXd u, v, a;
  VectorXd f_ext_old, f_int_old, f_damp_old;
  VectorXd reactions;
  Vec3 acel = Vec3::Zero();
  double time = 0.0;

  /// At rest on `dofs` except for the initial conditions (IC: displacement and velocity at
  /// t = 0).
  void start(const DofMap& dofs, const Model& model);
  /// The same state on the DOF numbering `to` (by DOF key; DOFs new in `to` start at 0).
  void remap(const DofMap& from, const DofMap& to);
};

/// A vector over the active DOFs of `from` on the numbering `to`, by DOF key (0 for DOFs not in
/// `from`; all 0 when `values` is not over `from`).
VectorXd remap_by_key(const VectorXd& values, const DofMap& from, const DofMap& to);

/// Moves the history of `integrator` (IntegratorHistory: u, v, a and Houbolt's past
/// displacements) from numbering `from` to `to`; false when the integrator cannot (its history
/// must then start anew).
bool remap_integrator_history(TimeIntegrator& integrator, const DofMap& from, const DofMap& to);

}  // namespace impactfe
