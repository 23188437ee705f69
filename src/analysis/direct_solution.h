#pragma once
/// Static and full transient solution on all DOFs (spec §10.3, §10.7; thesis eqs. 4-13..4-15):
/// load steps and substeps from the time axis, each increment solved by Newton-Raphson with the
/// element status loop (src/nonlinear), time integration through the TimeIntegrator interface,
/// energy balance and time-step advice as units of their own. The driver knows neither element
/// kinds nor the time scheme.
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "analysis/energy_balance.h"
#include "analysis/linear_part_condensation.h"
#include "analysis/restart_file.h"
#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "analysis/time_step_advice.h"
#include "assembly/loads.h"
#include "elements/penetration_check.h"
#include "linalg/linear_solver.h"
#include "nonlinear/newton_raphson.h"
#include "nonlinear/status_loop.h"
#include "results/output_selection.h"
#include "results/results_file.h"
#include "time/step_control.h"
#include "time/time_integrator.h"

namespace impactfe {

class DirectSolution : private NonlinearProblem {
 public:
  DirectSolution(Structure& structure, ResultsWriter& writer, const RunSettings& settings,
                 AnalysisStatistics& stats);
  /// Runs the load steps. `transient`: dynamic steps (unless TIMINT is off for a step).
  void run(const std::vector<LoadStep>& steps, bool transient);

  /// The same, one load step at a time (MAPDL solves a load step when SOLVE is read): begin,
  /// then solve_load_step for each load step in order, then finish.
  void begin(bool transient);
  void solve_load_step(const LoadStep& step);
  /// The load steps known to come after the one being solved (for the progress estimate of
  /// the whole run); empty by default.
  void set_following_steps(std::vector<LoadStep> steps);
  void finish();
  /// "; the condensed tangent: N factorization(s), M rank-one update(s)" (run summary).
  std::string condensed_tangent_note() const;

 private:
  void update_counters();
  void set_constraints(const LoadStep& step);
  /// A new DOF numbering (DofMap, Assembler, status loop, solver, condensation) for the
  /// constraint set `wanted`, the state remapped by DOF key. `keep_dynamics`: the integrator
  /// continues (its history remapped) instead of restarting (direct_solution_connectivity.cpp).
  void renumber(std::set<DofKey> wanted, bool keep_dynamics);
  /// After an accepted step: elements whose DOFs follow the deformation (contact on deformable
  /// targets with large sliding, elements/connectivity.h) re-find them; renumbers when one
  /// changed (direct_solution_connectivity.cpp).
  void refresh_connectivity();
  /// The integrator's history vectors from numbering `from` to `to` (by DOF key).
  void remap_integrator(const DofMap& from, const DofMap& to);
  void start_dynamics(const LoadPoint& at, double h);
  VectorXd external_force(const LoadPoint& at) const;
  void external_force(const LoadPoint& at, VectorXd& f) const;
  LoadPoint load_point(const LoadStep& step, const LoadStep* previous, double fraction,
                       double time) const;
  /// Solves one increment and accepts it. `may_cut` (automatic time stepping): a failure
  /// (no convergence, status chatter, a non-finite or singular solution) returns false with
  /// `cut_reason_` set and the state untouched, instead of the SolutionError.
  bool solve_increment(const LoadPoint& at, const StepLabel& label, bool dynamic,
                       bool may_cut = false);
  /// The substeps of a load step at constant Δt, or under AUTOTS (direct_solution_steps.cpp).
  struct StepContext {
    const LoadStep& step;
    const LoadStep* previous;
    const LoadStepTiming& timing;
    bool dynamic;
    long long later_substeps;
    double run_end;
  };
  void solve_constant_steps(const StepContext& c);
  void solve_automatic_steps(const StepContext& c, const AutoStepPlan& plan);
  /// Gives the integrator step h (Houbolt re-samples its history on a change).
  void change_step(double h);
  // Restart points (direct_solution_restart.cpp): ANTYPE,,RESTART read in begin(), applied at
  // the first load step (after its DOF numbering); RESCONTROL points written after substeps.
  void take_restart_request();
  void apply_restart(const LoadStep& step);
  /// `control`: the step controller of an AUTOTS load step (its state is part of the point).
  void save_restart_point(const LoadStep& step, int substep, bool last, double t_start,
                          const StepController* control = nullptr);
  /// A dynamic increment on the condensed system; false when the full Newton path must take
  /// over (from the returned state), with `result` holding the condensed iterations.
  bool solve_condensed(VectorXd& u, const NewtonOptions& newton, NewtonResult& result);
  void factorize(const IntegrationCoefficients& coeff, const VectorXd& u);
  void store(double time, int load_step, int substep, bool dynamic,
             const OutputSelection& selection);
  void time_step_advice(double h);
  /// "elements 3, 4" carrying active DOF `index` (for messages).
  std::string elements_at(int index) const;
  /// Names the free DOF with the largest out-of-balance force at u and its elements.
  std::string largest_residual(const VectorXd& u);
  /// SolutionError at the first DOF whose value (or force) is NaN or infinite.
  [[noreturn]] void fail_not_finite(const VectorXd& u, const StepLabel& label);

