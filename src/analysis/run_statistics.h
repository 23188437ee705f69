#pragma once
/// Counters and figures of a run, printed in the run summary and stored as attributes.
#include <string>
#include <vector>

#include "linalg/linear_solver.h"

namespace impactfe {

struct AnalysisStatistics {
  std::string description;  // e.g. "transient (full, Houbolt)"
  int n_dofs = 0;           // free DOFs
  int n_load_steps = 0;
  int n_substeps = 0;
  int n_iterations = 0;      // equilibrium iterations
  bool line_search = false;  // LNSRCH on
  int n_line_searches = 0;   // corrections the line search shortened
  int n_stored = 0;          // time points written
  long n_analyses = 0;       // symbolic factorizations
  long n_factorizations = 0;
  long n_solves = 0;
  // Linear solver figures (SolverCounters): phase times and the sizes of the largest factor.
  double analyze_seconds = 0.0;
  double factorize_seconds = 0.0;
  double solve_seconds = 0.0;
  long matrix_nonzeros = 0;  // nnz of the factored matrix (lower triangle)
  long factor_nonzeros = 0;  // nnz(L)
  long factor_bytes = 0;     // bytes of L a solve reads
  int n_status_changes = 0;
  int n_cuts = 0;  // automatic time stepping: substeps cut (bisected) and retried
  double wall_seconds = 0.0;
  /// Wall time of the substeps alone (a direct solution's stepping loops, factorizations in
  /// them included; 0 for the other drivers): the benchmark's time per step.
  double stepping_seconds = 0.0;
  std::vector<std::string> notes;  // time-step advice, energy balance, ...
};

/// Copies a linear solver's counters (counts, phase times, factor sizes) into `stats`.
inline void record_solver_counters(AnalysisStatistics& stats, const SolverCounters& c) {
  stats.n_analyses = c.analyses;
  stats.n_factorizations = c.factorizations;
  stats.n_solves = c.solves;
  stats.analyze_seconds = c.analyze_seconds;
  stats.factorize_seconds = c.factorize_seconds;
  stats.solve_seconds = c.solve_seconds;
  stats.matrix_nonzeros = c.matrix_nonzeros;
  stats.factor_nonzeros = c.factor_nonzeros;
  stats.factor_bytes = c.factor_bytes;
}

struct RunStatistics {
  std::vector<AnalysisStatistics> analyses;
};

}  // namespace impactfe
