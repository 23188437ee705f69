#pragma once
/// The loads of the load step being solved on the current DOF numbering: F and D resolved to DOF
/// indices once per load step (and again after a renumbering), the frame acceleration (ACEL),
/// the rotational inertia loads (OMEGA, DOMEGA, CGOMGA, DCGOMG) and the face pressures, at any load
/// point of the step (KBC ramps, time functions).
#include "analysis/discretisation.h"
#include "assembly/loads.h"

namespace impactfe {

class StepLoads {
 public:
  explicit StepLoads(const Structure& structure) : structure_(structure) {}

  /// The load step `step` (ramping from `previous` under KBC 0) on `disc`'s numbering; again
  /// after a renumbering with the same load step.
  void resolve(const Discretisation& disc, const LoadStep& step, const LoadStep* previous);
  void resolve_again(const Discretisation& disc);

  /// The load point at `fraction` of the load step, time `time`.
  LoadPoint at(double fraction, double time) const;
  /// External force at `at` over the active DOFs: frame acceleration, rotational inertia, F,
  /// face pressures on
  /// the faces as deformed by `u` (large deflection; undeformed otherwise), and the equivalent
  /// forces of the thermal strain (which also sets each element's temperature change at `at`,
  /// for its results).
  void external_force(const Discretisation& disc, const LoadPoint& at, const VectorXd& u,
                      VectorXd& f) const;
  /// Sets the constrained DOFs of `u` to their prescribed values at `at` (D; 0 for the
  /// automatic constraints).
  void prescribe(const Discretisation& disc, const LoadPoint& at, VectorXd& u) const;

 private:
  /// Adds the thermal strain loads at `at` (docs/thermal_loads.md).
  void add_thermal_forces(const Discretisation& disc, const LoadPoint& at, VectorXd& f) const;

  /// Adds the rotational inertia load at `at` (OMEGA, DOMEGA, CGOMGA, DCGOMG): formed again
  /// only when the loads differ from the last ones on this numbering (a linear step: once).
  void add_rotational_forces(const Discretisation& disc, const LoadPoint& at, VectorXd& f) const;

  const Structure& structure_;
  mutable RotationalLoads rotation_;  // the loads of rotation_force_ (empty: none formed yet)
  mutable VectorXd rotation_force_;
  bool thermal_ = false;  // the step or the one before gives temperatures, or a material REFT
  const LoadStep* step_ = nullptr;
  const LoadStep* previous_ = nullptr;
  ResolvedDofLoads forces_, prescribed_;
};

}  // namespace impactfe
