#include "explicit/central_difference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "explicit/explicit_loads.h"

namespace impactfe {

namespace {

/// Node n's sum of its slots of an element buffer (x, y, z per slot), in ascending slot order:
/// the same sum whatever split the element loop had.
inline void sum_slots(const ExplicitSystem& system, const double* buffer, std::size_t n, double& x,
                      double& y, double& z) {
  const std::size_t* slot = system.slots.data();
  double sx = 0.0, sy = 0.0, sz = 0.0;
  for (std::size_t j = system.slot_start[n]; j < system.slot_start[n + 1]; ++j) {
    const double* s = buffer + 3 * slot[j];
    sx += s[0];
    sy += s[1];
    sz += s[2];
  }
  x = sx;
  y = sy;
  z = sz;
}

}  // namespace

CentralDifference::CentralDifference(ExplicitSystem& system, const ExplicitControls& controls)
    : system_(system), controls_(controls) {
  const std::size_t n = system.n_nodes();
  x_ = system.x0;
  y_ = system.y0;
  z_ = system.z0;
  for (auto* v : {&vx_, &vy_, &vz_, &ax_, &ay_, &az_, &fx_, &fy_, &fz_}) v->assign(n, 0.0);
  fixed_.assign(3 * n, 0);
  element_forces_.assign(3 * system.n_slots, 0.0);
  if (system.has_rotations()) {
    for (auto* v : {&wx_, &wy_, &wz_, &rx_, &ry_, &rz_, &bx_, &by_, &bz_, &mx_, &my_, &mz_})
      v->assign(n, 0.0);
    element_moments_.assign(3 * system.n_slots, 0.0);
    fixed_rotation_.assign(3 * n, 0);
    rotational_.assign(n, 0);
    for (std::size_t r : system.rotational_nodes) rotational_[r] = 1;
  }
  for (const RigidBody& b : system.rigid_bodies)
    rigid_.push_back({b.centre0, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
}

void CentralDifference::set_rotation_fixes(std::vector<std::uint8_t> fixed) {
  if (!system_.has_rotations()) return;
  fixed_rotation_ = std::move(fixed);
  for (std::size_t i : system_.rotational_nodes) {
    if (fixed_rotation_[3 * i]) wx_[i] = bx_[i] = 0.0;
    if (fixed_rotation_[3 * i + 1]) wy_[i] = by_[i] = 0.0;
    if (fixed_rotation_[3 * i + 2]) wz_[i] = bz_[i] = 0.0;
  }
}

void CentralDifference::set_loads(std::vector<std::uint8_t> fixed, const Vec3& frame_acceleration) {
  fixed_ = std::move(fixed);
  frame_acceleration_ = frame_acceleration;
  for (std::size_t i = 0; i < system_.n_nodes(); ++i) {
    if (fixed_[3 * i]) vx_[i] = ax_[i] = 0.0;
    if (fixed_[3 * i + 1]) vy_[i] = ay_[i] = 0.0;
    if (fixed_[3 * i + 2]) vz_[i] = az_[i] = 0.0;
  }
}

void CentralDifference::set_velocity(std::size_t node, const Vec3& v) {
  vx_[node] = v.x();
  vy_[node] = v.y();
  vz_[node] = v.z();
}

void CentralDifference::set_angular_velocity(std::size_t node, const Vec3& w) {
  if (!has_rotations(node)) return;
  wx_[node] = w.x();
  wy_[node] = w.y();
  wz_[node] = w.z();
}

void CentralDifference::internal_forces(double dt) {
  const bool rotations = system_.has_rotations();
  const ExplicitNodalView view{x_.data(),
                               y_.data(),
                               z_.data(),
                               vx_.data(),
                               vy_.data(),
                               vz_.data(),
                               rotations ? wx_.data() : nullptr,
                               rotations ? wy_.data() : nullptr,
                               rotations ? wz_.data() : nullptr,
                               system_.mass.data()};
  ExplicitStepLimit limit;
  for (std::size_t i = 0; i < system_.sets.size(); ++i) {
    const std::size_t offset = 3 * system_.set_offset[i];
    const ExplicitStepLimit l = system_.sets[i]->internal_forces_and_moments(
        view, dt, element_forces_.data() + offset,
        rotations ? element_moments_.data() + offset : nullptr);
    limit.take(l.dt, l.element);
  }
  if (rotations) sum_moments();
  // Each node sums its slots in ascending slot order: the same sum whatever split the element
  // loop had (docs/explicit_dynamics.md, "Determinism").
  for (std::size_t n = 0; n < system_.n_nodes(); ++n)
    sum_slots(system_, element_forces_.data(), n, fx_[n], fy_[n], fz_[n]);
  // Loads by curve and contact at x_{n+1}, t_{n+1} (explicit_interaction.h).
  // An interaction's stiffness adds to the elements': the largest frequency of M⁻¹(K_e + K_c)
  // is at most √(ω_e² + ω_c²) (Weyl's inequality), so its step combines with the elements' as
  // 1/√(1/dt_e² + 1/dt_c²).
  const double elements = limit.dt;
  for (ExplicitInteraction* i : interactions_) {
    const ExplicitStepLimit l = i->add_forces(view, system_.mass.data(), time_ + dt, dt, fx_.data(),
                                              fy_.data(), fz_.data());
    if (l.dt < std::numeric_limits<double>::infinity())
      limit.take(1.0 / std::sqrt(1.0 / (elements * elements) + 1.0 / (l.dt * l.dt)), l.element);
  }
  controlling_ = limit.element;
  critical_ = limit.dt;
}

void CentralDifference::sum_moments() {
  // As the forces: each rotational node sums its slots in ascending order (slots of sets without
  // rotations hold zero moments).
  for (std::size_t n : system_.rotational_nodes)
    sum_slots(system_, element_moments_.data(), n, mx_[n], my_[n], mz_[n]);
}

void CentralDifference::choose_step() {
  const double dtms = controls_.mass_scaling_step;
  if (dtms > 0.0) {
    // Positive DTMS holds the step at TSSFAC·DTMS: an element whose stable step fell below DTMS
    // (distortion) gets mass now, so the next cycle's step is stable again.
    if (critical_ < dtms * (1.0 - 1e-9)) scale_masses();
    step_ = controls_.time_step_factor * dtms;
  } else {
    step_ = controls_.time_step_factor * critical_;
  }
}

double CentralDifference::mass_damping(double t) const {
  const auto& d = controls_.mass_damping;
  if (!d) return 0.0;
  if (d->curve == 0) return d->alpha;
  const ExplicitCurve& c = controls_.curves.at(d->curve);
  return curve_value(c.x, c.y, t);
}

void CentralDifference::accelerations() {
  const double* m = system_.mass.data();
  const std::uint8_t* fix = fixed_.data();
  // ACEL accelerates the reference frame: the body force on a node is −m a_frame.
  const double gx = -frame_acceleration_.x(), gy = -frame_acceleration_.y(),
               gz = -frame_acceleration_.z();
  // Mass-weighted damping (EDDAMP) at the integer time: a = f/m − α v_{n+1} with
  // v_{n+1} = v_{n+1/2} + (Δt/2) a, so a = (f/m − α v_{n+1/2}) / (1 + α Δt/2) (time-centred,
  // stable for any α).
  damping_ = mass_damping(time_);
  const double alpha = damping_, keep = 1.0 / (1.0 + 0.5 * alpha * previous_step_);
  for (std::size_t n = 0; n < system_.n_nodes(); ++n) {
    // A node without mass carries no element's DOFs (LINK160's orientation node K): it stays.
    const double inv = m[n] > 0.0 ? 1.0 / m[n] : 0.0;
    ax_[n] = fix[3 * n] ? 0.0 : (gx - fx_[n] * inv - alpha * vx_[n]) * keep;
    ay_[n] = fix[3 * n + 1] ? 0.0 : (gy - fy_[n] * inv - alpha * vy_[n]) * keep;
    az_[n] = fix[3 * n + 2] ? 0.0 : (gz - fz_[n] * inv - alpha * vz_[n]) * keep;
  }
  // Rotations: ω̇ = −m_int / I about global axes (a lumped isotropic rotary inertia, so the
  // gyroscopic term ω × Iω vanishes).
  const double* inertia = system_.inertia.data();
  const std::uint8_t* rfix = fixed_rotation_.data();
  for (std::size_t n : system_.rotational_nodes) {
    const double inv = inertia[n] > 0.0 ? 1.0 / inertia[n] : 0.0;
    bx_[n] = rfix[3 * n] ? 0.0 : (-mx_[n] * inv - alpha * wx_[n]) * keep;
    by_[n] = rfix[3 * n + 1] ? 0.0 : (-my_[n] * inv - alpha * wy_[n]) * keep;
    bz_[n] = rfix[3 * n + 2] ? 0.0 : (-mz_[n] * inv - alpha * wz_[n]) * keep;
  }
  if (!rigid_.empty()) rigid_accelerations();
  for (ExplicitInteraction* i : interactions_) i->hold(ax_.data(), ay_.data(), az_.data());
  if (system_.has_rotations())
    for (ExplicitInteraction* i : interactions_)
      i->hold_rotations(inertia, bx_.data(), by_.data(), bz_.data());
}

void CentralDifference::fit_rigid_velocities() {
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const RigidBody& body = system_.rigid_bodies[k];
    RigidMotion& r = rigid_[k];
    // The rigid motion nearest to the nodes' velocities, weighted by their masses: v_c = p/M
    // and ω = J_m⁻¹ L with p, L and J_m the momentum, angular momentum and inertia of the nodal
    // masses (so a rigid motion given at the nodes is kept exactly; about fixed axes ω = 0).
    Vec3 p = Vec3::Zero(), L = Vec3::Zero();
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      const Vec3 v(vx_[n], vy_[n], vz_[n]), q = body.offsets[j];
      const double m = system_.mass[n];
      p += m * v;
      L += m * q.cross(v);
      J += m * (q.squaredNorm() * Eigen::Matrix3d::Identity() - q * q.transpose());
    }
    r.velocity = p / body.mass;
    for (int i = 0; i < 3; ++i)
      if (body.fixed_translation[static_cast<std::size_t>(i)]) r.velocity(i) = 0.0;
    r.omega = rigid_angular_acceleration(J, L, body.fixed_rotation);
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      set_velocity(n, r.velocity + r.omega.cross(body.offsets[j]));
      set_angular_velocity(n, r.omega);
    }
  }
}

