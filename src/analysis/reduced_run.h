#pragma once
/// Pieces shared by the reduced (Guyan) and mode-superposition transients and their expansion
/// pass: the KAN=5 time axis, loads in generalized coordinates, GP gaps, and the state the
/// expansion pass needs (spec §10.4, §10.5).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/analyses.h"
#include "analysis/generalized_history.h"
#include "analysis/progress.h"
#include "assembly/loads.h"
#include "linalg/eigen_solver.h"
#include "reduction/guyan.h"
#include "reduction/reduced_dynamics.h"
#include "time/time_axis.h"

namespace impactfe {

/// Everything the expansion pass needs from the transient that ran before it.
class ReducedRunState : public ReducedSolutionState {
 public:
  // Owned model view (the transient's Structure is gone when the expansion pass runs).
  std::unique_ptr<Structure> structure;
  std::unique_ptr<DofMap> dofs;
  std::unique_ptr<Assembler> assembler;
  SparseMatrix mass_all;
  FrameAccelerationLoad frame_load;  // -M r a (exact for superelements through the element hook)
  std::vector<LoadStep> load_steps;
  double alpha_damping = 0.0, beta_damping = 0.0;

  // Basis: Guyan (u_free = [I; T] u_m + static correction) or modes (u_free = Φ q).
  std::unique_ptr<GuyanReduction> guyan;
  MatrixXd modes;
  std::string method;  // "reduced" or "msup"

  double dt = 0.0;
  ReducedTimeAxis points;
  std::unique_ptr<GeneralizedHistory> history;  // q, q̇, q̈, gap forces of every point

  /// External load over all active DOFs at a computed point (F + ACEL inertia).
  VectorXd external_force(const ReducedPoint& p) const;
  /// F, ACEL and face pressures at a load point (no LVSCALE load vector).
  VectorXd loads_at(const LoadPoint& at) const;
  /// The loads of the modal analysis's load step `number` (LVSCALE), at full value.
  VectorXd modal_load_vector(int number, double time) const;
  /// Free-DOF vector from generalized coordinates; `f` (free-DOF load) adds the static
  /// correction of the slaves (Guyan only).
  VectorXd expand(const VectorXd& gq, const VectorXd* f) const;
  /// Vector over all active DOFs (constrained DOFs zero) from a free-DOF vector.
  VectorXd to_active(const VectorXd& free) const;
};

/// Rebuilds the structure for the state and the DOF numbering of a reduction: constraints of
/// load step 1, plus free DOFs with a zero stiffness diagonal that are not in `keep` (spec U24:
/// they carry mass but nothing restrains them — dropped as constrained slaves, logged).
void prepare_reduced_model(ReducedRunState& state, const Structure& structure,
                           const AnalysisRequest& request, const RunSettings& settings,
                           const std::vector<DofKey>& keep, AnalysisStatistics& stats);

/// Full-storage damping over the active DOFs: element dampers + α M + β K.
SparseMatrix damping_matrix(const ReducedRunState& state, const SparseMatrix& k);

/// The lowest `wanted` modes of K x = λ M x over the free DOFs of the state's model (only modes
/// with mass), mass-normalised; `analysis` names the analysis in messages (msup_transient.cpp).
EigenResult lowest_modes(Structure& structure, const ReducedRunState& state, int wanted,
                         const char* analysis, AnalysisStatistics& stats);

/// Modal damping: Φᵀ C_elem Φ + α I + β diag(ω²) + diag(2 ζ_j ω_j) with ζ_j = DMPRAT +
/// MDAMP(j), for the state's mass-normalised modes (msup_transient.cpp).
MatrixXd modal_damping(const ReducedRunState& state, const AnalysisOptions& options,
                       const VectorXd& omega);

/// GP gap conditions in generalized coordinates. `row(free_index)` gives the row of the basis
/// (b with u_i = bᵀ q); a node without active DOFs (or a constrained DOF) is ground; any other
/// DOF that row() cannot express (returns an empty vector) is an input error.
std::vector<GeneralizedGap> generalized_gaps(const Model& model, const DofMap& dofs,
                                             const std::function<VectorXd(int free_index)>& row,
                                             const std::string& requirement);

/// Runs the time loop shared by both transients: initial state (static solve when load step 1
/// carries loads), integration, a results point per step (`table`: free-DOF values for the
/// nodal tables, NaN where not computed), and the histories kept in the state. `progress`
/// (may be null) is told after every step.
void integrate_reduced(ReducedRunState& state, ReducedDynamics& dynamics,
                       const std::function<VectorXd(const VectorXd& f_free)>& reduce,
                       const std::function<VectorXd(const VectorXd& gq)>& table, const VectorXd& q0,
                       const VectorXd& v0, const std::function<std::string(int)>& coordinate_name,
                       ResultsWriter& writer, AnalysisStatistics& stats, double& seconds_per_step,
                       ProgressObserver* progress);

}  // namespace impactfe
