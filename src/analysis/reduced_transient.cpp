// Reduced linear transient on master DOFs with GP gap conditions (KAN,5 / TRNOPT,REDUC;
// spec §10.4): Guyan reduction, constant-step integration of the dense reduced system, explicit
// gap forces, and the master histories kept for the expansion pass.
#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/analyses.h"
#include "analysis/reduced_run.h"
#include "core/log.h"

namespace impactfe {

namespace {

/// The master DOFs of the reduction (M, MDELE, TOTAL): a master that is no element's DOF is an
/// input error; a constrained one is ignored with a warning; one without mass is named.
std::vector<int> checked_masters(const Model& model, const DofMap& dofs, const VectorXd& k_diagonal,
                                 const SparseMatrix& mass, const AnalysisOptions& options,
                                 const AnalysisRequest& request, AnalysisStatistics& stats) {
  const int nf = dofs.n_free();
  const MasterSelection masters =
      select_masters(model.masters, dofs, k_diagonal, mass.diagonal().head(nf),
                     options.total_masters, options.total_masters_exclude_rotations);
  for (const DofKey& key : masters.ignored) {
    if (!dofs.is_active(key)) {
      const auto w = model.master_where.find(key);
      throw InputError(w != model.master_where.end() ? w->second : request.where,
                       fmt::format("master DOF {} is not a DOF of any element (no element at "
                                   "node {} carries {})",
                                   describe(key), key.node, dof_name(key.dof)));
    }
    Log::warn("master DOF {} is constrained; ignored", describe(key));
  }
  if (!masters.automatic.empty()) {
    std::string list;
    for (const DofKey& key : masters.automatic) list += " " + describe(key);
    const std::string note =
        fmt::format("TOTAL: {} automatic master DOF(s):{}", masters.automatic.size(), list);
    Log::info("{}", note);
    stats.notes.push_back(note);
  }
  if (masters.indices.empty())
    throw InputError(request.where,
                     "reduced transient: no master DOFs (give them with M or TOTAL)");
  for (int i : masters.indices)
    if (!(mass.coeff(i, i) > 0.0))
      Log::warn("master DOF {} carries no mass", describe(dofs.key(i)));
  return masters.indices;
}

/// IC on the master DOFs (q0, v0 in master order); an IC on a slave DOF is ignored with a warning.
void master_initial_conditions(const Model& model, const DofMap& dofs,
                               const std::vector<int>& master_position, VectorXd& q0,
                               VectorXd& v0) {
  const int nf = dofs.n_free();
  for (const auto& [key, ic] : model.initial_conditions) {
    const int i = dofs.index(key);
    const int j = (i >= 0 && i < nf) ? master_position[static_cast<std::size_t>(i)] : -1;
    if (j < 0) {
      Log::warn("IC on {} ignored: not a master DOF of the reduced transient", describe(key));
      continue;
    }
    q0(j) = ic.displacement;
    v0(j) = ic.velocity;
  }
}

/// The run summary's line for each gap condition: when it first carried force, and its peak.
void note_gap_histories(const ReducedRunState& state, std::size_t n_gaps,
                        AnalysisStatistics& stats) {
  // One pass over the history (it may be read back from its file), all gaps at once.
  std::vector<double> peak(n_gaps, 0.0);
  std::vector<double> closed_at(n_gaps, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t p = 0; n_gaps > 0 && p < state.points.size(); ++p) {
    const VectorXd forces = state.history->at(p).gap_forces;
    for (std::size_t g = 0; g < n_gaps; ++g) {
      const double f = forces(static_cast<Eigen::Index>(g));
      if (f != 0.0 && std::isnan(closed_at[g])) closed_at[g] = state.points[p].time;
      if (std::abs(f) > std::abs(peak[g])) peak[g] = f;
    }
  }
  for (std::size_t g = 0; g < n_gaps; ++g)
    stats.notes.push_back(std::isnan(closed_at[g])
                              ? fmt::format("gap {}: never closed (no force)", g + 1)
                              : fmt::format("gap {}: first force at t = {:g}, peak force {:.6g}",
                                            g + 1, closed_at[g], peak[g]));
}

}  // namespace

void run_reduced_transient(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings& settings,
                           AnalysisStatistics& stats,
                           std::unique_ptr<ReducedSolutionState>& state_for_expansion) {
  using clock = std::chrono::steady_clock;
  const AnalysisOptions& options = structure.options();
  auto state = std::make_unique<ReducedRunState>();
  state->method = "reduced";
  const Model& model = structure.model();
  const std::unique_ptr<TimeIntegrator> probe = make_time_integrator(options);
  stats.description = fmt::format("transient (reduced, {})", probe->name());
  writer.begin_analysis(ResultsKind::ReducedTransient,
                        fmt::format("reduced transient ({}) on master DOFs", probe->name()));

  // --- Reduction -----------------------------------------------------------------------------
  const auto t_reduction = clock::now();
  prepare_reduced_model(*state, structure, request, settings, model.masters, stats);
  const DofMap& dofs = *state->dofs;
  const int nf = dofs.n_free();
  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  const SparseMatrix k = state->assembler->stiffness_matrix(zero);
  const SparseMatrix c = damping_matrix(*state, k);
  const std::vector<int> masters =
      checked_masters(model, dofs, k.diagonal().head(nf), state->mass_all, options, request, stats);
  state->guyan = std::make_unique<GuyanReduction>(k, state->mass_all, c.nonZeros() ? &c : nullptr,
                                                  nf, masters, &dofs);
  const GuyanReduction& guyan = *state->guyan;
  const double reduction_seconds =
      std::chrono::duration<double>(clock::now() - t_reduction).count();

  // GP ends must be masters (or ground): their row of [I; T] is a unit vector.
  std::vector<int> master_position(static_cast<std::size_t>(nf), -1);
  for (int j = 0; j < guyan.n_masters(); ++j)
    master_position[static_cast<std::size_t>(guyan.masters()[static_cast<std::size_t>(j)])] = j;
  auto row = [&](int i) -> VectorXd {
    const int j = master_position[static_cast<std::size_t>(i)];
    if (j < 0) return {};
    VectorXd b = VectorXd::Zero(guyan.n_masters());
    b(j) = 1.0;
    return b;
  };
  std::vector<GeneralizedGap> gaps =
      generalized_gaps(model, dofs, row, "gap conditions act between master DOFs or to ground");

  // --- Initial conditions on masters (IC); slaves follow the masters -------------------------
  VectorXd q0 = VectorXd::Zero(guyan.n_masters()), v0 = q0;
  master_initial_conditions(model, dofs, master_position, q0, v0);

  // --- Integration ---------------------------------------------------------------------------
  state->points = reduced_time_axis(state->load_steps, state->dt, stats.notes);
  GeneralizedHistory::require_disk_space(static_cast<double>(state->points.size()),
                                         guyan.n_masters(), static_cast<int>(gaps.size()));
  ReducedDynamics dynamics(guyan.k(), guyan.m(), guyan.c(), std::move(gaps),
                           make_time_integrator(options));
  double seconds_per_step = 0.0;
  integrate_reduced(
      *state, dynamics, [&](const VectorXd& f) { return guyan.reduce_force(f); },
      [&](const VectorXd& q) {
        VectorXd out = VectorXd::Constant(nf, std::numeric_limits<double>::quiet_NaN());
        for (int j = 0; j < guyan.n_masters(); ++j)
          out(guyan.masters()[static_cast<std::size_t>(j)]) = q(j);
        return out;
      },
      q0, v0,
      [&](int j) { return describe(dofs.key(guyan.masters()[static_cast<std::size_t>(j)])); },
      writer, stats, seconds_per_step, settings.progress);

  // --- Summary -------------------------------------------------------------------------------
  writer.set_count("masters", static_cast<long long>(guyan.n_masters()));
  writer.set_count("slaves", static_cast<long long>(guyan.n_slaves()));
  writer.set_count("gap_conditions", static_cast<long long>(model.gap_conditions.size()));
  writer.set_attribute("time_step", state->dt);
  writer.set_attribute("reduction_seconds", reduction_seconds);
  writer.set_attribute("integration_seconds_per_step", seconds_per_step);
  stats.notes.push_back(
      fmt::format("reduction: {} masters, {} slaves, {:.3g} s; integration: {} steps of dt = {:g}, "
                  "{:.3g} s per step",
                  guyan.n_masters(), guyan.n_slaves(), reduction_seconds, state->points.size() - 1,
                  state->dt, seconds_per_step));
  note_gap_histories(*state, model.gap_conditions.size(), stats);
  state_for_expansion = std::move(state);
}

}  // namespace impactfe