void CentralDifference::rigid_accelerations() {
  const Vec3 g = -frame_acceleration_;
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const RigidBody& body = system_.rigid_bodies[k];
    RigidMotion& r = rigid_[k];
    // The nodes' forces: the body force m g minus what the elements, contact and loads by curve
    // gathered (f = f_int − f_ext); the moments of shells sharing a node act on the body too.
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      const Vec3 f = system_.mass[n] * g - Vec3(fx_[n], fy_[n], fz_[n]);
      force += f;
      moment += (r.rotation * body.offsets[j]).cross(f);
      if (has_rotations(n)) moment -= Vec3(mx_[n], my_[n], mz_[n]);
    }
    // Mass-weighted damping acts on the centre of mass only (as accelerations(), time-centred).
    r.acceleration =
        (force / body.mass - damping_ * r.velocity) / (1.0 + 0.5 * damping_ * previous_step_);
    for (int i = 0; i < 3; ++i)
      if (body.fixed_translation[static_cast<std::size_t>(i)]) r.acceleration(i) = 0.0;
    // A centre velocity prescribed by curve (EDLOAD RBVX ...) is held.
    for (ExplicitInteraction* i : interactions_) i->hold_rigid(k, body.mass, r.acceleration.data());
    // Euler's equations in global axes: J α = m − ω × J ω, J = R J₀ Rᵀ (ω of the half step
    // before: the explicit gyroscopic term).
    const Eigen::Matrix3d J = r.rotation * body.inertia0 * r.rotation.transpose();
    r.alpha =
        rigid_angular_acceleration(J, moment - r.omega.cross(J * r.omega), body.fixed_rotation);
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      const Vec3 q = r.rotation * body.offsets[j];
      const Vec3 a = r.acceleration + r.alpha.cross(q) + r.omega.cross(r.omega.cross(q));
      ax_[n] = a.x();
      ay_[n] = a.y();
      az_[n] = a.z();
      if (has_rotations(n)) {
        bx_[n] = r.alpha.x();
        by_[n] = r.alpha.y();
        bz_[n] = r.alpha.z();
      }
    }
  }
}

