#pragma once
/// Analysis drivers. Each gets the solvable structure, the request (options + load steps) and
/// the results writer; none knows element internals.
#include <memory>
#include <string>

#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "results/results_file.h"

namespace impactfe {

class DirectSolution;
/// Opens a linear or nonlinear static analysis (KAN,0 / ANTYPE,STATIC; spec §10.7) or a full
/// (nonlinear) transient (KAN,4 / TRNOPT,FULL; spec §10.3), as the structure's options say: the
/// results analysis is begun and the solution waits for its load steps. `known_steps`: the load
/// steps known now (planned once); `count_points`: they are all the analysis has, so the
/// results file's time blocks are sized to the points they store.
std::unique_ptr<DirectSolution> begin_direct_analysis(Structure& structure, ResultsWriter& writer,
                                                      const RunSettings& settings,
                                                      AnalysisStatistics& stats,
                                                      const std::vector<LoadStep>& known_steps,
                                                      bool count_points);
/// The number of modes a modal or mode-superposition analysis can compute: `wanted`, or fewer
/// when fewer free DOFs carry mass (noted in `stats`). ModelError naming the materials without
/// density when no free DOF has mass (the mass matrix is zero: no frequency exists).
int modes_with_mass(const Structure& structure, const SparseMatrix& m_lower, int wanted,
                    const char* analysis, AnalysisStatistics& stats);
/// Single-point response spectrum analysis (ANTYPE,SPECTR + SPOPT,SPRS; spectrum_analysis.cpp):
/// the modes of the model again, their participation in the excitation direction, the mode
/// coefficients from the spectrum, the combined response and the missing mass response.
void run_spectrum_analysis(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings& settings,
                           AnalysisStatistics& stats);
/// Harmonic response (ANTYPE,HARMIC + HROPT,FULL or MSUP): the complex steady-state response at
/// each frequency of the load steps (harmonic_analysis.cpp).
void run_harmonic_analysis(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings& settings,
                           AnalysisStatistics& stats);
/// The modes of K x = λ M x over the free DOFs of the first load step's constraints (MODOPT:
/// count, frequency window), as a modal analysis and the analyses built on its modes use them.
struct ModalSolution {
  std::unique_ptr<DofMap> dofs;
  std::unique_ptr<Assembler> assembler;  // over `dofs`
  SparseMatrix k_lower, m_lower;         // lower triangles over the free DOFs
  std::vector<double> frequencies;       // Hz, ascending
  MatrixXd shapes;                       // free DOFs x modes, mass-normalised (φᵀ M φ = 1)
  /// The factor from the mass-normalised shape to the stored one (MODOPT Nrmkey ON: largest
  /// component 1; else 1).
  VectorXd stored_scale;
};
ModalSolution solve_modes(Structure& structure, const AnalysisRequest& request,
                          AnalysisStatistics& stats, const char* analysis);
/// Modal analysis (ANTYPE,MODAL + MODOPT): natural frequencies (Hz) and mode shapes.
void run_modal_analysis(Structure& structure, const AnalysisRequest& request, ResultsWriter& writer,
                        const RunSettings& settings, AnalysisStatistics& stats);

}  // namespace impactfe

namespace impactfe {

/// State a reduced (KAN,5 / TRNOPT,REDUC) or MSUP transient leaves for its expansion pass.
struct ReducedSolutionState {
  virtual ~ReducedSolutionState() = default;
};

/// Reduced linear transient on master DOFs with GP gap conditions (spec §10.4).
void run_reduced_transient(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings& settings,
                           AnalysisStatistics& stats,
                           std::unique_ptr<ReducedSolutionState>& state_for_expansion);
/// Mode-superposition transient (TRNOPT,MSUP) with GP gap conditions.
void run_msup_transient(Structure& structure, const AnalysisRequest& request, ResultsWriter& writer,
                        const RunSettings& settings, AnalysisStatistics& stats,
                        std::unique_ptr<ReducedSolutionState>& state_for_expansion);
/// Expansion ("stress") pass of the preceding reduced / MSUP transient (spec §10.5).
void run_expansion_pass(const ExpansionPassRequest& request, ReducedSolutionState* state,
                        ResultsWriter& writer, const RunSettings& settings,
                        AnalysisStatistics& stats);
/// Superelement expansion pass (EXPASS + SEEXP; spec §10.6): the use pass's master histories
/// expanded to the whole substructure, appended to `writer` as one Expansion analysis.
void run_superelement_expansion(const ExpansionPassRequest& request, ResultsWriter& writer,
                                AnalysisStatistics& stats);
/// Superelement generation (KAN,7 / ANTYPE,SUBSTR; spec §10.6): writes <jobname>.sub.h5.
/// Under MPI with several ranks, one rank generates it (round-robin over the passes, docs/
/// scaling.md) and the others only record it until share_generated_superelements.
void run_substructure_generation(Structure& structure, const AnalysisRequest& request,
                                 ResultsWriter& writer, const RunSettings& settings,
                                 AnalysisStatistics& stats, const std::string& jobname);
/// Copies the superelement files generated so far by one rank each to every rank (collective
/// under MPI; nothing to do otherwise). Before a pass that may read them and at the end of a run.
void share_generated_superelements();

}  // namespace impactfe
