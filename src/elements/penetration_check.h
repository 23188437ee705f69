#pragma once
/// Contact elements that ask automatic time stepping for a smaller step when a converged
/// substep ends with too much penetration: CONTA174 / CONTA175 with KEYOPT(7) = 1
/// (APDL_MODELING §9.3 item 2: "penetration > FTOLN·depth with KEYOPT(7) ≥ 1" is a cutback
/// trigger). Such an element implements this interface beside Element; the driver reaches it
/// with dynamic_cast (kept out of element.h, which much of the program includes) once per DOF
/// numbering and asks it after each converged substep of an AUTOTS load step.
#include <Eigen/Core>

namespace impactfe {

class PenetrationCheck {
 public:
  virtual ~PenetrationCheck() = default;
  /// False when the element does not check (KEYOPT(7) = 0): the driver skips it.
  virtual bool checks_penetration() const = 0;
  /// For a substep from `start` to the trial state at `u` (both over the element's DOFs): the
  /// penetration the substep added, as a fraction of the allowed one (FTOLN·depth), where the
  /// penetration at `u` exceeds it; above 1 the substep is cut. 0 when open or within FTOLN.
  /// [A] The spec's trigger "penetration > FTOLN·depth" counts what the substep added: a
  /// penetration that smaller substeps cannot reduce (a penalty contact resting under load, an
  /// augmented-Lagrange contact whose multiplier is still catching up with an impact) would
  /// otherwise cut every substep down to the minimum step.
  virtual double penetration_ratio(const Eigen::VectorXd& start,
                                   const Eigen::VectorXd& u) const = 0;
};

}  // namespace impactfe
