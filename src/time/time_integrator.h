#pragma once
/// Time integrators behind one interface. Elements never see the scheme: the integrator supplies
/// the coefficients of the effective stiffness K_eff = cK K + cC C + cM M, the weights of the
/// residual, and v(u), a(u) for a trial u_{n+1}.
///
/// The driver's residual at a trial u = u_{n+1} is (generalized-alpha form, Chung & Hulbert 1993):
///   r = wf f_{n+1} + (1-wf) f_n - wm M a_{n+1} - (1-wm) M a_n
///       - wk (f_int(u) + C v_{n+1}) - (1-wk) (f_int(u_n) + C v_n)
/// and the effective tangent is K_eff = wk K_T + wk (dv/du) C + wm (da/du) M, i.e.
/// cK = wk, cC = wk * dv/du, cM = wm * da/du. Newmark and Houbolt have wf = wk = wm = 1.
/// Vectors cover every active DOF (free and constrained), so prescribed motion gets its own
/// velocity and acceleration from the same formulas.
#include <Eigen/Core>

#include <memory>
#include <string>

#include "core/model.h"

namespace impactfe {

struct IntegrationCoefficients {
  double cK = 1.0;  // multiplies the tangent stiffness
  double cC = 0.0;  // multiplies the damping matrix
  double cM = 0.0;  // multiplies the mass matrix
};

struct ResidualWeights {
  double external = 1.0;   // wf: weight of f_{n+1} (HHT: 1 - alpha_f)
  double stiffness = 1.0;  // wk: weight of f_int(u_{n+1}) + C v_{n+1}
  double inertia = 1.0;    // wm: weight of M a_{n+1} (generalized-alpha: 1 - alpha_m)
};

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  virtual std::string name() const = 0;

  /// Starts at state (u0, v0, a0) with step h; a0 comes from equilibrium at t0 (the driver
  /// solves M a0 = f(0) - C v0 - f_int(u0)).
  virtual void start(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
                     const Eigen::VectorXd& a0, double h) = 0;
  /// Changes the step between load steps. Houbolt re-samples its history (spec §10.2).
  virtual void set_step(double h) = 0;
  virtual double step() const = 0;

  virtual IntegrationCoefficients coefficients() const = 0;
  virtual ResidualWeights weights() const = 0;

  /// Predictor for u_{n+1} (start of the equilibrium iterations), into `u` (resized; its
  /// storage reused, so that a step allocates no vector of model size: issue 11).
  virtual void predict(Eigen::VectorXd& u) const = 0;
  Eigen::VectorXd predict() const {
    Eigen::VectorXd u;
    predict(u);
    return u;
  }
  /// v_{n+1} and a_{n+1} for a trial u_{n+1}.
  virtual void kinematics(const Eigen::VectorXd& u_next, Eigen::VectorXd& v_next,
                          Eigen::VectorXd& a_next) const = 0;
  /// Accepts u_{n+1} as the converged state; the history moves one step.
  virtual void advance(const Eigen::VectorXd& u_next) = 0;
  /// The load jumps at t_n (a stepped load, KBC,1): `a_jump` is the acceleration of the current
  /// state under the new load, M a = f_new − C v_n − K u_n. A one-step scheme takes it as a_n, so
  /// that the new load acts over the whole next step (with the old a_n the trapezoidal rule
  /// would average the old and the new load over that step, which delays the load by h/2).
  virtual void jump_acceleration(const Eigen::VectorXd& a_jump) = 0;

  /// Current (last accepted) state.
  virtual const Eigen::VectorXd& u() const = 0;
  virtual const Eigen::VectorXd& v() const = 0;
  virtual const Eigen::VectorXd& a() const = 0;
};

/// Houbolt (thesis eqs. 3-2..3-4; Bathe 9.2.3) with the "uniformly accelerated past motion"
/// start-up (spec §10.2) and history re-sampling when h changes.
std::unique_ptr<TimeIntegrator> make_houbolt();

/// Newmark / HHT-alpha / generalized-alpha in one class (ANSYS TINTP: ALPHA = beta, DELTA = gamma).
struct GeneralizedAlphaParameters {
  double beta = 0.25;
  double gamma = 0.5;
  double alpha_f = 0.0;  // weight of the old state in forces (HHT alpha = alpha_f)
  double alpha_m = 0.0;  // weight of the old state in inertia
  /// Newmark with TINTP GAMMA amplitude decay g: beta = (1+g)^2/4, gamma = 1/2 + g.
  static GeneralizedAlphaParameters newmark(double amplitude_decay);
  /// Textbook Newmark beta/gamma.
  static GeneralizedAlphaParameters newmark_beta_gamma(double beta, double gamma);
  /// HHT-alpha (ANSYS convention alpha_f >= 0): beta = (1+af-am)^2/4, gamma = 1/2 + af - am.
  static GeneralizedAlphaParameters hht(double alpha_f, double alpha_m = 0.0);
};
std::unique_ptr<TimeIntegrator> make_generalized_alpha(const GeneralizedAlphaParameters& p);

/// Integrator selected by the analysis options (Houbolt / Newmark / HHT with TINTP values).
std::unique_ptr<TimeIntegrator> make_time_integrator(const AnalysisOptions& options);

/// Houbolt amplification matrix A of thesis eq. 3-9 for dt/T and damping ratio xi.
Eigen::Matrix3d houbolt_amplification_matrix(double dt_over_period, double damping_ratio);
/// Spectral radius of a square matrix (max |eigenvalue|), thesis eq. 3-11.
double spectral_radius(const Eigen::MatrixXd& A);

}  // namespace impactfe
