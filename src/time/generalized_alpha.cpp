/// Newmark / HHT-alpha / Chung-Hulbert generalized-alpha in one class (Chung & Hulbert 1993;
/// Hilber, Hughes & Taylor 1977; Newmark 1959). Old-state weights alpha_f, alpha_m follow the
/// ANSYS/Chung-Hulbert convention: f_{n+1-af} = (1-af) f_{n+1} + af f_n.
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "time/integrator_history.h"
#include "time/time_integrator.h"

namespace impactfe {

GeneralizedAlphaParameters GeneralizedAlphaParameters::newmark(double amplitude_decay) {
  const double g = amplitude_decay;
  return newmark_beta_gamma(0.25 * (1.0 + g) * (1.0 + g), 0.5 + g);
}

GeneralizedAlphaParameters GeneralizedAlphaParameters::newmark_beta_gamma(double beta,
                                                                          double gamma) {
  GeneralizedAlphaParameters p;
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

GeneralizedAlphaParameters GeneralizedAlphaParameters::hht(double alpha_f, double alpha_m) {
  GeneralizedAlphaParameters p;
  p.alpha_f = alpha_f;
  p.alpha_m = alpha_m;
  const double s = 1.0 + alpha_f - alpha_m;
  p.beta = 0.25 * s * s;
  p.gamma = 0.5 + alpha_f - alpha_m;
  return p;
}

namespace {

class GeneralizedAlpha final : public TimeIntegrator, public IntegratorHistory {
 public:
  explicit GeneralizedAlpha(const GeneralizedAlphaParameters& p) : p_(p) {
    if (!(p.beta > 0.0)) {
      throw InputError("Newmark: beta (TINTP ALPHA) must be positive for an implicit scheme, got " +
                       std::to_string(p.beta));
    }
    if (!(p.alpha_f >= 0.0 && p.alpha_f < 1.0) || !(p.alpha_m < 1.0)) {
      throw InputError("generalized-alpha: need 0 <= alpha_f < 1 and alpha_m < 1");
    }
  }

  std::string name() const override {
    if (p_.alpha_f == 0.0 && p_.alpha_m == 0.0) return "Newmark";
    if (p_.alpha_m == 0.0) return "HHT-alpha";
    return "generalized-alpha";
  }

  void start(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, const Eigen::VectorXd& a0,
             double h) override {
    set_step(h);
    IMPACTFE_CHECK(!(v0.size() != u0.size() || a0.size() != u0.size()),
                   "GeneralizedAlpha::start: u0, v0, a0 sizes differ");
    u_ = u0;
    v_ = v0;
    a_ = a0;
    started_ = true;
  }

  /// One-step scheme: the state (u, v, a) needs no re-sampling.
  void set_step(double h) override {
    if (!(h > 0.0) || !std::isfinite(h)) {
      throw InputError("Newmark: the time step must be positive and finite, got " +
                       std::to_string(h));
    }
    h_ = h;
  }
  double step() const override { return h_; }

  /// cK = 1-af, cC = (1-af) gamma/(beta h), cM = (1-am)/(beta h^2).
  IntegrationCoefficients coefficients() const override {
    const double wk = 1.0 - p_.alpha_f;
    return {wk, wk * p_.gamma / (p_.beta * h_), (1.0 - p_.alpha_m) / (p_.beta * h_ * h_)};
  }

  ResidualWeights weights() const override {
    return {1.0 - p_.alpha_f, 1.0 - p_.alpha_f, 1.0 - p_.alpha_m};
  }

  /// Constant-acceleration predictor (a_{n+1} = a_n): u_n + h v_n + h^2/2 a_n.
  using TimeIntegrator::predict;
  void predict(Eigen::VectorXd& u) const override { u = u_ + h_ * v_ + (0.5 * h_ * h_) * a_; }

  /// Newmark kinematics: a_{n+1} = (u_{n+1} - u_n - h v_n - h^2 (1/2 - beta) a_n)/(beta h^2),
  /// v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1}).
  void kinematics(const Eigen::VectorXd& u_next, Eigen::VectorXd& v_next,
                  Eigen::VectorXd& a_next) const override {
    IMPACTFE_CHECK(!(!started_), "GeneralizedAlpha: start() must be called first");
    IMPACTFE_CHECK(!(u_next.size() != u_.size()),
                   "GeneralizedAlpha::kinematics: trial vector has the wrong size");
    const double h2 = h_ * h_;
    a_next = (u_next - u_ - h_ * v_ - (h2 * (0.5 - p_.beta)) * a_) / (p_.beta * h2);
    v_next = v_ + (h_ * (1.0 - p_.gamma)) * a_ + (h_ * p_.gamma) * a_next;
  }

  void advance(const Eigen::VectorXd& u_next) override {
    // Into kept vectors, swapped in: a step allocates no vector of model size (issue 11).
    kinematics(u_next, v_next_, a_next_);
    u_ = u_next;
    v_.swap(v_next_);
    a_.swap(a_next_);
  }

  void jump_acceleration(const Eigen::VectorXd& a_jump) override {
    IMPACTFE_CHECK(started_ && a_jump.size() == a_.size(),
                   "GeneralizedAlpha::jump_acceleration: not started or wrong size");
    a_ = a_jump;
  }

  const Eigen::VectorXd& u() const override { return u_; }
  const Eigen::VectorXd& v() const override { return v_; }
  const Eigen::VectorXd& a() const override { return a_; }

  std::vector<Eigen::VectorXd> history() const override { return {u_, v_, a_}; }
  void restore(const std::vector<Eigen::VectorXd>& s, double h) override {
    IMPACTFE_CHECK(s.size() == 3 && h > 0.0, "GeneralizedAlpha::restore: expected u, v, a, h > 0");
    h_ = h;
    u_ = s[0];
    v_ = s[1];
    a_ = s[2];
    started_ = true;
  }

  const GeneralizedAlphaParameters& parameters() const { return p_; }

 private:
  GeneralizedAlphaParameters p_;
  double h_ = 0.0;
  bool started_ = false;
  Eigen::VectorXd u_, v_, a_;
  Eigen::VectorXd v_next_, a_next_;  // scratch of advance
};

}  // namespace

std::unique_ptr<TimeIntegrator> make_generalized_alpha(const GeneralizedAlphaParameters& p) {
  return std::make_unique<GeneralizedAlpha>(p);
}

}  // namespace impactfe