void CentralDifference::move_rigid_bodies(double dt, double mean) {
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const RigidBody& body = system_.rigid_bodies[k];
    RigidMotion& r = rigid_[k];
    r.velocity += mean * r.acceleration;
    for (ExplicitInteraction* i : interactions_)
      i->prescribe_rigid(k, body.mass, mean, r.velocity.data());
    r.omega += mean * r.alpha;
    r.centre += dt * r.velocity;
    // R_{n+1} = exp(Δt ω̂) R_n: the rotation by the angle Δt|ω| about ω (Rodrigues).
    const double angle = dt * r.omega.norm();
    if (angle > 0.0)
      r.rotation = Eigen::AngleAxisd(angle, r.omega.normalized()).toRotationMatrix() * r.rotation;
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      const Vec3 x = r.centre + r.rotation * body.offsets[j];
      set_velocity(n, (x - Vec3(x_[n], y_[n], z_[n])) / dt);
      set_angular_velocity(n, r.omega);
    }
  }
}

void CentralDifference::place_rigid_nodes() {
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const RigidBody& body = system_.rigid_bodies[k];
    const RigidMotion& r = rigid_[k];
    for (std::size_t j = 0; j < body.nodes.size(); ++j) {
      const std::size_t n = body.nodes[j];
      const Vec3 x = r.centre + r.rotation * body.offsets[j];
      x_[n] = x.x();
      y_[n] = x.y();
      z_[n] = x.z();
    }
  }
}

