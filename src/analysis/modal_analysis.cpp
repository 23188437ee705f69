#include <cmath>
#include <limits>

#include "analysis/analyses.h"
#include "analysis/damped_modes.h"
#include "assembly/loads.h"
#include "core/log.h"
#include "linalg/eigen_solver.h"
#include "linalg/linear_solver.h"

namespace impactfe {

int modes_with_mass(const Structure& structure, const SparseMatrix& m_lower, int wanted,
                    const char* analysis, AnalysisStatistics& stats) {
  int massive = 0;
  for (int i = 0; i < m_lower.rows(); ++i)
    if (m_lower.coeff(i, i) > 0.0) ++massive;
  if (massive == 0) {
    std::string no_density;
    for (const auto& [id, mat] : structure.model().materials)
      if (!(mat.get("DENS", 0.0) > 0.0)) no_density += " " + std::to_string(id);
    throw ModelError(fmt::format(
        "{}: the mass matrix is zero (no free DOF carries mass), so no natural frequency "
        "exists; give the material a density (MP,DENS{}) or add point masses (MASS21)",
        analysis, no_density.empty() ? std::string() : "; material(s) without DENS:" + no_density));
  }
  if (massive < wanted) {
    stats.notes.push_back(
        fmt::format("{}: only {} free DOF(s) carry mass, so at most {} modes exist ({} requested)",
                    analysis, massive, massive, wanted));
    return massive;
  }
  return wanted;
}

namespace {

/// MODOPT,QRDAMP: the damped modes of the system projected on the undamped ones (damped_modes.h)
/// with the damping of the model: element dampers (COMBIN14/40 ...), α M + β K (ALPHAD, BETAD)
/// and the modal ratios DMPRAT + MDAMP(j) (2 ζ_j ω_j on the diagonal). Stored as the analysis's
/// attributes damped_frequency_<n> and stability_<n> (Hz: Im λ / 2π, Re λ / 2π; *GET MODE DFRQ,
/// STAB); the mode shapes stay the undamped real ones.
void write_qr_damped_modes(const Structure& structure, const Assembler& assembler,
                           const MatrixXd& phi, const VectorXd& omega, ResultsWriter& writer,
                           AnalysisStatistics& stats) {
  const AnalysisOptions& options = structure.options();
  const int nf = static_cast<int>(phi.rows());
  SparseMatrix c_free;
  if (assembler.has_damping())
    c_free =
        assembler.damping_matrix(VectorXd::Zero(assembler.dofs().n_active())).topLeftCorner(nf, nf);
  MatrixXd cm = project_modal_damping(phi, c_free, options, omega);
  // α M + β K in the mass-normalised modes: α I + β diag(ω²).
  cm.diagonal().array() += options.alpha_damping + options.beta_damping * omega.array().square();
  const std::vector<DampedMode> modes = damped_modes(omega, cm);
  std::vector<double> stability, damped;
  for (const DampedMode& m : modes) {
    stability.push_back(m.stability / (2.0 * M_PI));
    damped.push_back(m.damped_frequency / (2.0 * M_PI));
  }
  for (std::size_t j = 0; j < modes.size(); ++j) {
    writer.set_attribute(fmt::format("damped_frequency_{}", j + 1), damped[j]);
    writer.set_attribute(fmt::format("stability_{}", j + 1), stability[j]);
  }
  for (std::size_t j = 0; j < modes.size(); ++j)
    stats.notes.push_back(
        fmt::format("QRDAMP mode {}: damped frequency {:.6g} Hz, stability {:.6g} Hz", j + 1,
                    damped[j], stability[j]));
}

}  // namespace

ModalSolution solve_modes(Structure& structure, const AnalysisRequest& request,
                          AnalysisStatistics& stats, const char* analysis) {
  const ModalOptions& modal = structure.options().modal;
  const LoadStep empty;
  const LoadStep& step = request.load_steps.empty() ? empty : request.load_steps.front();
  ModalSolution sol;
  sol.dofs = std::make_unique<DofMap>(structure.elements(), structure.constraints_of(step),
                                      structure.coupled_dofs(), structure.dependent_dofs());
  const DofMap& dofs = *sol.dofs;
  sol.assembler = std::make_unique<Assembler>(structure.elements(), dofs, structure.context());
  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  SparseMatrix& k = sol.k_lower;
  SparseMatrix& m = sol.m_lower;
  k.resize(dofs.n_free(), dofs.n_free());
  m.resize(dofs.n_free(), dofs.n_free());
  sol.assembler->assemble({1.0, 0.0, 0.0}, zero, zero, Assembler::Output{&k, nullptr, nullptr});
  sol.assembler->assemble({0.0, 0.0, 1.0}, zero, zero, Assembler::Output{&m, nullptr, nullptr});
  stats.n_dofs = dofs.n_free();

  // Shift below the lowest wanted eigenvalue: FREQB when given, else slightly negative so that
  // rigid-body modes (λ = 0) are found and K − σM stays regular.
  double shift = 0.0;
  if (modal.freq_begin && *modal.freq_begin > 0.0) {
    shift = std::pow(2.0 * M_PI * *modal.freq_begin, 2);
  } else {
    double ratio_sum = 0.0;
    int count = 0;
    for (int i = 0; i < dofs.n_free(); ++i)
      if (m.coeff(i, i) > 0.0 && k.coeff(i, i) > 0.0) {
        ratio_sum += k.coeff(i, i) / m.coeff(i, i);
        ++count;
      }
    shift = -1e-6 * (count > 0 ? ratio_sum / count : 1.0);
  }
  const int n_modes = modes_with_mass(structure, m, modal.n_modes, analysis, stats);
  EigenResult eig;
  try {
    eig = lowest_eigenpairs(k, m, n_modes, shift);
  } catch (const SingularMatrixError& e) {
    throw ModelError(
        e.column() >= 0
            ? fmt::format("{}: {} has neither stiffness nor mass coupling (singular K - sigma M)",
                          analysis, describe(dofs.key(e.column())))
            : fmt::format("{}: K - sigma M is singular (a DOF has neither stiffness nor mass)",
                          analysis));
  }
  std::vector<int> kept;
  for (int j = 0; j < eig.eigenvalues.size(); ++j) {
    const double f = std::sqrt(std::max(eig.eigenvalues(j), 0.0)) / (2.0 * M_PI);
    if (modal.freq_end && f > *modal.freq_end) break;
    if (modal.freq_begin && f < *modal.freq_begin) continue;
    kept.push_back(j);
    sol.frequencies.push_back(f);
  }
  sol.shapes.resize(dofs.n_free(), static_cast<Eigen::Index>(kept.size()));
  sol.stored_scale.resize(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t c = 0; c < kept.size(); ++c) {
    const auto col = static_cast<Eigen::Index>(c);
    sol.shapes.col(col) = eig.eigenvectors.col(kept[c]);
    sol.stored_scale(col) =
        modal.normalize_to_unity ? 1.0 / sol.shapes.col(col).cwiseAbs().maxCoeff() : 1.0;
  }
  return sol;
}

void run_modal_analysis(Structure& structure, const AnalysisRequest& request, ResultsWriter& writer,
                        const RunSettings&, AnalysisStatistics& stats) {
  stats.description = "modal";
  writer.begin_analysis(ResultsKind::Modal, "modal analysis");
  const ModalSolution sol = solve_modes(structure, request, stats, "modal analysis");
  const DofMap& dofs = *sol.dofs;
  const std::vector<double>& freqs = sol.frequencies;
  std::vector<Eigen::MatrixXd> shapes;
  for (Eigen::Index j = 0; j < sol.shapes.cols(); ++j) {
    VectorXd shape = VectorXd::Zero(dofs.n_active());
    shape.head(dofs.n_free()) = sol.stored_scale(j) * sol.shapes.col(j);
    shapes.push_back(structure.nodal_table(dofs, shape));
  }
  writer.write_modes(freqs, shapes);
  if (structure.options().modal.element_results) {
    // MXPAND Elcalc YES: each mode's element results and reactions (of the stored shape), as a
    // time point at the mode's frequency (load step 1, substep = mode) that POST1 reads with the
    // mode's set.
    const VectorXd zero = VectorXd::Zero(dofs.n_active());
    const SparseMatrix k_all = sol.assembler->stiffness_matrix(zero);
    const SparseMatrix m_all = sol.assembler->mass_matrix();
    for (Eigen::Index j = 0; j < sol.shapes.cols(); ++j) {
      VectorXd shape = VectorXd::Zero(dofs.n_active());
      shape.head(dofs.n_free()) = sol.stored_scale(j) * sol.shapes.col(j);
      TimePoint p;
      p.time = freqs[static_cast<std::size_t>(j)];
      p.load_step = 1;
      p.substep = static_cast<int>(j) + 1;
      p.displacement = shapes[static_cast<std::size_t>(j)];
      p.velocity = Eigen::MatrixXd::Constant(p.displacement.rows(), 6,
                                             std::numeric_limits<double>::quiet_NaN());
      p.acceleration = p.velocity;
      // The supports' forces of the harmonic motion in the mode: R = K φ − ω² M φ.
      const double w2 = std::pow(2.0 * M_PI * freqs[static_cast<std::size_t>(j)], 2);
      const VectorXd reactions = k_all * shape - w2 * (m_all * shape);
      p.reaction = structure.reaction_table(dofs, reactions);
      p.element_results = structure.element_results(*sol.assembler, shape, zero);
      writer.append(std::move(p));
    }
  }
  for (std::size_t j = 0; j < freqs.size(); ++j)
    stats.notes.push_back(fmt::format("mode {}: {:.6g} Hz", j + 1, freqs[j]));
  if (structure.options().modal.method == "QRDAMP") {
    VectorXd omega(sol.shapes.cols());
    for (Eigen::Index j = 0; j < omega.size(); ++j)
      omega(j) = 2.0 * M_PI * freqs[static_cast<std::size_t>(j)];
    write_qr_damped_modes(structure, *sol.assembler, sol.shapes, omega, writer, stats);
  }
  stats.n_stored = static_cast<int>(freqs.size());
}

}  // namespace impactfe
