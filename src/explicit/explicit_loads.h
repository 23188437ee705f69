#pragma once
/// Loads by curve of an explicit run (EDLOAD; docs/explicit_dynamics.md): nodal forces FX, FY,
/// FZ, base accelerations ACLX, ACLY, ACLZ (the body force −m a on each node), prescribed
/// velocities VX, VY, VZ and displacements UX, UY, UZ on the nodes of a component, pressures
/// (PRESS) on element faces, forces on the centre of mass of a rigid body (RBFX, RBFY, RBFZ)
/// and its prescribed velocity or displacement (RBVX.., RBUX..) or a moment on it (RBMX..), valued
/// by a curve of time: linear between its points, held at the first before it and at the last
/// beyond it (as LS-DYNA's load curves), times SCALE, active between BTIME and DTIME.
#include <vector>

#include "core/explicit_controls.h"
#include "explicit/explicit_interaction.h"
#include "explicit/explicit_system.h"

namespace impactfe {

/// The value of a curve (abscissae increasing) at `t`: linear interpolation, constant beyond
/// the ends.
double curve_value(const std::vector<double>& x, const std::vector<double>& y, double t);

class ExplicitCurveLoads final : public ExplicitInteraction {
 public:
  /// The loads of `controls` on the nodes of `system` (InputError at the EDLOAD for a node that
  /// carries no explicit element).
  ExplicitCurveLoads(const ExplicitSystem& system, const ExplicitControls& controls);
  bool empty() const {
    return forces_.empty() && velocities_.empty() && pressures_.empty() && rigid_motions_.empty() &&
           rotations_.empty();
  }

  ExplicitStepLimit add_forces(const ExplicitNodalView& state, const double* mass, double time,
                               double dt, double* fx, double* fy, double* fz) override;
  void prescribe(double time, double mean, const double* mass, double* vx, double* vy,
                 double* vz) override;
  void hold(double* ax, double* ay, double* az) override;
  void prescribe_rotations(double mean, const double* inertia, double* wx, double* wy,
                           double* wz) override;
  void hold_rotations(const double* inertia, double* bx, double* by, double* bz) override;
  void prescribe_rigid(std::size_t body, double mass, double mean, double* velocity) override;
  void hold_rigid(std::size_t body, double mass, double* acceleration) override;
  double external_work() const override { return work_; }

 private:
  struct Entry {
    const ExplicitCurveLoad* load;
    int direction;                   // 0 x, 1 y, 2 z
    bool per_mass = false;           // ACLX..: the body force −m a of a base acceleration
    bool displacement = false;       // UX..: the velocity from the curve's differences
    double body_mass = 0.0;          // RBFX..: the rigid body's mass (its nodes take m_i/M)
    std::size_t body = 0;            // RBVX.., RBUX..: the rigid body whose centre is driven
    bool moment = false;             // RBMX..: a moment on the rigid body (3 forces per node)
    std::vector<std::size_t> nodes;  // run indices
    std::vector<double> previous;    // force at t_n of each node (trapezoidal work)
    std::vector<double> held;        // prescribed: the acceleration the forces would give
    bool active = false;             // a velocity prescribed at the last half step
    double current = 0.0;            // the velocity prescribed at the last half step
  };
  /// PRESS: faces of 4 run node indices (a triangle repeats one), the pressure acting along
  /// the right-hand normal of that order.
  struct Pressure {
    const ExplicitCurveLoad* load;
    std::vector<std::size_t> nodes;  // 4 per face
    std::vector<double> previous;    // 12 per face: the nodal forces at t_n (trapezoidal work)
  };
  double value(const ExplicitCurveLoad& l, double time) const;
  /// The prescribed velocity of a motion entry over the step to t_{n+1} = integer_time_ (the
  /// curve's value at t_{n+1/2}, or the displacement's difference over the step).
  double prescribed_velocity(const Entry& e) const;
  /// Adds the nodal forces of a moment on a rigid body (RBMX ..) at x_{n+1} and their work.
  void add_rigid_moment(Entry& e, const ExplicitNodalView& state, const double* mass, double time,
                        double dt, double* fx, double* fy, double* fz);
  /// Adds the forces of a pressure entry at x_{n+1} and their work over the step.
  void add_pressure(Pressure& p, const ExplicitNodalView& state, double time, double dt, double* fx,
                    double* fy, double* fz);
  std::vector<Entry> forces_, velocities_;
  std::vector<Entry> rigid_motions_;
  std::vector<Entry> rotations_;  // ROTX.., OMGX..: prescribed rotations of shell, beam nodes
  /// Prescribes the half-step velocities of `entries` (v: x, y, z arrays; `mass` the inertia)
  /// and counts the work; release() zeroes their accelerations after keeping them.
  void drive(std::vector<Entry>& entries, double mean, const double* mass, double* v[3]);
  void release(std::vector<Entry>& entries, const double* mass,
               double* a[3]);  // RBVX.., RBUX..: prescribed motion of a body's centre
  std::vector<Pressure> pressures_;
  double work_ = 0.0;
  double integer_time_ = 0.0;     // t_{n+1} after prescribe() at t_{n+1/2}
  double step_ = 0.0;             // dt_{n+1/2}, the step after the last prescribe()
  const double* mass_ = nullptr;  // the nodal masses prescribe() was given
};

}  // namespace impactfe
