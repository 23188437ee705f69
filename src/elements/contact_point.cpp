#include "elements/contact_point.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "elements/element_build_cache.h"
#include "elements/element_registry.h"

namespace impactfe {

ContactPoint::ContactPoint(int id, int node_i, int node_j, const ContactLawData& data)
    : Element(id), data_(data) {
  for (int node : {node_i, node_j})
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ}) dofs_.push_back({node, d});
}

ContactPoint::ContactPoint(int id, std::vector<DofKey> dofs, const ContactLawData& data)
    : Element(id), data_(data), dofs_(std::move(dofs)) {}

ContactKinematics ContactPoint::kinematics(const Eigen::VectorXd& u) const {
  ContactKinematics k;
  const Vec3 d(u(3) - u(0), u(4) - u(1), u(5) - u(2));
  const Vec3& n = data_.normal;
  k.normal = n;
  k.gap = data_.gap0 + n.dot(d);
  k.ut = d - n.dot(d) * n;
  k.G.resize(6);
  k.G << -n, n;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  k.T.resize(3, 6);
  k.T << -P, P;
  return k;
}

void ContactPoint::initialize() {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_dofs());
  trial_ = State{};
  const bool in_range = locate(zero);
  if (data_.behaviour == ContactBehaviour::BondedInitial) {
    // Bonded when the nodes start in contact, never in contact otherwise.
    if (in_range && kinematics(zero).gap <= 0.0)
      data_.behaviour = ContactBehaviour::BondedAlways;
    else
      trial_.never = true;
  }
  if (always_tied()) trial_.tied = true;
  if (data_.start > 0) trial_.status = Contact::Stick;
  if (data_.start == 0 || trial_.tied) trial_ = next_state(zero, in_range);
  committed_ = trial_;
}

bool ContactPoint::always_tied() const {
  return data_.behaviour == ContactBehaviour::NoSeparationAlways ||
         data_.behaviour == ContactBehaviour::BondedAlways;
}

bool ContactPoint::bonded() const {
  return data_.behaviour == ContactBehaviour::Bonded ||
         data_.behaviour == ContactBehaviour::BondedAlways;
}

bool ContactPoint::frictionless() const {
  if (data_.behaviour == ContactBehaviour::NoSeparation ||
      data_.behaviour == ContactBehaviour::NoSeparationAlways)
    return true;
  return data_.mu == 0.0 && data_.behaviour == ContactBehaviour::Standard;
}

bool ContactPoint::never_slides() const {
  return bonded() || data_.behaviour == ContactBehaviour::Rough;
}

ContactPoint::Response ContactPoint::response(const State& s, const ContactKinematics& kin) const {
  Response r;
  r.gap = kin.gap;
  r.ut = kin.ut;
  if (s.status == Contact::Open) return r;
  r.pn = s.lambda - data_.kn * r.gap;
  r.kn = data_.kn;
  if (frictionless()) return r;
  // K_t = ∂f_t/∂u_t in full: with T = [−P, P] (a point pair) Tᵀ K_t T is the same with P K_t P,
  // but a deformable or rotating target's T has a normal part (the variation of P), which the
  // consistent tangent needs.
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Vec3 xi = data_.kt * (r.ut - committed_.slip);
  if (s.status == Contact::Stick) {
    r.ft = xi;
    r.kt = data_.kt * I;
    return r;
  }
  const double norm = xi.norm();
  const double limit = data_.mu * std::max(r.pn, 0.0);
  if (norm > 0.0) {
    const Vec3 dir = xi / norm;
    r.ft = limit * dir;
    r.kt = (limit * data_.kt / norm) * (I - dir * dir.transpose());
  }
  return r;
}

