#pragma once
/// Linear transient on a small dense system in generalized coordinates q (Guyan masters or
/// modal coordinates): M q̈ + C q̇ + K q = f(t) + Σ gap forces, integrated by any TimeIntegrator.
/// The effective matrix cK K + cC C + cM M is constant for a constant step and factorized once
/// (dense LDLᵀ). The spring of a gap condition (GP) of positive stiffness acts implicitly: the
/// step solves with the springs of the closed gaps (a low-rank update of the constant factor)
/// and iterates the gaps' status to a fixed point. A gap's damper, and a gap of negative
/// stiffness, act explicitly as loads from the displacements extrapolated from the previous two
/// time points (spec §10.4 step 5, which applies the whole gap force so). K is never modified.
#include <Eigen/Cholesky>

#include <memory>
#include <vector>

#include "linalg/sparse.h"
#include "time/time_integrator.h"

namespace impactfe {

/// A GP gap condition in generalized coordinates: the physical displacement of end I is
/// b_iᵀ q (b_i empty: ground, u = 0), likewise J. Separation s = u_J − u_I + gap; closed when
/// s <= 0, force P = stiffness·s + damping·(v_J − v_I) (<= 0 when closed), applied as −P on J
/// and +P on I.
struct GeneralizedGap {
  VectorXd b_i, b_j;
  double stiffness = 0.0;
  double gap = 0.0;
  double damping = 0.0;

  /// d = b_j − b_i (n generalized coordinates): s = dᵀq + gap.
  VectorXd direction(Eigen::Index n) const;
  double separation(const VectorXd& q) const;
  double closing_rate(const VectorXd& v) const;  // v_J − v_I
  /// The spring of a positive stiffness is solved with the step; a negative one (a piece of a
  /// force–deflection curve built from parallel gaps) stays an explicit load.
  bool implicit() const { return stiffness > 0.0; }
};

class ReducedDynamics {
 public:
  ReducedDynamics(MatrixXd k, MatrixXd m, MatrixXd c, std::vector<GeneralizedGap> gaps,
                  std::unique_ptr<TimeIntegrator> integrator);

  /// Starts at (q0, v0) with the load f0 at t = 0 (gap forces of the initial state added):
  /// a0 from M a0 = f0 − C v0 − K q0 (min-norm when M is singular), then the integrator
  /// start-up with step h (spec §10.2).
  void start(const VectorXd& q0, const VectorXd& v0, const VectorXd& f0, double h);
  /// Advances one step to t_{n+1} with the reduced external load f_{n+1} (without gap forces).
  void step(const VectorXd& f_next);
  /// The external load jumps to f_now at the current time t_n (a stepped load, KBC,1): the
  /// acceleration at t_n is taken from M a = f_now + gap load − C v − K q and f_now becomes the
  /// old load of the next step, so that the new load acts from t_n on, not from t_n + h/2.
  void jump_load(const VectorXd& f_now);

  const VectorXd& q() const { return integrator_->u(); }
  const VectorXd& v() const { return integrator_->v(); }
  const VectorXd& a() const { return integrator_->a(); }
  /// Gap forces P (input order) used in the last step (or at the start).
  const VectorXd& gap_forces() const { return gap_forces_; }
  /// Generalized gap load Σ (±P b) of the last step.
  const VectorXd& gap_load() const { return gap_load_; }
  long n_factorizations() const { return n_factorizations_; }
  /// Steps whose gap status did not settle within the status iterations.
  long n_status_cycles() const { return n_status_cycles_; }
  long n_solves() const { return n_solves_; }
  const TimeIntegrator& integrator() const { return *integrator_; }
  const MatrixXd& k() const { return k_; }
  const MatrixXd& m() const { return m_; }

 private:
  /// Whole gap forces at the state (q, v), into gap_forces_ / gap_load_ (start, load jumps).
  void gap_loads(const VectorXd& q, const VectorXd& v);
  /// The explicit part of one gap's force at the predictor (q*, v*).
  static double explicit_gap_force(const GeneralizedGap& gap, const VectorXd& q_star,
                                   const VectorXd& v_star);
  /// The explicit parts of all gap forces, into gap_forces_ / gap_load_.
  void explicit_gap_loads(const VectorXd& q_star, const VectorXd& v_star);
  /// The correction Δq from the predictor q_pred of a step whose gap-free correction is y,
  /// with the springs of the closed gaps (residual weight w of the external forces).
  VectorXd implicit_gap_correction(const VectorXd& q_pred, const VectorXd& y, double weight);
  /// The gap forces a finished step used: springs at q, explicit parts at (q*, v*).
  void gap_loads_at(const VectorXd& q, const VectorXd& q_star, const VectorXd& v_star);
  void add_gap_force(std::size_t g, double p);
  void factorize();

  MatrixXd k_, m_, c_;
  std::vector<GeneralizedGap> gaps_;
  std::unique_ptr<TimeIntegrator> integrator_;
  Eigen::LDLT<MatrixXd> effective_;
  IntegrationCoefficients factored_{0.0, 0.0, 0.0};
  bool factor_valid_ = false;
  VectorXd q_prev_;  // q_{n−1}, for the gap predictor
  VectorXd f_old_;   // total load (external + gaps) of the last step
  VectorXd gap_forces_, gap_load_;
  MatrixXd gap_response_;  // column g: K_eff⁻¹ d_g of an implicit gap (zero otherwise)
  long n_factorizations_ = 0, n_solves_ = 0, n_status_cycles_ = 0;
  bool first_step_ = true;
};

}  // namespace impactfe
