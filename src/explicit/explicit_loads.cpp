#include "explicit/explicit_loads.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "elements/face_pressure.h"

namespace impactfe {

double curve_value(const std::vector<double>& x, const std::vector<double>& y, double t) {
  if (t <= x.front()) return y.front();
  if (t >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - x.begin());
  const double s = (t - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + s * (y[i] - y[i - 1]);
}

ExplicitCurveLoads::ExplicitCurveLoads(const ExplicitSystem& system,
                                       const ExplicitControls& controls) {
  const auto index = [&](const ExplicitCurveLoad& l, int node) {
    const int n = system.index_of(node);
    if (n < 0)
      throw InputError(l.where, fmt::format("EDLOAD {} on {}: node {} carries no explicit element",
                                            l.label, l.component, node));
    return static_cast<std::size_t>(n);
  };
  for (const ExplicitCurveLoad& l : controls.loads) {
    if (l.label == "PRESS") {
      Pressure p{&l, {}, {}};
      for (int node : l.nodes) p.nodes.push_back(index(l, node));
      p.previous.assign(3 * p.nodes.size(), 0.0);
      pressures_.push_back(std::move(p));
      continue;
    }
    // ACLX/ACLY/ACLZ accelerate the base (as ACEL): each node feels the body force −m a.
    const bool base = l.label.rfind("ACL", 0) == 0;
    const bool rigid = l.label.rfind("RB", 0) == 0;
    const char kind = rigid ? l.label[2] : l.label[0];  // F, M, V, U, A(CL)
    // ROTX.. and OMGX..: the rotation and angular velocity of a node with rotational DOFs.
    const bool rotational = !rigid && (kind == 'R' || kind == 'O');
    const bool prescribed = kind == 'V' || kind == 'U' || rotational;
    Entry e{.load = &l,
            .direction = l.label.back() - 'X',
            .per_mass = base,
            .displacement = kind == 'U' || (rotational && kind == 'R'),
            .active = prescribed && l.birth <= 0.0};
    if (rigid) {
      // A force on the centre of mass: m_i/M of it on each node of the body has no moment
      // about the centre (Σ m_i r_i = 0), so the body's Newton–Euler equations see F alone.
      int body = -1;
      for (int node : l.nodes) {
        const std::size_t n = index(l, node);
        const int b = system.is_rigid(n) ? system.rigid_body_of[n] : -1;
        if (b < 0 || (body >= 0 && b != body))
          throw InputError(l.where, fmt::format("EDLOAD {} on part {}: node {} is not a node of "
                                                "the part's rigid body",
                                                l.label, l.component, node));
        body = b;
      }
      const RigidBody& b = system.rigid_bodies[static_cast<std::size_t>(body)];
      // EDCRB: the slave body takes the master's loading; a load of its own is refused rather
      // than silently moved to the merged body.
      if (l.part_material != 0 && l.part_material != b.material)
        throw InputError(l.where, fmt::format("EDLOAD {} on part {}: EDCRB merges its rigid body "
                                              "(material {}) into that of material {}; load the "
                                              "master part",
                                              l.label, l.component, l.part_material, b.material));
      if (prescribed) {
        // The motion of the centre: the body's own state, driven in prescribe_rigid().
        if (b.fixed_translation[static_cast<std::size_t>(e.direction)])
          throw InputError(l.where, fmt::format("EDLOAD {} on part {}: EDMP,RIGID,{} fixes that "
                                                "translation of the body",
                                                l.label, l.component, b.material));
        e.body = static_cast<std::size_t>(body);
        e.held.assign(1, 0.0);
        rigid_motions_.push_back(std::move(e));
        continue;
      }
      e.nodes = b.nodes;
      for (std::size_t n : e.nodes) e.body_mass += system.mass[n];
      if (kind == 'M') {
        e.moment = true;
        e.previous.assign(3 * e.nodes.size(), 0.0);
        forces_.push_back(std::move(e));
        continue;
      }
    } else {
      for (int node : l.nodes) e.nodes.push_back(index(l, node));
    }
    e.previous.assign(e.nodes.size(), 0.0);
    e.held.assign(e.nodes.size(), 0.0);
    if (rotational)
      for (int node : l.nodes)
        if (!std::binary_search(system.rotational_nodes.begin(), system.rotational_nodes.end(),
                                index(l, node)))
          throw InputError(l.where, fmt::format("EDLOAD {} on {}: node {} has no rotational "
                                                "DOFs (those of SHELL163 and BEAM161 nodes)",
                                                l.label, l.component, node));
    (rotational ? rotations_ : prescribed ? velocities_ : forces_).push_back(std::move(e));
  }
}

double ExplicitCurveLoads::value(const ExplicitCurveLoad& l, double time) const {
  if (time < l.birth || (l.death > 0.0 && time > l.death)) return 0.0;
  return l.scale * curve_value(l.times, l.values, time - l.birth);
}

double ExplicitCurveLoads::prescribed_velocity(const Entry& e) const {
  // A prescribed displacement u(t) moves the DOF by u(t_{n+1}) − u(t_n) over the step: the
  // half-step velocity of its differences, so that x = X + u(t) at the integer times.
  if (e.displacement)
    return (this->value(*e.load, integer_time_) - this->value(*e.load, integer_time_ - step_)) /
           step_;
  return this->value(*e.load, integer_time_ - 0.5 * step_);
}

ExplicitStepLimit ExplicitCurveLoads::add_forces(const ExplicitNodalView& state, const double* mass,
                                                 double time, double dt, double* fx, double* fy,
                                                 double* fz) {
  double* f[3] = {fx, fy, fz};
  const double* v[3] = {state.vx, state.vy, state.vz};
  for (Entry& e : forces_) {
    if (e.moment) {
      add_rigid_moment(e, state, mass, time, dt, fx, fy, fz);
      continue;
    }
    const double curve = this->value(*e.load, time);
    for (std::size_t j = 0; j < e.nodes.size(); ++j) {
      const std::size_t n = e.nodes[j];
      const double value = e.per_mass          ? -mass[n] * curve
                           : e.body_mass > 0.0 ? mass[n] / e.body_mass * curve
                                               : curve;
      // Work over the step by the trapezoidal rule: ½(f_n + f_{n+1})·Δx, Δx = dt v_{n+1/2}.
      work_ += 0.5 * (e.previous[j] + value) * dt * v[e.direction][n];
      e.previous[j] = value;
      f[e.direction][n] -= value;  // an external force: f_int sign
    }
  }
  for (Pressure& p : pressures_) add_pressure(p, state, time, dt, fx, fy, fz);
  return {};
}

void ExplicitCurveLoads::add_rigid_moment(Entry& e, const ExplicitNodalView& s, const double* mass,
                                          double time, double dt, double* fx, double* fy,
                                          double* fz) {
  // A moment M on the body as nodal forces F_i = m_i α × q_i about the centre of the nodal
  // masses c (q_i = x_i − c) with J_m α = M, J_m = Σ m_i (|q_i|² 1 − q_i q_iᵀ): their moment
  // Σ q_i × F_i = J_m α = M and their sum α × Σ m_i q_i = 0, so the body's Newton–Euler
  // equations see M alone, whatever its own inertia.
  Vec3 moment = Vec3::Zero();
  moment(e.direction) = this->value(*e.load, time);
  Vec3 centre = Vec3::Zero();
  for (std::size_t n : e.nodes) centre += mass[n] * Vec3(s.x[n], s.y[n], s.z[n]);
  centre /= e.body_mass;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t n : e.nodes) {
    const Vec3 q = Vec3(s.x[n], s.y[n], s.z[n]) - centre;
    inertia += mass[n] * (q.squaredNorm() * Eigen::Matrix3d::Identity() - q * q.transpose());
  }
  const Vec3 alpha = rigid_angular_acceleration(inertia, moment, {false, false, false});
  double* f[3] = {fx, fy, fz};
  const double* v[3] = {s.vx, s.vy, s.vz};
  for (std::size_t j = 0; j < e.nodes.size(); ++j) {
    const std::size_t n = e.nodes[j];
    const Vec3 force = mass[n] * alpha.cross(Vec3(s.x[n], s.y[n], s.z[n]) - centre);
    for (int d = 0; d < 3; ++d) {
      double& previous = e.previous[3 * j + static_cast<std::size_t>(d)];
      // Work over the step by the trapezoidal rule, as the forces'.
      work_ += 0.5 * (previous + force(d)) * dt * v[d][n];
      previous = force(d);
      f[d][n] -= force(d);
    }
  }
}

void ExplicitCurveLoads::add_pressure(Pressure& p, const ExplicitNodalView& s, double time,
                                      double dt, double* fx, double* fy, double* fz) {
  const double pressure = this->value(*p.load, time);
  double* f[3] = {fx, fy, fz};
  const double* v[3] = {s.vx, s.vy, s.vz};
  for (std::size_t k = 0; 4 * k < p.nodes.size(); ++k) {
    const std::size_t* n = &p.nodes[4 * k];
    std::array<Vec3, 4> x;
    for (std::size_t a = 0; a < 4; ++a) x[a] = Vec3(s.x[n[a]], s.y[n[a]], s.z[n[a]]);
    // A follower load on the face at x_{n+1}: f_a = p ∫ N_a (∂x/∂ξ × ∂x/∂η) dξ dη (exact for
    // the bilinear face); a triangle (a corner repeated) gives p A n / 3 to each corner.
    std::array<Vec3, 4> force;
    int skip = -1;
    for (int a = 0; a < 4; ++a)
      if (n[a] == n[(a + 3) % 4]) skip = a;
    if (skip >= 0) {
      std::size_t c[3], m = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) c[m++] = static_cast<std::size_t>(a);
      const Vec3 share = pressure / 6.0 * (x[c[1]] - x[c[0]]).cross(x[c[2]] - x[c[0]]);
      force.fill(share);
      force[static_cast<std::size_t>(skip)] = Vec3::Zero();
    } else {
      force = bilinear_face_pressure_forces(x, {pressure, pressure, pressure, pressure});
    }
    double* previous = &p.previous[12 * k];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        const double value = force[static_cast<std::size_t>(a)](d);
        // Work over the step by the trapezoidal rule: ½(f_n + f_{n+1})·Δx, Δx = dt v_{n+1/2}.
        work_ += 0.5 * (previous[3 * a + d] + value) * dt * v[d][n[a]];
        previous[3 * a + d] = value;
        f[d][n[a]] -= value;  // an external force: f_int sign
      }
  }
}

