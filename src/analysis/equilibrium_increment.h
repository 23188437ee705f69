#pragma once
/// One increment of a static or full transient run (spec §10.3, §10.7; thesis eqs. 4-13..4-15):
/// the equations at the end of the substep — static f_ext − f_int = 0, dynamic in the
/// generalized-α form of the time integrator — solved by Newton-Raphson with the element status
/// loop, on all free DOFs or, in a transient whose linear part is condensed
/// (linear_part_condensation.h), on the nonlinear elements' DOFs first (condensed_increment.cpp).
/// solve() leaves the converged state untouched and reports what happened (SubstepOutcome); the
/// driver then accepts the increment (elements committed, integrator advanced, work summed) or
/// rejects it (elements reverted: the substep is cut).
#include <optional>
#include <string>

#include "analysis/discretisation.h"
#include "analysis/energy_balance.h"
#include "analysis/motion_state.h"
#include "analysis/run_statistics.h"
#include "analysis/step_loads.h"
#include "nonlinear/newton_raphson.h"
#include "time/time_integrator.h"
#include "time/time_schedule.h"

namespace impactfe {

class EquilibriumIncrement final : private NonlinearProblem {
 public:
  EquilibriumIncrement(const Structure& structure, const RunSettings& settings,
                       AnalysisStatistics& stats, MotionState& state, const StepLoads& loads,
                       EnergyBalance& energy);

  /// The discretisation and time integrator (nullptr: static) the increments are solved on;
  /// again after every renumbering.
  void bind(Discretisation& disc, TimeIntegrator* integrator);

  /// The start of the time integration at load point `at` with step h: the accelerations from
  /// equilibrium, M a0 = f(0) − C v0 − f_int(u0), on the DOFs that carry mass (spec §10.2;
  /// massless DOFs get a0 = 0).
  void start_motion(const LoadPoint& at, double h);
  /// Solves the increment to load point `at`. `may_cut` (automatic time stepping): a failure
  /// (no convergence, status chatter, a non-finite or singular solution) is reported in the
  /// outcome instead of thrown (SolutionError), and a KEYOPT(7) contact's penetration checked.
  SubstepOutcome find_equilibrium(const LoadPoint& at, const StepLabel& label, bool dynamic,
                                  bool may_cut);
  /// The increment solved last is the converged state: elements committed, work summed into
  /// the energy balance, the integrator advanced.
  void accept();
  /// The increment solved last is discarded: elements back to their committed states.
  void reject();
  /// Status changes of the increment solved last.
  int status_changes() const { return inc_.n_status_changes; }
  /// The next static find_equilibrium starts from u_n + `delta` (free DOFs; the prescribed ones
  /// take their values) instead of u_n: the substep predictor of creep steps (DirectSolution).
  /// Used once; ignored when its size is not the state's.
  void predict_static(VectorXd delta) { static_delta_ = std::move(delta); }

  /// The run summary's line on the condensed transient (empty when it never applied).
  std::string condensation_summary() const;
  /// "; the condensed tangent: N factorization(s), M rank-one update(s)".
  std::string condensed_tangent_note() const;

 private:
  void prepare(const LoadPoint& at, const StepLabel& label, bool dynamic, VectorXd& u);
  NewtonOptions newton_options(const LoadPoint& at) const;
  /// Why a substep that may be cut failed (empty: it converged), from Newton's result at u.
  std::string failure(const NewtonResult& result, bool finite) const;
  /// The SolutionError of a substep that did not converge (a warning with
  /// --continue-on-nonconvergence).
  void report_no_convergence(const NewtonResult& result, const VectorXd& u, const StepLabel& label);
  /// A dynamic increment on the condensed system; false when the full Newton path must take
  /// over (from the returned state), with `result` holding the condensed iterations.
  bool solve_condensed(VectorXd& u, const NewtonOptions& newton, NewtonResult& result);
  void factorize(const IntegrationCoefficients& coeff, const VectorXd& u);
  /// The error of a singular effective matrix at DOF `column`.
  [[noreturn]] void fail_singular(const IntegrationCoefficients& coeff, int column);
  void warn_negative_pivots(const IntegrationCoefficients& coeff);
  /// Names the free DOF with the largest out-of-balance force at u and its elements.
  std::string largest_residual(const VectorXd& u);
  /// SolutionError at the first DOF whose value (or force) is NaN or infinite.
  [[noreturn]] void fail_not_finite(const VectorXd& u, const StepLabel& label);
  /// M a, from the last residual evaluation when a is the same vector (the accepted step's
  /// acceleration is needed again for its reactions and the next step's fixed terms).
  const VectorXd& inertia_of(const VectorXd& a);

  // ---- NonlinearProblem: the equations of the current increment ----------------------------
  int n_unknowns() const override { return disc_->dofs().n_free(); }
  double residual(const VectorXd& u, VectorXd& r, double& reference) override;
  bool tangent_stale() const override { return !disc_->factor_valid(); }
  void factorize_tangent(const VectorXd& u) override { factorize(inc_.coeff, u); }
  VectorXd solve(const VectorXd& r) override { return disc_->solver().solve(r); }
  bool update_status(const VectorXd& u) override;
  void expect_tangent(bool likely) override { tangent_expected_ = likely; }

  const Structure& structure_;
  const RunSettings& settings_;
  AnalysisStatistics& stats_;
  MotionState& state_;
  const StepLoads& loads_;
  EnergyBalance& energy_;
  Discretisation* disc_ = nullptr;
  TimeIntegrator* integrator_ = nullptr;

  // The increment being solved: integration coefficients, residual weights, the load at its
  // end, the residual terms fixed within it, and the latest iterate's forces.
  struct Increment {
    bool dynamic = false;
    IntegrationCoefficients coeff;
    ResidualWeights weights;
    VectorXd f_ext;
    VectorXd fixed_terms;  // dynamic: old-state forces and inertia (generalized-α form)
    VectorXd v, a, f_int, f_damp, inertia;  // inertia = M a
    StepLabel label;
    int n_status_changes = 0;
    LoadPoint at;           // the load point of the increment
    bool follower = false;  // face pressures that follow the deformation (large deflection)
    VectorXd f_pressure;    // their load at the latest iterate
  } inc_;
  /// The iterate u, and a condensed step's residual and correction over the active / free DOFs,
  /// kept from step to step: a vector of model size allocated per step is a fresh mapping on
  /// large models, faulted in page by page.
  VectorXd step_state_, step_residual_, step_correction_;
  VectorXd static_delta_;  // predict_static
  VectorXd inertia_a_, inertia_;
  /// Newton said that a factorization at the next residual's iterate will follow: that
  /// residual forms the element tangents too (read and cleared by residual()).
  bool tangent_expected_ = false;
  bool negative_pivot_warned_ = false;  // the negative-pivot warning is given once per analysis
  std::string condensation_note_;
  long condensed_steps_ = 0, full_fallback_steps_ = 0;
};

}  // namespace impactfe
