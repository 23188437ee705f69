#pragma once
/// The central-difference cycle of explicit dynamics with half-step velocities (LS-DYNA theory
/// manual, "Time integration"; Belytschko, Liu & Moran, Nonlinear Finite Elements, Box 6.1):
///   v_{n+1/2} = v_{n−1/2} + ½(Δt_{n−1/2} + Δt_{n+1/2}) a_n,   x_{n+1} = x_n + Δt_{n+1/2}
///   v_{n+1/2}, a_{n+1} = M⁻¹ (f_ext − f_int(x_{n+1}, v_{n+1/2})),
/// M the lumped mass: no matrix, no factorisation, nothing allocated per cycle. The stable step
/// of every element is recomputed each cycle at x_{n+1}; the next step is TSSFAC times the
/// smallest. Fixed DOFs (D, value 0) keep v = a = 0. State is structure of arrays.
#include <cstdint>
#include <vector>

#include "core/explicit_controls.h"
#include "explicit/explicit_interaction.h"
#include "explicit/explicit_system.h"

namespace impactfe {

/// The energy balance of an explicit run since its start.
struct ExplicitEnergies {
  double kinetic = 0.0;  // ½ Σ m v² at the integer time (v_{n+1/2} + ½Δt a_{n+1})
  double internal = 0.0;
  double hourglass = 0.0;
  double plastic_work = 0.0;
  double external_work = 0.0;  // work of f_ext (ACEL, EDLOAD) on the motion
  double contact = 0.0;        // penalty springs and friction (EDCGEN)
  double damping = 0.0;        // work of the mass-weighted damping (EDDAMP), dissipated
  double initial_kinetic = 0.0;
  /// Total minus what was put in: zero for an exact balance.
  double drift() const {
    return kinetic + internal + hourglass + contact + damping - initial_kinetic - external_work;
  }
  double put_in() const { return initial_kinetic + external_work; }
};

class CentralDifference {
 public:
  CentralDifference(ExplicitSystem& system, const ExplicitControls& controls);

  /// The DOFs fixed (3 per node, x y z) and the frame acceleration (ACEL: body force −m a on
  /// every node) of the current load step.
  void set_loads(std::vector<std::uint8_t> fixed, const Vec3& frame_acceleration);
  /// The rotations fixed (3 per node, about x y z) of the current load step; entries of nodes
  /// without rotational DOFs are ignored. Only for a system with rotations.
  void set_rotation_fixes(std::vector<std::uint8_t> fixed);
  /// Forces beyond the elements' (explicit_interaction.h), evaluated in the order added; the
  /// interaction must outlive the run.
  void add_interaction(ExplicitInteraction* interaction) { interactions_.push_back(interaction); }
  /// Initial velocities (before start()).
  void set_velocity(std::size_t node, const Vec3& v);
  /// Initial angular velocity of a node with rotational DOFs (before start()).
  void set_angular_velocity(std::size_t node, const Vec3& w);
  /// Forces and accelerations at t = 0 and the first stable step; mass scaling at the start.
  void start();
  /// One cycle of step `dt` (at most stable_step(): the caller may shorten it to land on an end
  /// time).
  void cycle(double dt);

  double time() const { return time_; }
  long cycles() const { return cycles_; }
  /// TSSFAC × the smallest element step at the current configuration (or the mass-scaled step).
  double stable_step() const { return step_; }
  int controlling_element() const { return controlling_; }
  double added_mass() const { return added_mass_; }
  ExplicitEnergies energies() const;
  /// Nodal displacement, velocity (integer time), acceleration of a node; reaction at a fixed
  /// DOF (f_int − f_ext, the support's force on the structure with the opposite sign).
  Vec3 displacement(std::size_t n) const;
  Vec3 velocity(std::size_t n) const;
  Vec3 acceleration(std::size_t n) const;
  Vec3 reaction(std::size_t n) const;
  bool fixed(std::size_t n, int direction) const { return fixed_[3 * n + direction] != 0; }
  /// Rotational DOFs (nodes of a set with rotations): the rotation (the sum of the increments
  /// Δt ω in global axes), angular velocity and acceleration, the moment reaction at a fixed
  /// rotation. Zero at nodes without rotations.
  bool has_rotations(std::size_t n) const { return !rotational_.empty() && rotational_[n] != 0; }
  Vec3 rotation(std::size_t n) const;
  Vec3 angular_velocity(std::size_t n) const;
  Vec3 angular_acceleration(std::size_t n) const;
  Vec3 moment_reaction(std::size_t n) const;
  bool rotation_fixed(std::size_t n, int axis) const {
    return !fixed_rotation_.empty() && fixed_rotation_[3 * n + axis] != 0;
  }