ContactPoint::State ContactPoint::next_state(const Eigen::VectorXd& u, bool in_range) const {
  State s = trial_;
  if (s.never) return s;
  const ContactKinematics kin = kinematics(u);
  const double gap = kin.gap;
  bool closed;
  if (s.tied)
    closed = true;
  else if (!in_range)
    closed = false;
  else
    // Closed only while the nodes penetrate (MAPDL Theory §14.174: P = 0 for an open gap,
    // P = λ + k_n·pen otherwise). A multiplier that still pushes across a positive gap
    // (λ − k_n g > 0 for 0 < g < λ/k_n) acts as a spring anchored beyond the surface: on
    // rebound it does work λ²/(2 k_n) and more that the impact never put in.
    // A multiplier that carries the load converges to g = 0 (its Uzawa update is exact for a
    // linear neighbourhood), and round-off then leaves g a few ulps either side: within 1e-8 of
    // the penetration the multiplier stands for (λ/k_n) the contact stays closed, else a body
    // resting on it alone would come loose (singular) at the iteration after an update.
    closed = gap <= 0.0 || (s.lambda > 0.0 && gap <= 1e-8 * s.lambda / data_.kn);
  if (!closed) {
    // Opening releases the multiplier: a re-closure starts from the penalty force.

    s.status = Contact::Open;
    s.lambda = 0.0;
    return s;
  }
  if (data_.behaviour == ContactBehaviour::NoSeparation ||
      data_.behaviour == ContactBehaviour::Bonded)
    s.tied = true;
  if (frictionless()) {
    s.status = Contact::Slide;
    return s;
  }
  if (never_slides()) {
    s.status = Contact::Stick;
    return s;
  }
  const double pn = std::max(s.lambda - data_.kn * gap, 0.0);
  const Vec3 xi = data_.kt * (kin.ut - committed_.slip);
  s.status = xi.norm() <= data_.mu * pn ? Contact::Stick : Contact::Slide;
  return s;
}

void ContactPoint::tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                           Eigen::VectorXd& f_int) const {
  const ContactKinematics kin = kinematics(u);
  const Response r = response(trial_, kin);
  // f = −p G + Tᵀ f_t (the contact pushes the node along +n), K = k_n G Gᵀ − p H + Tᵀ K_t T.
  K.noalias() = r.kn * kin.G * kin.G.transpose();
  if (r.pn != 0.0 && kin.H.size() > 0) K -= r.pn * kin.H;
  if (!r.kt.isZero(0.0)) K.noalias() += kin.T.transpose() * r.kt * kin.T;
  f_int = -r.pn * kin.G;
  if (!r.ft.isZero(0.0)) {
    f_int.noalias() += kin.T.transpose() * r.ft;
    add_friction_curvature(u, r.ft, K);
  }
}

bool ContactPoint::update_status(const ElementContext&, const Eigen::VectorXd& u) {
  if (frozen_) return false;
  const bool in_range = locate(u);
  State next = next_state(u, in_range);
  bool changed = next.status != trial_.status;
  if (!changed && next.status != Contact::Open && data_.augmented &&
      next.augmentations < kMaxAugmentations) {
    const Response r = response(next, kinematics(u));
    // A closed contact penetrates (g ≤ 0, next_state) unless it is tied; a tied one with a gap
    // (g > 0) is as wrong as one with a penetration: both update λ, tensile only when tied.
    const double error = std::abs(r.gap);
    // Tolerance: TOLN when given, else 1 % of the penetration of the pure penalty method.
    const double tol = data_.toln > 0.0 ? data_.toln : 0.01 * std::abs(r.pn) / data_.kn;
    if (error > tol) {
      next.lambda = next.tied ? r.pn : std::max(r.pn, 0.0);  // λ ← λ − k_n g
      ++next.augmentations;
      changed = true;
    }
  }
  trial_ = next;
  return changed;
}

void ContactPoint::commit(const Eigen::VectorXd& u) {
  const Response r = response(trial_, kinematics(u));
  if (trial_.status == Contact::Open) {
    // The tangential spring is relaxed while open: a re-closure sticks where it lands.
    trial_.slip = r.ut;
  } else if (trial_.status == Contact::Slide) {
    const Vec3 slip = data_.kt > 0.0 ? Vec3(r.ut - r.ft / data_.kt) : Vec3(r.ut);
    trial_.slide += (slip - committed_.slip).norm();
    trial_.slip = slip;
  }
  trial_.augmentations = 0;
  committed_ = trial_;
  frozen_ = false;
}

void ContactPoint::revert() {
  trial_ = committed_;
  frozen_ = false;
}

