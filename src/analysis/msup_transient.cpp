// Mode-superposition transient (ANTYPE,TRANS + TRNOPT,MSUP): the lowest modes of K x = λ M x,
// modal damping (DMPRAT + MDAMP + Rayleigh, plus element dampers projected), GP gap conditions
// as nonlinear modal forces, same time axis and integrators as the reduced transient.
#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/analyses.h"
#include "analysis/damped_modes.h"
#include "analysis/reduced_run.h"
#include "core/log.h"
#include "linalg/eigen_solver.h"
#include "time/time_schedule.h"

namespace impactfe {

/// The lowest modes of K x = λ M x over the free DOFs of the reduced model (MODOPT or the MSUP
/// mode count, only modes with mass), mass-normalised; the shift keeps rigid-body modes regular.
EigenResult lowest_modes(Structure& structure, const ReducedRunState& state, int wanted,
                         const char* analysis, AnalysisStatistics& stats) {
  const AnalysisOptions& options = structure.options();
  const DofMap& dofs = *state.dofs;
  const int nf = dofs.n_free();
  const std::string& method = options.modal.method;
  // QRDAMP's basis is the undamped real modes, with the full projected damping matrix
  // (modal_damping below): what the QR damped mode superposition is. DAMP and UNSYM are not.
  if (method == "DAMP" || method == "UNSYM")
    Log::warn("MODOPT,{}: undamped real modes from the symmetric Lanczos solver are used", method);
  int n_modes = std::min(std::max(wanted, 1), nf);
  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  SparseMatrix k_lower(nf, nf), m_lower(nf, nf);
  state.assembler->assemble({1.0, 0.0, 0.0}, zero, zero,
                            Assembler::Output{&k_lower, nullptr, nullptr});
  state.assembler->assemble({0.0, 0.0, 1.0}, zero, zero,
                            Assembler::Output{&m_lower, nullptr, nullptr});
  double ratio_sum = 0.0;
  int count = 0;
  for (int i = 0; i < nf; ++i)
    if (m_lower.coeff(i, i) > 0.0 && k_lower.coeff(i, i) > 0.0) {
      ratio_sum += k_lower.coeff(i, i) / m_lower.coeff(i, i);
      ++count;
    }
  const double shift = -1e-6 * (count > 0 ? ratio_sum / count : 1.0);
  n_modes = modes_with_mass(structure, m_lower, n_modes, analysis, stats);
  try {
    return lowest_eigenpairs(k_lower, m_lower, n_modes, shift);
  } catch (const SingularMatrixError& e) {
    throw ModelError(fmt::format(
        "{}: K - sigma M is singular{}", analysis,
        e.column() >= 0 && e.column() < nf ? " at " + describe(dofs.key(e.column())) : ""));
  }
}

/// Modal damping: Φᵀ C_elem Φ + α I + β diag(ω²) + diag(2 ζ_j ω_j) with ζ_j = DMPRAT +
/// MDAMP(j) (Φᵀ M Φ = I, Φᵀ K Φ = diag(ω²)).
MatrixXd modal_damping(const ReducedRunState& state, const AnalysisOptions& options,
                       const VectorXd& omega) {
  const int nf = state.dofs->n_free();
  const VectorXd zero = VectorXd::Zero(state.dofs->n_active());
  const SparseMatrix k_full = state.assembler->stiffness_matrix(zero);
  const SparseMatrix c_full = damping_matrix(state, k_full);
  const SparseMatrix c_free =
      c_full.nonZeros() ? SparseMatrix(c_full.topLeftCorner(nf, nf)) : SparseMatrix();
  return project_modal_damping(state.modes, c_free, options, omega);
}

namespace {

/// The initial conditions (IC) projected on the modes: q0 = Φᵀ M u0, q̇0 = Φᵀ M v0.
std::pair<VectorXd, VectorXd> modal_initial_state(const Model& model,
                                                  const ReducedRunState& state) {
  const DofMap& dofs = *state.dofs;
  const int nf = dofs.n_free();
  VectorXd u0 = VectorXd::Zero(dofs.n_active()), vel0 = u0;
  for (const auto& [key, ic] : model.initial_conditions) {
    const int i = dofs.index(key);
    if (i < 0 || i >= nf) continue;
    u0(i) = ic.displacement;
    vel0(i) = ic.velocity;
  }
  const MatrixXd m_phi = state.mass_all.topLeftCorner(nf, nf) * state.modes;
  return {m_phi.transpose() * u0.head(nf), m_phi.transpose() * vel0.head(nf)};
}

}  // namespace

void run_msup_transient(Structure& structure, const AnalysisRequest& request, ResultsWriter& writer,
                        const RunSettings& settings, AnalysisStatistics& stats,
                        std::unique_ptr<ReducedSolutionState>& state_for_expansion) {
  using clock = std::chrono::steady_clock;
  const AnalysisOptions& options = structure.options();
  const Model& model = structure.model();
  auto state = std::make_unique<ReducedRunState>();
  state->method = "msup";
  const std::unique_ptr<TimeIntegrator> probe = make_time_integrator(options);
  stats.description = fmt::format("transient (mode superposition, {})", probe->name());
  writer.begin_analysis(ResultsKind::ReducedTransient,
                        fmt::format("mode-superposition transient ({})", probe->name()));

  // --- Modes and modal matrices ----------------------------------------------------------------
  const auto t_modes = clock::now();
  prepare_reduced_model(*state, structure, request, settings, {}, stats);
  const DofMap& dofs = *state->dofs;
  const int nf = dofs.n_free();
  const EigenResult eig = lowest_modes(
      structure, *state, options.msup_modes > 0 ? options.msup_modes : options.modal.n_modes,
      "mode-superposition transient", stats);
  const int nm = static_cast<int>(eig.eigenvalues.size());
  state->modes = eig.eigenvectors.topRows(nf);
  VectorXd omega(nm);
  for (int j = 0; j < nm; ++j) omega(j) = std::sqrt(std::max(eig.eigenvalues(j), 0.0));
  const MatrixXd& phi = state->modes;
  MatrixXd km = MatrixXd::Zero(nm, nm), mm = MatrixXd::Identity(nm, nm);
  km.diagonal() = omega.cwiseProduct(omega);
  MatrixXd cm = modal_damping(*state, options, omega);
  const double modes_seconds = std::chrono::duration<double>(clock::now() - t_modes).count();
  {
    std::string list;
    for (int j = 0; j < nm && j < 12; ++j) list += fmt::format(" {:.5g}", omega(j) / (2 * M_PI));
    stats.notes.push_back(
        fmt::format("{} modes, frequencies (Hz):{}{}", nm, list, nm > 12 ? " ..." : ""));
  }

  // GP ends: any free DOF, through its row of Φ.
  std::vector<GeneralizedGap> gaps = generalized_gaps(
      model, dofs, [&](int i) { return VectorXd(phi.row(i).transpose()); }, "");
  const auto [q0, v0] = modal_initial_state(model, *state);

  state->points = reduced_time_axis(state->load_steps, state->dt, stats.notes);
  GeneralizedHistory::require_disk_space(static_cast<double>(state->points.size()), nm,
                                         static_cast<int>(gaps.size()));
  if (state->dt > 0.0 && nm > 0) {
    const double period = 2.0 * M_PI / omega(nm - 1);
    if (state->dt > coarsest_step(period))
      Log::warn("dt = {:g} is coarser than T/10 = {:g} of the highest mode used ({:.5g} Hz)",
                state->dt, coarsest_step(period), omega(nm - 1) / (2 * M_PI));
  }
  ReducedDynamics dynamics(km, mm, cm, std::move(gaps), make_time_integrator(options));
  double seconds_per_step = 0.0;
  integrate_reduced(
      *state, dynamics, [&](const VectorXd& f) { return VectorXd(phi.transpose() * f); },
      [&](const VectorXd& q) { return VectorXd(phi * q); }, q0, v0,
      [&](int j) { return fmt::format("mode {}", j + 1); }, writer, stats, seconds_per_step,
      settings.progress);

  writer.set_count("modes", static_cast<long long>(nm));
  writer.set_count("gap_conditions", static_cast<long long>(model.gap_conditions.size()));
  writer.set_attribute("time_step", state->dt);
  writer.set_attribute("reduction_seconds", modes_seconds);
  writer.set_attribute("integration_seconds_per_step", seconds_per_step);
  stats.notes.push_back(
      fmt::format("modes: {} in {:.3g} s; integration: {} steps of dt = {:g}, {:.3g} s per step",
                  nm, modes_seconds, state->points.size() - 1, state->dt, seconds_per_step));
  state_for_expansion = std::move(state);
}

}  // namespace impactfe
