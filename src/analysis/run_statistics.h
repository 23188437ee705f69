#pragma once
/// Counters and figures of a run, printed in the run summary and stored as attributes.
#include <string>
#include <vector>

namespace impactfe {

struct AnalysisStatistics {
  std::string description;  // e.g. "transient (full, Houbolt)"
  int n_dofs = 0;           // free DOFs
  int n_load_steps = 0;
  int n_substeps = 0;
  int n_iterations = 0;  // equilibrium iterations
  int n_stored = 0;      // time points written
  long n_analyses = 0;   // symbolic factorizations
  long n_factorizations = 0;
  long n_solves = 0;
  int n_status_changes = 0;
  double wall_seconds = 0.0;
  std::vector<std::string> notes;  // time-step advice, energy balance, ...
};

struct RunStatistics {
  std::vector<AnalysisStatistics> analyses;
};

}  // namespace impactfe