double CentralDifference::mass_weighted_speed(double half, bool rigid_spin) const {
  double sum = 0.0;
  for (std::size_t n = 0; n < system_.n_nodes(); ++n) {
    if (system_.is_rigid(n)) continue;
    const double vx = vx_[n] + half * ax_[n], vy = vy_[n] + half * ay_[n],
                 vz = vz_[n] + half * az_[n];
    sum += system_.mass[n] * (vx * vx + vy * vy + vz * vz);
  }
  for (std::size_t r : system_.rotational_nodes) {
    if (system_.is_rigid(r)) continue;
    const double wx = wx_[r] + half * bx_[r], wy = wy_[r] + half * by_[r],
                 wz = wz_[r] + half * bz_[r];
    sum += system_.inertia[r] * (wx * wx + wy * wy + wz * wz);
  }
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const RigidBody& body = system_.rigid_bodies[k];
    const RigidMotion& r = rigid_[k];
    const Vec3 v = r.velocity + half * r.acceleration;
    sum += body.mass * v.squaredNorm();
    if (!rigid_spin) continue;
    const Vec3 w = r.omega + half * r.alpha;
    const Eigen::Matrix3d J = r.rotation * body.inertia0 * r.rotation.transpose();
    sum += w.dot(J * w);
  }
  return sum;
}

double CentralDifference::kinetic_energy(double half) const {
  return 0.5 * mass_weighted_speed(half, true);
}

double CentralDifference::damping_power(double half) const {
  // A rigid body is damped in its translation only (rigid_accelerations).
  return damping_ * mass_weighted_speed(half, false);
}

bool CentralDifference::scale_masses() {
  const double target = std::abs(controls_.mass_scaling_step);
  if (!(target > 0.0)) return false;
  const ExplicitNodalView view{x_.data(),  y_.data(), z_.data(), vx_.data(), vy_.data(),
                               vz_.data(), nullptr,   nullptr,   nullptr,    system_.mass.data()};
  bool any = false;
  for (auto& set : system_.sets)
    for (std::size_t k = 0; k < set->size(); ++k) {
      const double dt = set->element_step(view, k);
      // The stable step goes as 1/√ρ: ρ (target/dt)² brings it to the target.
      if (dt < target) {
        added_mass_ += set->scale_mass(k, (target / dt) * (target / dt), system_.mass);
        any = true;
      }
    }
  if (any) system_.update_inertia();  // the rotary inertia follows the scaled densities
  return any;
}

void CentralDifference::start() {
  scale_masses();
  fit_rigid_velocities();
  internal_forces(0.0);
  choose_step();
  accelerations();
  initial_kinetic_ = kinetic_energy(0.0);
  previous_step_ = 0.0;
}

