// Elastic-plastic response of PLANE182 / PLANE183 (elements/plane_solid.h) with a TB plasticity
// or implicit creep law (materials/j2_plasticity.h): the J2 return at every stiffness point from
// its committed state, the consistent tangent assembled, the incompatible modes of the 4-node
// quadrilateral solved per element and condensed, restart state and the plastic result items.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/plane_solid.h"

namespace impactfe {

Eigen::MatrixXd PlaneSolid::point_operator(std::size_t q, bool modes) const {
  const Eigen::Vector2d xi = rule_[q].xi.head<2>();
  const Point p = point_at(xi);
  const Eigen::MatrixXd b = point_strain(p);
  const auto n = b.cols();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(4, n + (modes ? 4 : 0));
  out.leftCols(n) = b;
  if (options_.technology == PlaneTechnology::BBar) {
    // Mean dilatation as in form_stiffness(): θ replaced by the element mean θ̄ at every point,
    // so that isochoric plastic flow does not lock (Hughes 1980).
    const Eigen::RowVectorXd shift = (mean_dilatation_ - b.topRows(3).colwise().sum()) / 3.0;
    for (int r = 0; r < 3; ++r) out.row(r).head(n) += shift;
  }
  if (modes) out.rightCols(4) = mode_matrix(p, xi) - mean_modes_;
  return out;
}

void PlaneSolid::point_response(const PlasticState& committed, const Eigen::Vector4d& strain,
                                Eigen::Vector4d& stress, Eigen::Matrix4d& tangent,
                                PlasticState* updated) const {
  tangent.setZero();
  if (options_.behaviour == PlaneBehaviour::PlaneStress) {
    // σzz = 0: the plane-stress return on (εxx, εyy, γxy); εzz is the law's own unknown. The
    // zz row and column of the 4-component form stay 0 (the zz row of B is 0 here).
    Vector5d e = Vector5d::Zero();
    e << strain(0), strain(1), strain(3), 0.0, 0.0;
    const PlaneStressResponse r = plasticity_->plane_stress(committed, e, updated);
    const int map[3] = {0, 1, 3};
    stress << r.stress(0), r.stress(1), 0.0, r.stress(2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) tangent(map[i], map[j]) = r.tangent(i, j);
    return;
  }
  // Plane strain (εzz = 0 from B) and axisymmetry (εzz = u/r from B): the 3-D return with
  // γyz = γxz = 0; σ and C_alg restricted to (xx, yy, zz, xy), the components B produces.
  Vector6d e = Vector6d::Zero();
  e.head<4>() = strain;
  const PlasticResponse r = plasticity_->solid(committed, e, updated);
  stress = r.stress.head<4>();
  tangent = r.tangent.topLeftCorner<4, 4>();
}

void PlaneSolid::plastic_sum(const Eigen::VectorXd& q, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                             PointStates* updated, std::vector<Eigen::Vector4d>* stresses) const {
  const auto nq = q.size();
  const bool modes = nq > 2 * static_cast<Eigen::Index>(nodes_.size());
  k.setZero(nq, nq);
  f.setZero(nq);
  if (stresses) stresses->clear();
  for (std::size_t p = 0; p < rule_.size(); ++p) {
    const Eigen::MatrixXd b = point_operator(p, modes);
    Eigen::Vector4d sigma;
    Eigen::Matrix4d c;
    point_response(committed_[p], b * q, sigma, c, updated ? &(*updated)[p] : nullptr);
    f.noalias() += point_dv_[p] * (b.transpose() * sigma);
    k.noalias() += point_dv_[p] * (b.transpose() * c * b);
    if (stresses) stresses->push_back(sigma);
  }
}

void PlaneSolid::tangent_plastic(const Eigen::VectorXd& u, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                                 PointStates* updated,
                                 std::vector<Eigen::Vector4d>* stresses) const {
  if (options_.technology != PlaneTechnology::IncompatibleModes) {
    plastic_sum(u, k, f, updated, stresses);
    if (options_.technology == PlaneTechnology::Reduced) {
      // The material at the centre; the hourglass stiffness stays elastic (Flanagan &
      // Belytschko 1981, their stiffness form; plane_solid_reduced.cpp).
      k += hourglass_;
      f.noalias() += hourglass_ * u;
    }
    return;
  }
  // The mode amplitudes α are internal: f_α(u, α) = ∫Gᵀσ dV = 0 solved by Newton from the
  // elastic recovery (every evaluation returns from the committed states, so the result stays a
  // function of (committed state, u)); then K = K_uu − K_uα K_αα⁻¹ K_αu, exact at f_α = 0 (the
  // treatment of the plastic SOLID185 with extra shapes, brick8.cpp).
  const auto n = u.size();
  Eigen::VectorXd q(n + 4);
  q.head(n) = u;
  q.tail<4>() = -(mode_recovery_ * u);
  Eigen::MatrixXd kq;
  Eigen::VectorXd fq;
  const double scale = std::max(u.lpNorm<Eigen::Infinity>(), 1e-300);
  for (int iter = 0; iter < 25; ++iter) {
    plastic_sum(q, kq, fq, nullptr, nullptr);
    const Eigen::Vector4d step = -kq.bottomRightCorner<4, 4>().ldlt().solve(fq.tail<4>());
    q.tail<4>() += step;
    if (step.lpNorm<Eigen::Infinity>() <=
        1e-12 * std::max(scale, q.tail<4>().lpNorm<Eigen::Infinity>()))
      break;
  }
  plastic_sum(q, kq, fq, updated, stresses);
  const Eigen::MatrixXd kau = kq.bottomLeftCorner(4, n);
  const auto kaa = kq.bottomRightCorner<4, 4>().ldlt();
  k = kq.topLeftCorner(n, n) - kau.transpose() * kaa.solve(kau);
  f = fq.head(n) - kau.transpose() * kaa.solve(fq.tail<4>());
}

void PlaneSolid::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (options_.large_deflection && ctx.large_deflection) {
    finite_commit(u);
    return;
  }
  if (!plasticity_) return;
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  PointStates next = committed_;
  tangent_plastic(u, k, f, &next, nullptr);
  committed_ = next;
}

