#pragma once
/// Static and full transient solution on all DOFs: load steps, substeps, Newton-Raphson
/// equilibrium iterations wrapped in the element status loop (gap open/closed, slider), time
/// integration through the TimeIntegrator interface (spec §10.3, §10.7; thesis eqs. 4-13..4-15).
#include <memory>
#include <optional>
#include <vector>

#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "assembly/loads.h"
#include "linalg/linear_solver.h"
#include "results/results_file.h"
#include "time/time_integrator.h"

namespace impactfe {

class DirectSolution {
 public:
  DirectSolution(Structure& structure, ResultsWriter& writer, const RunSettings& settings,
                 AnalysisStatistics& stats);
  /// Runs the load steps. `transient`: dynamic steps (unless TIMINT is off for a step).
  void run(const std::vector<LoadStep>& steps, bool transient);

 private:
  struct StepTiming {
    double t_start = 0.0;
    double t_end = 0.0;
    int n_substeps = 1;
    double h = 0.0;
  };
  StepTiming timing(const LoadStep& step, double t_start, bool transient) const;
  void set_constraints(const LoadStep& step);
  void start_dynamics(const LoadPoint& at, double h);
  VectorXd external_force(const LoadPoint& at) const;
  void solve_increment(const LoadPoint& at, double time, int load_step, int substep, bool dynamic);
  void factorize(const IntegrationCoefficients& coeff, const VectorXd& u);
  void store(double time, int load_step, int substep, bool dynamic);
  void time_step_advice(double h);

  Structure& structure_;
  ResultsWriter& writer_;
  RunSettings settings_;
  AnalysisStatistics& stats_;
  const ElementContext& ctx_;

  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::unique_ptr<LinearSolver> solver_;
  SolverCounters retired_;  // counts of solvers replaced when the constraint set changed
  std::set<DofKey> constrained_;
  SparseMatrix mass_all_;
  FrameAccelerationLoad frame_load_;  // -M r a, assembled once per DOF numbering
  SparseMatrix effective_;
  std::unique_ptr<TimeIntegrator> integrator_;
  bool dynamics_started_ = false;

  // Converged state over all active DOFs, and the force terms of the last converged step.
  VectorXd u_, v_, a_;
  VectorXd f_ext_old_, f_int_old_, f_damp_old_;
  VectorXd reactions_;
  double time_ = 0.0;

  // Factorization bookkeeping: refactor only when the effective matrix can have changed.
  bool factor_valid_ = false;
  IntegrationCoefficients factored_{};

  // Energy balance (spec: kinetic, strain, external work, gap work, dissipation).
  double external_work_ = 0.0, internal_work_ = 0.0, gap_work_ = 0.0, damping_work_ = 0.0;
  std::vector<bool> is_gap_;
  std::vector<VectorXd> gap_force_old_;
  bool advice_given_ = false;  // the time-step advice note is given once per analysis  // gap
                               // element forces at the last converged step
};

}  // namespace impactfe