void ExplicitCurveLoads::prescribe(double time, double mean, const double* mass, double* vx,
                                   double* vy, double* vz) {
  // `time` is t_{n+1/2} = t_n + ½dt_{n+1/2}: the step about to be taken is 2(t_{n+1/2} − t_n).
  step_ = 2.0 * (time - integer_time_);
  integer_time_ += step_;
  mass_ = mass;
  double* v[3] = {vx, vy, vz};
  drive(velocities_, mean, mass, v);
}

void ExplicitCurveLoads::prescribe_rotations(double mean, const double* inertia, double* wx,
                                             double* wy, double* wz) {
  double* w[3] = {wx, wy, wz};
  drive(rotations_, mean, inertia, w);
}

void ExplicitCurveLoads::drive(std::vector<Entry>& entries, double mean, const double* mass,
                               double* v[3]) {
  const double time = integer_time_ - 0.5 * step_;
  for (Entry& e : entries) {
    const bool held = e.active;  // its accelerations were zeroed at the last hold
    e.active = time >= e.load->birth && !(e.load->death > 0.0 && time > e.load->death);
    if (!e.active) continue;
    const double value = prescribed_velocity(e);
    e.current = value;
    for (std::size_t j = 0; j < e.nodes.size(); ++j) {
      const std::size_t n = e.nodes[j];
      // The constraint's work: what it changes the DOF's kinetic energy by, ½m(v_p² − v_old²),
      // here; the work against the other forces on it over the step, in hold().
      double& u = v[e.direction][n];
      const double old = held ? u : u - mean * e.held[j];
      work_ += 0.5 * mass[n] * (value * value - old * old);
      u = value;
    }
  }
}