 private:
  /// f_int from the element sets at (x, v) over dt, gathered per node in fixed order.
  void internal_forces(double dt);
  void accelerations();
  /// The nodal moments of the sets with rotations, gathered like the forces.
  void sum_moments();
  /// The next step from the critical one (and mass scaling under a positive DTMS).
  void choose_step();
  /// Mass scaling (EDCTS DTMS): adds mass to the elements whose stable step is below the
  /// target; returns whether any was added.
  bool scale_masses();
  /// Rigid bodies (rigid_body.h): the body velocities nearest to the nodes' initial ones (the
  /// nodes then move with the body).
  void fit_rigid_velocities();
  /// Newton–Euler accelerations of the bodies from the forces of their nodes, and the nodes'
  /// accelerations that follow.
  void rigid_accelerations();
  /// The half-step update of the bodies; the velocity of each node of a body becomes its chord
  /// velocity (x_{n+1} − x_n)/Δt, so that x += Δt v lands on c + R r.
  void move_rigid_bodies(double dt, double mean);
  /// Puts the nodes of the bodies exactly on c + R r.
  void place_rigid_nodes();
  /// Σ m v·v (and I ω·ω at rotational DOFs) at v_{n+1/2} + half·a_n; rigid bodies give
  /// M v_c·v_c, plus ωᵀ J ω with `rigid_spin`.
  double mass_weighted_speed(double half, bool rigid_spin) const;
  /// ½ Σ m v² at v_{n+1/2} + half·a_n (rigid bodies: ½ M v_c² + ½ ωᵀ J ω).
  double kinetic_energy(double half) const;
  /// α of the mass-weighted damping (EDDAMP) at time t; 0 without it.
  double mass_damping(double t) const;
  /// Σ α m v·v at the integer time (v_{n+1/2} + half·a_n): the power the damping dissipates
  /// (deformable nodes, rotations, rigid bodies' centres).
  double damping_power(double half) const;

  ExplicitSystem& system_;
  ExplicitControls controls_;
  std::vector<double> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_, fx_, fy_, fz_;
  Vec3 frame_acceleration_ = Vec3::Zero();
  std::vector<double> element_forces_;
  std::vector<std::uint8_t> fixed_;
  // Rotational DOFs: allocated only when a set has rotations; the loops visit only
  // system_.rotational_nodes.
  std::vector<double> wx_, wy_, wz_, rx_, ry_, rz_, bx_, by_, bz_, mx_, my_, mz_;
  std::vector<double> element_moments_;
  std::vector<std::uint8_t> fixed_rotation_, rotational_;
  std::vector<ExplicitInteraction*> interactions_;
  struct RigidMotion {
    Vec3 centre, velocity, acceleration, omega, alpha;  // ω, α in global axes
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  };
  std::vector<RigidMotion> rigid_;  // per system_.rigid_bodies
  double critical_ = 0.0;           // the smallest element step at the current configuration
  double time_ = 0.0, step_ = 0.0, previous_step_ = 0.0, added_mass_ = 0.0;
  double external_work_ = 0.0, initial_kinetic_ = 0.0;
  double damping_ = 0.0;  // α of the accelerations a_n (EDDAMP)
  double damping_work_ = 0.0;
  int controlling_ = 0;
  long cycles_ = 0;
};

}  // namespace impactfe