void CentralDifference::cycle(double dt) {
  const double mean = 0.5 * (previous_step_ + dt);
  const std::size_t n_nodes = system_.n_nodes();
  // The damping force at t_n acts over the mean step around it (the velocities' interval).
  if (damping_ > 0.0) damping_work_ += mean * damping_power(0.5 * previous_step_);
  double work = 0.0;
  const double* m = system_.mass.data();
  const double gx = -frame_acceleration_.x(), gy = -frame_acceleration_.y(),
               gz = -frame_acceleration_.z();
  for (std::size_t n = 0; n < n_nodes; ++n) {
    vx_[n] += mean * ax_[n];
    vy_[n] += mean * ay_[n];
    vz_[n] += mean * az_[n];
  }
  for (ExplicitInteraction* i : interactions_)
    i->prescribe(time_ + 0.5 * dt, mean, m, vx_.data(), vy_.data(), vz_.data());
  if (!rigid_.empty()) move_rigid_bodies(dt, mean);
  for (std::size_t n = 0; n < n_nodes; ++n) {
    x_[n] += dt * vx_[n];
    y_[n] += dt * vy_[n];
    z_[n] += dt * vz_[n];
    work += m[n] * (gx * vx_[n] + gy * vy_[n] + gz * vz_[n]);
  }
  if (!rigid_.empty()) place_rigid_nodes();
  external_work_ += dt * work;  // f_ext constant over the step: f·Δx (fixed DOFs: v = 0)
  // Rotations: the same half-step update of ω; the rotation is the sum of the increments Δt ω
  // in global axes (output only: the shells work from ω and their current frame).
  for (std::size_t r : system_.rotational_nodes)
    if (!system_.is_rigid(r)) {  // a rigid body's nodes turn with it (move_rigid_bodies)
      wx_[r] += mean * bx_[r];
      wy_[r] += mean * by_[r];
      wz_[r] += mean * bz_[r];
    }
  if (system_.has_rotations())
    for (ExplicitInteraction* i : interactions_)
      i->prescribe_rotations(mean, system_.inertia.data(), wx_.data(), wy_.data(), wz_.data());
  for (std::size_t r : system_.rotational_nodes) {
    rx_[r] += dt * wx_[r];
    ry_[r] += dt * wy_[r];
    rz_[r] += dt * wz_[r];
  }
  internal_forces(dt);
  choose_step();
  previous_step_ = dt;
  time_ += dt;
  accelerations();
  ++cycles_;
}

ExplicitEnergies CentralDifference::energies() const {
  ExplicitEnergies e;
  e.kinetic = kinetic_energy(0.5 * previous_step_);
  for (const auto& set : system_.sets) {
    const ExplicitSetEnergies s = set->energies();
    e.internal += s.internal;
    e.hourglass += s.hourglass;
    e.plastic_work += s.plastic_work;
  }
  e.external_work = external_work_;
  for (const ExplicitInteraction* i : interactions_) {
    e.external_work += i->external_work();
    e.contact += i->contact_energy();
  }
  e.damping = damping_work_;
  e.initial_kinetic = initial_kinetic_;
  return e;
}

Vec3 CentralDifference::displacement(std::size_t n) const {
  return {x_[n] - system_.x0[n], y_[n] - system_.y0[n], z_[n] - system_.z0[n]};
}

Vec3 CentralDifference::velocity(std::size_t n) const {
  const double half = 0.5 * previous_step_;
  return {vx_[n] + half * ax_[n], vy_[n] + half * ay_[n], vz_[n] + half * az_[n]};
}

Vec3 CentralDifference::acceleration(std::size_t n) const {
  return {ax_[n], ay_[n], az_[n]};
}

Vec3 CentralDifference::reaction(std::size_t n) const {
  // f_int − f_ext at a fixed DOF (the body force −m a_frame is external).
  const double m = system_.mass[n];
  return {fx_[n] + m * frame_acceleration_.x(), fy_[n] + m * frame_acceleration_.y(),
          fz_[n] + m * frame_acceleration_.z()};
}

Vec3 CentralDifference::rotation(std::size_t n) const {
  if (!has_rotations(n)) return Vec3::Zero();
  return {rx_[n], ry_[n], rz_[n]};
}

Vec3 CentralDifference::angular_velocity(std::size_t n) const {
  if (!has_rotations(n)) return Vec3::Zero();
  const double half = 0.5 * previous_step_;
  return {wx_[n] + half * bx_[n], wy_[n] + half * by_[n], wz_[n] + half * bz_[n]};
}

Vec3 CentralDifference::angular_acceleration(std::size_t n) const {
  if (!has_rotations(n)) return Vec3::Zero();
  return {bx_[n], by_[n], bz_[n]};
}

Vec3 CentralDifference::moment_reaction(std::size_t n) const {
  if (!has_rotations(n)) return Vec3::Zero();
  return {mx_[n], my_[n], mz_[n]};  // no external moments: the internal moment
}

}  // namespace impactfe