void ExplicitCurveLoads::hold(double* ax, double* ay, double* az) {
  double* a[3] = {ax, ay, az};
  release(velocities_, mass_, a);
}

void ExplicitCurveLoads::hold_rotations(const double* inertia, double* bx, double* by, double* bz) {
  double* b[3] = {bx, by, bz};
  release(rotations_, inertia, b);
}

void ExplicitCurveLoads::release(std::vector<Entry>& entries, const double* mass, double* a[3]) {
  for (Entry& e : entries)
    for (std::size_t j = 0; j < e.nodes.size(); ++j) {
      double& u = a[e.direction][e.nodes[j]];
      // Held over the step just taken (Δx = dt v_p), the DOF had the other forces m a_free
      // (elements, contact, loads) against it: the constraint did minus their work, by the
      // trapezoidal rule as the forces' (½m(a_n + a_{n+1})·Δx), so that the work put in up to
      // t_{n+1} is there when the energies of t_{n+1} are taken. (The impulse m(v_p − v_free)
      // at the mean velocity instead credits half a step late or early.)
      if (e.active && mass) work_ -= 0.5 * mass[e.nodes[j]] * (e.held[j] + u) * step_ * e.current;
      e.held[j] = u;
      if (e.active) u = 0.0;
    }
}

void ExplicitCurveLoads::prescribe_rigid(std::size_t body, double mass, double mean,
                                         double* velocity) {
  // As prescribe() for a node, with the body's mass and centre velocity (called after it: the
  // step and t_{n+1} are this cycle's).
  const double time = integer_time_ - 0.5 * step_;
  for (Entry& e : rigid_motions_) {
    if (e.body != body) continue;
    const bool held = e.active;
    e.active = time >= e.load->birth && !(e.load->death > 0.0 && time > e.load->death);
    if (!e.active) continue;
    const double value = prescribed_velocity(e);
    e.current = value;
    double& u = velocity[e.direction];
    const double old = held ? u : u - mean * e.held[0];
    work_ += 0.5 * mass * (value * value - old * old);
    u = value;
  }
}

void ExplicitCurveLoads::hold_rigid(std::size_t body, double mass, double* acceleration) {
  for (Entry& e : rigid_motions_) {
    if (e.body != body) continue;
    double& u = acceleration[e.direction];
    // The work against the body's other forces over the step just taken, as hold().
    if (e.active && step_ > 0.0) work_ -= 0.5 * mass * (e.held[0] + u) * step_ * e.current;
    e.held[0] = u;
    if (e.active) u = 0.0;
  }
}

}  // namespace impactfe