  // ---- NonlinearProblem: the equations of the current increment ----------------------------
  int n_unknowns() const override;
  double residual(const VectorXd& u, VectorXd& r, double& reference) override;
  bool tangent_stale() const override { return !factor_valid_; }
  void factorize_tangent(const VectorXd& u) override { factorize(increment_.coeff, u); }
  VectorXd solve(const VectorXd& r) override { return solver_->solve(r); }
  bool update_status(const VectorXd& u) override;
  void expect_tangent(bool likely) override { tangent_expected_ = likely; }

  Structure& structure_;
  ResultsWriter& writer_;
  RunSettings settings_;
  AnalysisStatistics& stats_;
  const ElementContext& ctx_;

  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::unique_ptr<StatusLoop> status_loop_;
  std::unique_ptr<LinearSolver> solver_;
  SolverCounters retired_;  // counts of solvers replaced when the constraint set changed
  std::set<DofKey> constrained_;
  /// ½ vᵀ M v from the assembler's global products (no copy of M is kept).
  double kinetic_energy() const { return 0.5 * v_.dot(assembler_->inertia_force(v_)); }
  FrameAccelerationLoad frame_load_;  // -M r a, assembled once per DOF numbering
  SparseMatrix effective_;
  std::unique_ptr<TimeIntegrator> integrator_;
  bool transient_ = false;
  bool dynamics_started_ = false;
  std::optional<LoadStep> previous_;  // the last load step solved (KBC ramps start from it)
  double t_end_ = 0.0;                // end time of the last load step solved
  std::vector<LoadStep> following_;   // load steps known to come after the current one
  // F and D of the load step being solved, resolved to DOF indices (set per load step).
  ResolvedDofLoads forces_, prescribed_;
  const LoadStep* resolved_step_ = nullptr;
  const LoadStep* resolved_previous_ = nullptr;
  // Elements with a DOF list that follows the deformation (indices; found once), the refresh
  // passes made and the renumberings they caused.
  std::optional<std::vector<std::size_t>> connectivity_;
  long long refresh_passes_ = 0;
  int renumberings_ = 0;

  // Converged state over all active DOFs, and the force terms of the last converged step.
  VectorXd u_, v_, a_;
  VectorXd f_ext_old_, f_int_old_, f_damp_old_;
  VectorXd reactions_;
  Vec3 acel_ = Vec3::Zero();  // frame acceleration of the last converged step
  double time_ = 0.0;

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
  } increment_;

  // Factorization bookkeeping: refactor only when the effective matrix can have changed.
  bool factor_valid_ = false;
  IntegrationCoefficients factored_{};

  /// M a, from the last residual evaluation when a is the same vector (the accepted step's
  /// acceleration is needed again for its reactions and the next step's fixed terms).
  const VectorXd& inertia_of(const VectorXd& a);
  VectorXd inertia_a_, inertia_;

  std::unique_ptr<EnergyBalance> energy_;
  // Condensed transient (linear_part_condensation.h): set up per DOF numbering when it applies.
  std::unique_ptr<LinearPartCondensation> condensation_;
  std::string condensation_note_;
  /// A condensed step's residual and correction over the active / free DOFs, kept from step to
  /// step: a vector of model size allocated per step is a fresh mapping on large models,
  /// faulted in page by page (issue 11).
  VectorXd step_residual_, step_correction_;
  VectorXd step_state_;  // the iterate u of solve_increment
  long condensed_steps_ = 0, full_fallback_steps_ = 0;
  // Automatic time stepping: the contact frequency of the closed gaps (the step ceiling), the
  // reason of the last failed attempt, the last step size (Carry).
  std::unique_ptr<ContactFrequencyEstimator> contact_frequency_;
  std::string cut_reason_;
  double impact_step_limit_ = 0.0;  // AUTOTS: a status change in a longer step cuts it (0: off)
  // Contact elements with KEYOPT(7) = 1 (elements/penetration_check.h), per DOF numbering: their
  // index and interface; under AUTOTS a converged substep with too much penetration is cut.
  std::vector<std::pair<std::size_t, const PenetrationCheck*>> penetration_checks_;
  /// The cut reason when a KEYOPT(7) contact penetrates more than FTOLN·depth at u and the
  /// substep from u_ added more than that (PenetrationCheck); empty if none.
  std::string excessive_penetration(const VectorXd& u) const;
  std::optional<double> last_dt_;
  // Continuing from a restart point: the point (until applied), the load-step numbers and the
  // first substep of the continued load step.
  std::unique_ptr<RestartPoint> restart_;
  int load_step_offset_ = 0;
  int first_substep_ = 1;
  bool restarted_ = false;
  // The AUTOTS controller state of a point inside an AUTOTS load step (until the step resumes).
  std::optional<StepController::State> resume_autots_;
  double resume_autots_t_end_ = 0.0;
  bool advice_given_ = false;  // the time-step advice note is given once per analysis
  /// Newton said that a factorization at the next residual's iterate will follow: that
  /// residual forms the element tangents too (read and cleared by residual()).
  bool tangent_expected_ = false;
  bool negative_pivot_warned_ = false;  // the negative-pivot warning is given once per analysis
};

}  // namespace impactfe