std::vector<double> PlaneSolid::history_state() const {
  std::vector<double> out;
  for (const PlasticState& s : committed_) append_state(out, s);  // per stiffness point
  // Large deflection: the accumulated strains, then the committed displacement.
  for (const FiniteState& s : finite_) out.insert(out.end(), s.strain.data(), s.strain.data() + 4);
  out.insert(out.end(), committed_u_.data(), committed_u_.data() + committed_u_.size());
  return out;
}

void PlaneSolid::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  for (PlasticState& s : committed_) read_state(state, pos, s);
  const std::size_t finite = 4 * finite_.size() + static_cast<std::size_t>(committed_u_.size());
  IMPACTFE_CHECK(pos + finite == state.size(), "PLANE182/183: saved state of the wrong length");
  for (FiniteState& s : finite_)
    for (int i = 0; i < 4; ++i) s.strain(i) = state[pos++];
  for (Eigen::Index i = 0; i < committed_u_.size(); ++i) committed_u_(i) = state[pos++];
}

double PlaneSolid::plastic_work() const {
  double w = 0.0;
  for (std::size_t p = 0; p < committed_.size(); ++p)
    w += committed_[p].plastic_work * point_dv_[p];
  return w;
}

void PlaneSolid::plastic_results(const Eigen::VectorXd& u, ElementResultValues& out) const {
  // The states at u (the committed ones after a converged step), averaged over the volume.
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  PointStates at = committed_;
  std::vector<Eigen::Vector4d> sigma;
  if (plasticity_->has_creep()) {
    // A creep return at u would add the creep of the clock's substep once more: the committed
    // states are those at the converged u (results are taken after Element::commit_history).
    for (const PlasticState& st : at) sigma.emplace_back(st.stress.head<4>());
  } else {
    tangent_plastic(u, k, f, &at, &sigma);
  }
  Eigen::Vector4d s = Eigen::Vector4d::Zero();
  Vector6d eppl = Vector6d::Zero();
  double epeq = 0.0, plwk = 0.0, srat = 0.0, total = 0.0;
  for (double dv : point_dv_) total += dv;
  // A creep law has no yield surface (flow stress ∞): SEPL and SRAT stay 0.
  const bool creep = plasticity_->has_creep();
  for (std::size_t p = 0; p < at.size(); ++p) {
    const double w = point_dv_[p] / total;
    const PlasticState& st = at[p];
    s += w * sigma[p];
    eppl += w * st.plastic_strain;
    epeq += w * st.alpha;
    plwk += w * st.plastic_work;
    if (!creep)
      srat = std::max(srat,
                      von_mises(st.stress - st.back_stress) / plasticity_->flow_stress(st.alpha));
  }
  out = plane_stress_items(s);
  if (creep) {
    // EPCR X Y Z XY, EQV = √(2/3 ε:ε) of the (deviatoric) creep strain, engineering shear
    // halved; NL CREQ the accumulated equivalent creep strain. PLWK: the creep work.
    const double eqv = std::sqrt(
        2.0 / 3.0 *
        (eppl(0) * eppl(0) + eppl(1) * eppl(1) + eppl(2) * eppl(2) + 0.5 * eppl(3) * eppl(3)));
    const double inelastic[6] = {eppl(0), eppl(1), eppl(2), eppl(3), eqv, epeq};
    std::copy(inelastic, inelastic + 6, out.begin() + 17);
    out[16] = plwk;
    return;
  }
  const double sepl = plasticity_->flow_stress(epeq);
  const double plastic[8] = {eppl(0), eppl(1), eppl(2), eppl(3), epeq, sepl, srat, plwk};
  std::copy(plastic, plastic + 8, out.begin() + 9);
}

}  // namespace impactfe
