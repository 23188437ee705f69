#include "reduction/reduced_dynamics.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include "core/errors.h"
#include "core/log.h"

namespace impactfe {

ReducedDynamics::ReducedDynamics(MatrixXd k, MatrixXd m, MatrixXd c,
                                 std::vector<GeneralizedGap> gaps,
                                 std::unique_ptr<TimeIntegrator> integrator)
    : k_(std::move(k)),
      m_(std::move(m)),
      c_(std::move(c)),
      gaps_(std::move(gaps)),
      integrator_(std::move(integrator)) {
  if (c_.size() == 0) c_ = MatrixXd::Zero(k_.rows(), k_.cols());
  gap_forces_ = VectorXd::Zero(static_cast<int>(gaps_.size()));
  gap_load_ = VectorXd::Zero(k_.rows());
}

VectorXd GeneralizedGap::direction(Eigen::Index n) const {
  VectorXd d = VectorXd::Zero(n);
  if (b_j.size()) d += b_j;
  if (b_i.size()) d -= b_i;
  return d;
}

double GeneralizedGap::separation(const VectorXd& q) const {
  const double ui = b_i.size() ? b_i.dot(q) : 0.0;
  const double uj = b_j.size() ? b_j.dot(q) : 0.0;
  return uj - ui + gap;
}

double GeneralizedGap::closing_rate(const VectorXd& v) const {
  const double vi = b_i.size() ? b_i.dot(v) : 0.0;
  const double vj = b_j.size() ? b_j.dot(v) : 0.0;
  return vj - vi;
}

void ReducedDynamics::add_gap_force(std::size_t g, double p) {
  gap_forces_(static_cast<int>(g)) = p;
  if (p == 0.0) return;
  const GeneralizedGap& gap = gaps_[g];
  if (gap.b_j.size()) gap_load_ -= p * gap.b_j;
  if (gap.b_i.size()) gap_load_ += p * gap.b_i;
}

void ReducedDynamics::gap_loads(const VectorXd& q_star, const VectorXd& v_star) {
  gap_load_.setZero(k_.rows());
  for (std::size_t g = 0; g < gaps_.size(); ++g) {
    const GeneralizedGap& gap = gaps_[g];
    const double s = gap.separation(q_star);
    double p = 0.0;
    if (s <= 0.0) {
      p = gap.stiffness * s + gap.damping * gap.closing_rate(v_star);
      // A closed gap reports a negative (compressive) force; damping never makes it pull.
      if (gap.stiffness > 0.0) p = std::min(p, 0.0);
    }
    add_gap_force(g, p);
  }
}

double ReducedDynamics::explicit_gap_force(const GeneralizedGap& gap, const VectorXd& q_star,
                                           const VectorXd& v_star) {
  const double s = gap.separation(q_star);
  if (s > 0.0) return 0.0;
  const double p = gap.damping * gap.closing_rate(v_star);
  if (!gap.implicit()) return p + gap.stiffness * s;
  // The damper of a closed gap never pulls harder than its spring pushes (at the predictor).
  return std::min(p, -gap.stiffness * s);
}

void ReducedDynamics::explicit_gap_loads(const VectorXd& q_star, const VectorXd& v_star) {
  gap_load_.setZero(k_.rows());
  for (std::size_t g = 0; g < gaps_.size(); ++g)
    add_gap_force(g, explicit_gap_force(gaps_[g], q_star, v_star));
}

VectorXd ReducedDynamics::implicit_gap_correction(const VectorXd& q_pred, const VectorXd& y,
                                                  double weight) {
  // The spring of a closed gap, P = k s with s = dᵀq + gap, is a linear force −k d (dᵀq + gap)
  // once the gap's status is known: the step solves (K_eff + w Σ_closed k d dᵀ) Δq = r − w Σ
  // k d (dᵀq_pred + gap) by the Sherman–Morrison–Woodbury formula on the constant factor
  // (Keff⁻¹ d is kept per gap), and the status (closed when s <= 0 at the end of the step) is
  // iterated to a fixed point. Implicit, the spring neither creates energy nor needs the
  // small steps an explicit gap force does (MAPDL Theory Reference, gap conditions: the
  // implicit treatment "normally allows larger time steps").
  std::vector<int> closed, next;
  for (std::size_t g = 0; g < gaps_.size(); ++g)
    if (gaps_[g].implicit() && gaps_[g].separation(q_pred + y) <= 0.0)
      closed.push_back(static_cast<int>(g));
  VectorXd dq = y;
  for (int iteration = 0; iteration < 2 * static_cast<int>(gaps_.size()) + 2; ++iteration) {
    dq = y;
    if (!closed.empty()) {
      const auto na = static_cast<Eigen::Index>(closed.size());
      MatrixXd schur(na, na);
      VectorXd rhs(na);
      for (Eigen::Index i = 0; i < na; ++i) {
        const GeneralizedGap& gi = gaps_[static_cast<std::size_t>(closed[i])];
        // Row i of (W⁻¹ + Dᵀ Z) z = Dᵀ x0, where x0 = Keff⁻¹ (r − w Σ k d (dᵀq_pred + gap)).
        for (Eigen::Index j = 0; j < na; ++j)
          schur(i, j) = gi.direction(k_.rows()).dot(gap_response_.col(closed[j]));
        schur(i, i) += 1.0 / (weight * gi.stiffness);
      }
      // x0 = y − Σ_j Z_j (w k_j s_j(q_pred)); then Δq = x0 − Z_A z with z from the Schur system.
      VectorXd x0 = y;
      for (Eigen::Index j = 0; j < na; ++j) {
        const GeneralizedGap& gj = gaps_[static_cast<std::size_t>(closed[j])];
        x0 -= gap_response_.col(closed[j]) * (weight * gj.stiffness * gj.separation(q_pred));
      }
      for (Eigen::Index i = 0; i < na; ++i)
        rhs(i) = gaps_[static_cast<std::size_t>(closed[i])].direction(k_.rows()).dot(x0);
      const VectorXd z = schur.partialPivLu().solve(rhs);
      dq = x0;
      for (Eigen::Index j = 0; j < na; ++j) dq -= gap_response_.col(closed[j]) * z(j);
    }
    next.clear();
    for (std::size_t g = 0; g < gaps_.size(); ++g)
      if (gaps_[g].implicit() && gaps_[g].separation(q_pred + dq) <= 0.0)
        next.push_back(static_cast<int>(g));
    if (next == closed) return dq;
    closed.swap(next);
  }
  ++n_status_cycles_;  // the status did not settle: the last solution is kept
  return dq;
}

void ReducedDynamics::gap_loads_at(const VectorXd& q, const VectorXd& q_star,
                                   const VectorXd& v_star) {
  // The forces the step used: the implicit springs at the step's end, the explicit parts at
  // the predictor (explicit_gap_loads).
  gap_load_.setZero(k_.rows());
  for (std::size_t g = 0; g < gaps_.size(); ++g) {
    const GeneralizedGap& gap = gaps_[g];
    double p = explicit_gap_force(gap, q_star, v_star);
    if (gap.implicit()) p += gap.stiffness * std::min(gap.separation(q), 0.0);
    add_gap_force(g, p);
  }
}

void ReducedDynamics::start(const VectorXd& q0, const VectorXd& v0, const VectorXd& f0, double h) {
  gap_loads(q0, v0);
  const VectorXd rhs = f0 + gap_load_ - c_ * v0 - k_ * q0;
  VectorXd a0 = VectorXd::Zero(q0.size());
  if (rhs.squaredNorm() > 0.0) {
    // Masters without mass (if any) get the minimum-norm acceleration.
    a0 = m_.completeOrthogonalDecomposition().solve(rhs);
  }
  integrator_->start(q0, v0, a0, h);
  q_prev_ = q0;
  f_old_ = f0 + gap_load_;
  first_step_ = true;
  factor_valid_ = false;
}

void ReducedDynamics::jump_load(const VectorXd& f_now) {
  const TimeIntegrator& ti = *integrator_;
  const VectorXd rhs = f_now + gap_load_ - c_ * ti.v() - k_ * ti.u();
  // Masters without mass (if any) get the minimum-norm acceleration, as in start().
  const VectorXd a = m_.completeOrthogonalDecomposition().solve(rhs);
  integrator_->jump_acceleration(a);
  f_old_ = f_now + gap_load_;
}

void ReducedDynamics::factorize() {
  const IntegrationCoefficients coeff = integrator_->coefficients();
  effective_.compute(coeff.cK * k_ + coeff.cC * c_ + coeff.cM * m_);
  if (effective_.info() != Eigen::Success || !(effective_.vectorD().cwiseAbs().minCoeff() >
                                               1e-14 * effective_.vectorD().cwiseAbs().maxCoeff()))
    throw ModelError(
        "reduced transient: the effective matrix is singular (a master DOF without mass and "
        "stiffness?)");
  factored_ = coeff;
  factor_valid_ = true;
  gap_response_ = MatrixXd(k_.rows(), static_cast<int>(gaps_.size()));
  for (std::size_t g = 0; g < gaps_.size(); ++g)
    gap_response_.col(static_cast<int>(g)) =
        gaps_[g].implicit() ? VectorXd(effective_.solve(gaps_[g].direction(k_.rows())))
                            : VectorXd::Zero(k_.rows());
  ++n_factorizations_;
}

void ReducedDynamics::step(const VectorXd& f_next) {
  const TimeIntegrator& ti = *integrator_;
  const IntegrationCoefficients coeff = ti.coefficients();
  if (!factor_valid_ || coeff.cK != factored_.cK || coeff.cC != factored_.cC ||
      coeff.cM != factored_.cM)
    factorize();
  // Dampers of closed gaps (and gaps of negative stiffness) act explicitly, from the linear
  // extrapolation u* = 2u_n − u_{n−1} (u* = u_n on the first step); v* is the backward
  // difference (u* − u_n)/h.
  const VectorXd& qn = ti.u();
  const VectorXd q_star = first_step_ ? qn : VectorXd(2.0 * qn - q_prev_);
  const VectorXd v_star = first_step_ ? ti.v() : VectorXd((q_star - qn) / ti.step());
  explicit_gap_loads(q_star, v_star);

  // Linear system: one Newton correction from the predictor is exact for a fixed gap status.
  const ResidualWeights w = ti.weights();
  VectorXd q = ti.predict();
  VectorXd v, a;
  ti.kinematics(q, v, a);
  const VectorXd r = w.external * (f_next + gap_load_) + (1.0 - w.external) * f_old_ -
                     m_ * (w.inertia * a + (1.0 - w.inertia) * ti.a()) -
                     w.stiffness * (k_ * q + c_ * v) -
                     (1.0 - w.stiffness) * (k_ * qn + c_ * ti.v());
  const VectorXd y = effective_.solve(r);
  ++n_solves_;
  q += implicit_gap_correction(q, y, w.external);
  gap_loads_at(q, q_star, v_star);
  q_prev_ = qn;
  integrator_->advance(q);
  f_old_ = f_next + gap_load_;
  first_step_ = false;
}

}  // namespace impactfe
