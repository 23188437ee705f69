#include "explicit/explicit_loads.h"

#include <fmt/format.h>

#include <algorithm>

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
  for (const ExplicitCurveLoad& l : controls.loads) {
    // ACLX/ACLY/ACLZ accelerate the base (as ACEL): each node feels the body force −m a.
    const bool base = l.label.rfind("ACL", 0) == 0;
    Entry e{&l, l.label.back() - 'X', base, {}, {}, {}, l.label[0] == 'V' && l.birth <= 0.0};
    for (int node : l.nodes) {
      const int n = system.index_of(node);
      if (n < 0)
        throw InputError(l.where, fmt::format("EDLOAD {} on {}: node {} carries no explicit "
                                              "element",
                                              l.label, l.component, node));
      e.nodes.push_back(static_cast<std::size_t>(n));
    }
    e.previous.assign(e.nodes.size(), 0.0);
    e.held.assign(e.nodes.size(), 0.0);
    (l.label[0] == 'V' ? velocities_ : forces_).push_back(std::move(e));
  }
}

double ExplicitCurveLoads::value(const ExplicitCurveLoad& l, double time) const {
  if (time < l.birth || (l.death > 0.0 && time > l.death)) return 0.0;
  return l.scale * curve_value(l.times, l.values, time - l.birth);
}

ExplicitStepLimit ExplicitCurveLoads::add_forces(const ExplicitNodalView& state, const double* mass,
                                                 double time, double dt, double* fx, double* fy,
                                                 double* fz) {
  double* f[3] = {fx, fy, fz};
  const double* v[3] = {state.vx, state.vy, state.vz};
  for (Entry& e : forces_) {
    const double curve = this->value(*e.load, time);
    for (std::size_t j = 0; j < e.nodes.size(); ++j) {
      const std::size_t n = e.nodes[j];
      const double value = e.per_mass ? -mass[n] * curve : curve;
      // Work over the step by the trapezoidal rule: ½(f_n + f_{n+1})·Δx, Δx = dt v_{n+1/2}.
      work_ += 0.5 * (e.previous[j] + value) * dt * v[e.direction][n];
      e.previous[j] = value;
      f[e.direction][n] -= value;  // an external force: f_int sign
    }
  }
  return {};
}

void ExplicitCurveLoads::prescribe(double time, double mean, const double* mass, double* vx,
                                   double* vy, double* vz) {
  // `time` is t_{n+1/2} = t_n + ½dt_{n+1/2}: the step about to be taken is 2(t_{n+1/2} − t_n).
  step_ = 2.0 * (time - integer_time_);
  integer_time_ += step_;
  mass_ = mass;
  double* v[3] = {vx, vy, vz};
  for (Entry& e : velocities_) {
    const bool held = e.active;  // its accelerations were zeroed at the last hold
    e.active = time >= e.load->birth && !(e.load->death > 0.0 && time > e.load->death);
    if (!e.active) continue;
    const double value = this->value(*e.load, time);
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
  for (Entry& e : velocities_)
    for (std::size_t j = 0; j < e.nodes.size(); ++j) {
      double& u = a[e.direction][e.nodes[j]];
      // Held over the step just taken (Δx = dt v_p), the DOF had the other forces m a_free
      // (elements, contact, loads) against it: the constraint did minus their work, by the
      // trapezoidal rule as the forces' (½m(a_n + a_{n+1})·Δx), so that the work put in up to
      // t_{n+1} is there when the energies of t_{n+1} are taken. (The impulse m(v_p − v_free)
      // at the mean velocity instead credits half a step late or early.)
      if (e.active && mass_) work_ -= 0.5 * mass_[e.nodes[j]] * (e.held[j] + u) * step_ * e.current;
      e.held[j] = u;
      if (e.active) u = 0.0;
    }
}

}  // namespace impactfe
