#include "reduction/reduced_dynamics.h"

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

void ReducedDynamics::gap_loads(const VectorXd& q_star, const VectorXd& v_star) {
  gap_load_.setZero(k_.rows());
  for (std::size_t g = 0; g < gaps_.size(); ++g) {
    const GeneralizedGap& gap = gaps_[g];
    const double ui = gap.b_i.size() ? gap.b_i.dot(q_star) : 0.0;
    const double uj = gap.b_j.size() ? gap.b_j.dot(q_star) : 0.0;
    const double s = uj - ui + gap.gap;
    double p = 0.0;
    if (s <= 0.0) {
      const double vi = gap.b_i.size() ? gap.b_i.dot(v_star) : 0.0;
      const double vj = gap.b_j.size() ? gap.b_j.dot(v_star) : 0.0;
      p = gap.stiffness * s + gap.damping * (vj - vi);
      // A closed gap reports a negative (compressive) force; damping never makes it pull.
      if (gap.stiffness > 0.0) p = std::min(p, 0.0);
    }
    gap_forces_(static_cast<int>(g)) = p;
    if (p == 0.0) continue;
    if (gap.b_j.size()) gap_load_ -= p * gap.b_j;
    if (gap.b_i.size()) gap_load_ += p * gap.b_i;
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
  ++n_factorizations_;
}

void ReducedDynamics::step(const VectorXd& f_next) {
  const TimeIntegrator& ti = *integrator_;
  const IntegrationCoefficients coeff = ti.coefficients();
  if (!factor_valid_ || coeff.cK != factored_.cK || coeff.cC != factored_.cC ||
      coeff.cM != factored_.cM)
    factorize();
  // Explicit gap forces from the linear extrapolation u* = 2u_n − u_{n−1} (u* = u_n on the
  // first step); v* is the backward difference (u* − u_n)/h.
  const VectorXd& qn = ti.u();
  const VectorXd q_star = first_step_ ? qn : VectorXd(2.0 * qn - q_prev_);
  const VectorXd v_star = first_step_ ? ti.v() : VectorXd((q_star - qn) / ti.step());
  gap_loads(q_star, v_star);
  const VectorXd f_total = f_next + gap_load_;

  // Linear system: one Newton correction from the predictor is exact.
  const ResidualWeights w = ti.weights();
  VectorXd q = ti.predict();
  VectorXd v, a;
  ti.kinematics(q, v, a);
  const VectorXd r = w.external * f_total + (1.0 - w.external) * f_old_ -
                     m_ * (w.inertia * a + (1.0 - w.inertia) * ti.a()) -
                     w.stiffness * (k_ * q + c_ * v) -
                     (1.0 - w.stiffness) * (k_ * qn + c_ * ti.v());
  q += effective_.solve(r);
  ++n_solves_;
  q_prev_ = qn;
  integrator_->advance(q);
  f_old_ = f_total;
  first_step_ = false;
}

}  // namespace impactfe
