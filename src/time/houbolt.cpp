/// Houbolt backward-difference integrator (thesis eqs. 3-2..3-4; Bathe 1996 §9.2.3) with the
/// "uniformly accelerated past motion" start-up of spec §10.2.
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/log.h"
#include "time/integrator_history.h"
#include "time/time_integrator.h"

namespace impactfe {
namespace {

void require_positive_step(double h) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError("Houbolt: the time step must be positive and finite, got " +
                     std::to_string(h));
  }
}

class Houbolt final : public TimeIntegrator, public IntegratorHistory {
 public:
  std::string name() const override { return "Houbolt"; }

  void start(const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, const Eigen::VectorXd& a0,
             double h) override {
    require_positive_step(h);
    IMPACTFE_CHECK(!(v0.size() != u0.size() || a0.size() != u0.size()),
                   "Houbolt::start: u0, v0, a0 sizes differ");
    h_ = h;
    u_ = u0;
    v_ = v0;
    a_ = a0;
    resample_history();
    started_ = true;
  }

  void set_step(double h) override {
    require_positive_step(h);
    // A step recomputed by the driver (e.g. (t_end - t_start)/n) may differ from the current
    // one by round-off; re-sampling then would needlessly replace the true history by a
    // parabola, so changes below 1e-9 relative keep the history.
    const bool same_step = started_ && std::abs(h - h_) <= 1e-9 * h_;
    h_ = h;
    if (same_step) return;
    // v_, a_ are the backward-difference values at the old spacing (or the initial state), so
    // the new history is the parabola through the current state (spec §10.2). It is exact for
    // uniformly accelerated motion, which keeps a free fall exact across the step change.
    if (started_) resample_history();
  }

  double step() const override { return h_; }

  /// K_eff = K + 11/(6h) C + 2/h^2 M (thesis eq. 3-4).
  IntegrationCoefficients coefficients() const override {
    return {1.0, 11.0 / (6.0 * h_), 2.0 / (h_ * h_)};
  }

  ResidualWeights weights() const override { return {1.0, 1.0, 1.0}; }

  /// Taylor predictor u_n + h v_n + h^2/2 a_n with the backward-difference v_n, a_n: exact for
  /// uniformly accelerated motion (free fall converges in one iteration).
  using TimeIntegrator::predict;
  void predict(Eigen::VectorXd& u) const override { u = u_ + h_ * v_ + (0.5 * h_ * h_) * a_; }

  /// Thesis eqs. 3-2, 3-3 at t_{n+1}.
  void kinematics(const Eigen::VectorXd& u_next, Eigen::VectorXd& v_next,
                  Eigen::VectorXd& a_next) const override {
    require_started();
    IMPACTFE_CHECK(!(u_next.size() != u_.size()),
                   "Houbolt::kinematics: trial vector has the wrong size");
    v_next = (11.0 * u_next - 18.0 * u_ + 9.0 * u_m1_ - 2.0 * u_m2_) / (6.0 * h_);
    a_next = (2.0 * u_next - 5.0 * u_ + 4.0 * u_m1_ - u_m2_) / (h_ * h_);
  }

  void advance(const Eigen::VectorXd& u_next) override {
    require_started();
    Eigen::VectorXd v_next, a_next;
    kinematics(u_next, v_next, a_next);
    u_m2_ = std::move(u_m1_);
    u_m1_ = std::move(u_);
    u_ = u_next;
    v_ = std::move(v_next);
    a_ = std::move(a_next);
  }

  /// Houbolt's equation at t_{n+1} holds the load f_{n+1} alone and its a_n is a backward
  /// difference of the displacements (thesis eq. 3-3): a load jump at t_n needs nothing here.
  void jump_acceleration(const Eigen::VectorXd& /*a_jump*/) override {}

  const Eigen::VectorXd& u() const override { return u_; }
  const Eigen::VectorXd& v() const override { return v_; }
  const Eigen::VectorXd& a() const override { return a_; }

  std::vector<Eigen::VectorXd> history() const override { return {u_, v_, a_, u_m1_, u_m2_}; }
  void restore(const std::vector<Eigen::VectorXd>& s, double h) override {
    require_positive_step(h);
    IMPACTFE_CHECK(s.size() == 5, "Houbolt::restore: expected u, v, a, u_{n-1}, u_{n-2}");
    h_ = h;
    u_ = s[0];
    v_ = s[1];
    a_ = s[2];
    u_m1_ = s[3];
    u_m2_ = s[4];
    started_ = true;
  }

 private:
  void require_started() const {
    IMPACTFE_CHECK(!(!started_), "Houbolt: start() must be called first");
  }

  /// u_{n-1} = u_n - h v_n + h^2/2 a_n, u_{n-2} = u_n - 2h v_n + 2h^2 a_n (spec §10.2).
  void resample_history() {
    u_m1_ = u_ - h_ * v_ + (0.5 * h_ * h_) * a_;
    u_m2_ = u_ - (2.0 * h_) * v_ + (2.0 * h_ * h_) * a_;
  }

  double h_ = 0.0;
  bool started_ = false;
  Eigen::VectorXd u_, v_, a_;  // current state u_n, v_n, a_n
  Eigen::VectorXd u_m1_;       // u_{n-1}
  Eigen::VectorXd u_m2_;       // u_{n-2}
};

}  // namespace

std::unique_ptr<TimeIntegrator> make_houbolt() {
  return std::make_unique<Houbolt>();
}

}  // namespace impactfe