double ContactPoint::penetration_ratio(const Eigen::VectorXd& start,
                                       const Eigen::VectorXd& u) const {
  if (!data_.bisect_on_penetration || trial_.status == Contact::Open || !(data_.toln > 0.0))
    return 0.0;
  const double now = std::max(-kinematics(u).gap, 0.0);
  if (now <= data_.toln) return 0.0;
  return (now - std::max(-kinematics(start).gap, 0.0)) / data_.toln;
}

std::vector<double> ContactPoint::history_state() const {
  const State& s = committed_;
  return {static_cast<double>(static_cast<int>(s.status)),
          s.lambda,
          s.slip.x(),
          s.slip.y(),
          s.slip.z(),
          s.slide,
          s.tied ? 1.0 : 0.0,
          s.never ? 1.0 : 0.0};
}

void ContactPoint::restore_history_state(const std::vector<double>& state) {
  IMPACTFE_CHECK(state.size() == kStateSize,
                 fmt::format("contact element {}: a saved state of {} values, {} expected", id(),
                             state.size(), kStateSize));
  State s;
  s.status = static_cast<Contact>(static_cast<int>(state[0]));
  s.lambda = state[1];
  s.slip = Vec3(state[2], state[3], state[4]);
  s.slide = state[5];
  s.tied = state[6] != 0.0;
  s.never = state[7] != 0.0;
  committed_ = s;
  trial_ = committed_;
  frozen_ = false;
}

GapStatus ContactPoint::status() const {
  switch (trial_.status) {
    case Contact::Open:
      return GapStatus::Open;
    case Contact::Stick:
      return GapStatus::Closed;
    default:
      return GapStatus::Sliding;
  }
}

const std::vector<std::string>& ContactPoint::names() {
  static const std::vector<std::string> n = {"STAT", "FN", "PENE", "GAP", "FT", "SLIDE"};
  return n;
}

const std::vector<ResultSequence>& ContactPoint::sequences() {
  static const std::vector<ResultSequence> s = {
      {"CONT", "STAT", "STAT"}, {"CONT", "PRES", "FN"},  {"CONT", "PENE", "PENE"},
      {"CONT", "GAP", "GAP"},   {"CONT", "SFRIC", "FT"}, {"CONT", "SLIDE", "SLIDE"}};
  return s;
}

void ContactPoint::results(const ElementContext&, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                           ElementResultValues& out) const {
  const Response r = response(trial_, kinematics(u));
  const bool closed = trial_.status != Contact::Open;
  double slide = committed_.slide;
  if (trial_.status == Contact::Slide && data_.kt > 0.0)
    slide += (r.ut - r.ft / data_.kt - committed_.slip).norm();
  const double stat = !closed ? 0.0 : trial_.status == Contact::Slide ? 2.0 : 3.0;
  out = {stat, r.pn, closed ? std::max(-r.gap, 0.0) : 0.0, r.gap, r.ft.norm(), slide};
}

std::vector<DofKey> translation_dofs(const std::vector<int>& nodes) {
  std::vector<DofKey> out;
  for (int n : nodes)
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ}) out.push_back({n, d});
  return out;
}

double attached_stiffness(const ElementBuildContext& ctx, int node, const Vec3& n) {
  double s = 0.0;
  for (const int id : elements_at_node(ctx, node)) {
    const AttachedElement* attached = attached_element(ctx, id);
    if (attached == nullptr) continue;
    const int n_dofs = static_cast<int>(attached->dofs.size());
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n_dofs);
    for (int a = 0; a < n_dofs; ++a) {
      const DofKey& k = attached->dofs[static_cast<std::size_t>(a)];
      const int c = static_cast<int>(k.dof);
      if (k.node == node && c < 3) w(a) = n(c);
    }
    s += w.dot(attached->stiffness * w);
  }
  return s;
}

double attached_depth(const ElementBuildContext& ctx, int node) {
  double sum = 0.0;
  int count = 0;
  for (const int id : elements_at_node(ctx, node)) {
    const AttachedElement* attached = attached_element(ctx, id);
    if (attached == nullptr) continue;
    if (const auto v = attached->volume; v && *v > 0.0) {
      sum += *v;
      ++count;
    }
  }
  return count > 0 ? std::cbrt(sum / count) : 0.0;
}

}  // namespace impactfe
