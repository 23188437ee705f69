#pragma once
/// What acts on the nodes of an explicit run besides the elements (docs/explicit_dynamics.md):
/// loads by curve (EDLOAD) and contact (EDCGEN). The central difference calls each interaction
/// once per cycle at x_{n+1}; the interaction adds its nodal forces in the sign of f_int (the
/// node's acceleration is −f/m), tracks its own energy, and may prescribe velocities.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "elements/explicit_kernel.h"

namespace impactfe {

class ExplicitInteraction {
 public:
  virtual ~ExplicitInteraction() = default;
  /// Adds forces at x_{n+1} (time t_{n+1}) to f (3 per node, f_int sign) after the elements';
  /// v are the half-step velocities v_{n+1/2} that brought the nodes there over dt (0 at the
  /// start); `mass` the lumped nodal masses. Returns its limit on the stable step.
  virtual ExplicitStepLimit add_forces(const ExplicitNodalView& state, const double* mass,
                                       double time, double dt, double* fx, double* fy,
                                       double* fz) = 0;
  /// Overrides the half-step velocities v_{n+1/2} of prescribed DOFs (time t_{n+1/2}, `mean`
  /// the interval ½(dt_{n−1/2} + dt_{n+1/2}) of the velocity update just made) and counts the
  /// work that takes.
  virtual void prescribe(double time, double mean, const double* mass, double* vx, double* vy,
                         double* vz) {
    (void)time, (void)mean, (void)mass, (void)vx, (void)vy, (void)vz;
  }
  /// Zeroes the accelerations of the prescribed DOFs (after keeping what the forces would give
  /// them, for the work of the next prescribe).
  virtual void hold(double* ax, double* ay, double* az) { (void)ax, (void)ay, (void)az; }
  /// Overrides the angular velocities ω_{n+1/2} of prescribed rotational DOFs (after
  /// prescribe() of the same step; `inertia` the nodal rotary inertia) and counts the work.
  virtual void prescribe_rotations(double mean, const double* inertia, double* wx, double* wy,
                                   double* wz) {
    (void)mean, (void)inertia, (void)wx, (void)wy, (void)wz;
  }
  /// Zeroes the angular accelerations of the prescribed rotational DOFs.
  virtual void hold_rotations(const double* inertia, double* bx, double* by, double* bz) {
    (void)inertia, (void)bx, (void)by, (void)bz;
  }
  /// Overrides components of the centre velocity v_c(n+1/2) of rigid body `body` (of mass
  /// `mass`) prescribed there, after prescribe() of the same step, and counts the work.
  virtual void prescribe_rigid(std::size_t body, double mass, double mean, double* velocity) {
    (void)body, (void)mass, (void)mean, (void)velocity;
  }
  /// Zeroes the prescribed components of the body's centre acceleration (keeping what the
  /// forces would give, for the work).
  virtual void hold_rigid(std::size_t body, double mass, double* acceleration) {
    (void)body, (void)mass, (void)acceleration;
  }
  /// Work put into the model (forces by curve, prescribed velocities) since the start.
  virtual double external_work() const { return 0.0; }
  /// Energy held in or dissipated by the interaction (penalty springs, friction).
  virtual double contact_energy() const { return 0.0; }
};

}  // namespace impactfe
