// Harmonic response analysis (ANTYPE,HARMIC; HROPT,FULL or MSUP): the steady-state response
// u(t) = Re[(u_r + i u_i) e^{iΩt}] to loads F + i F_imag of one frequency at a time, at the
// frequencies of HARFRQ + NSUBST of each load step. Each frequency is stored as a time point
// whose time is the frequency (Hz): U the real part, UI the imaginary part.
#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/analyses.h"
#include "analysis/harmonic_response.h"
#include "analysis/reduced_run.h"
#include "core/log.h"

namespace impactfe {

namespace {

/// What the harmonic analysis does not carry out, refused before anything is solved.
void check_supported(const Model& model, const AnalysisOptions& options,
                     const std::vector<LoadStep>& steps) {
  for (const auto& [id, mat] : model.materials)
    for (const char* lab : {"DMPR", "DMPS"})
      if (mat.has(lab) && mat.props.at(lab) != 0.0)
        throw NotImplementedError(
            steps.front().where,
            fmt::format("MP,{} (material structural damping) of material {} is not "
                        "used by the harmonic analysis; give DMPSTR instead",
                        lab, id));
  if (!options.harmonic.mode_superposition && !options.modal_damping.empty())
    throw InputError(steps.front().where,
                     "MDAMP (modal damping ratios) applies to a mode-superposition harmonic "
                     "(HROPT,MSUP), not to the full method");
  for (const LoadStep& s : steps) {
    if (!s.force_tables.empty() || !s.constraint_tables.empty())
      throw NotImplementedError(s.where,
                                "table (%TABLE%) loads in a harmonic analysis are not supported");
    if (s.load_vector_scale != 0.0)
      throw NotImplementedError(s.where, "LVSCALE in a harmonic analysis is not supported");
    for (const auto& [face, load] : s.pressures)
      if (!load.table.empty())
        throw NotImplementedError(s.where,
                                  "table (%TABLE%) pressures in a harmonic analysis are not "
                                  "supported");
  }
}

/// The load over the active DOFs at a harmonic point: F (+ ACEL, SF) as the real part and
/// F VALUE2 as the imaginary part, both times the point's KBC factor.
VectorXcd harmonic_load(const ReducedRunState& state, const LoadStep& step,
                        const HarmonicPoint& p) {
  const auto* tables = &state.structure->model().time_functions;
  const VectorXd re = state.loads_at(LoadPoint{&step, nullptr, 1.0, p.frequency, tables});
  LoadStep imag_step;
  imag_step.forces = step.forces_imag;
  const VectorXd im = nodal_forces(*state.dofs, LoadPoint{&imag_step, nullptr, 1.0, 0.0, tables});
  VectorXcd f(re.size());
  f.real() = p.load_factor * re;
  f.imag() = p.load_factor * im;
  return f;
}

}  // namespace

void run_harmonic_analysis(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings& settings,
                           AnalysisStatistics& stats) {
  using clock = std::chrono::steady_clock;
  const AnalysisOptions& options = structure.options();
  const HarmonicOptions& h = options.harmonic;
  if (request.load_steps.empty()) throw InputError(request.where, "no load steps were written");
  check_supported(structure.model(), options, request.load_steps);
  const std::vector<HarmonicPoint> points = harmonic_points(request.load_steps);
  const bool msup = h.mode_superposition;
  stats.description = msup ? "harmonic (mode superposition)" : "harmonic (full)";
  writer.begin_analysis(ResultsKind::Harmonic, stats.description);

  ReducedRunState state;
  state.method = msup ? "msup" : "full";
  prepare_reduced_model(state, structure, request, settings, {}, stats);
  const DofMap& dofs = *state.dofs;
  const int nf = dofs.n_free();
  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  const SparseMatrix k_all = state.assembler->stiffness_matrix(zero);
  const SparseMatrix c_all = damping_matrix(state, k_all);

  // Modes (MSUP): from the structure, as the preceding modal analysis computed them.
  VectorXd omega_modes;
  MatrixXd modal_c;
  if (msup) {
    const auto t0 = clock::now();
    const int wanted = h.n_modes > 0 ? h.n_modes : options.modal.n_modes;
    const EigenResult eig =
        lowest_modes(structure, state, wanted, "mode-superposition harmonic", stats);
    const auto nm = eig.eigenvalues.size();
    state.modes = eig.eigenvectors.topRows(nf);
    omega_modes.resize(nm);
    for (Eigen::Index j = 0; j < nm; ++j)
      omega_modes(j) = std::sqrt(std::max(eig.eigenvalues(j), 0.0));
    modal_c = modal_damping(state, options, omega_modes);
    std::string list;
    for (Eigen::Index j = 0; j < nm && j < 12; ++j)
      list += fmt::format(" {:.5g}", omega_modes(j) / (2 * M_PI));
    stats.notes.push_back(fmt::format("{} modes in {:.3g} s, frequencies (Hz):{}{}", nm,
                                      std::chrono::duration<double>(clock::now() - t0).count(),
                                      list, nm > 12 ? " ..." : ""));
  }
  const SparseMatrix k = k_all.topLeftCorner(nf, nf);
  const SparseMatrix c = c_all.topLeftCorner(nf, nf);
  const SparseMatrix m = state.mass_all.topLeftCorner(nf, nf);

  for (const LoadStep& ls : request.load_steps)
    if (!ls.output.uniform())
      Log::info(
          "{}:{}: OUTRES per item: a harmonic analysis writes the displacements at every "
          "frequency",
          ls.where.file, ls.where.line);
  for (const HarmonicPoint& p : points) {
    const LoadStep& step = request.load_steps[p.step_index];
    const double omega = 2.0 * M_PI * p.frequency;
    const VectorXcd f = harmonic_load(state, step, p).head(nf);
    VectorXcd u;
    if (msup) {
      const VectorXcd fq = state.modes.transpose().cast<std::complex<double>>() * f;
      u = state.modes.cast<std::complex<double>>() *
          solve_modal_harmonic(omega_modes, modal_c, omega, h.structural_damping, fq);
    } else {
      u = solve_full_harmonic(k, c, m, omega, h.structural_damping, options.damping_ratio, f);
      ++stats.n_factorizations;
    }
    // Constrained DOFs are fixed (zero) in both parts.
    VectorXd re = VectorXd::Zero(dofs.n_active()), im = re;
    re.head(nf) = u.real();
    im.head(nf) = u.imag();
    TimePoint tp;
    tp.time = p.frequency;
    tp.load_step = step.number;
    tp.substep = p.substep;
    tp.displacement = structure.nodal_table(dofs, re);
    tp.displacement_imag = structure.nodal_table(dofs, im);
    writer.append(std::move(tp));
    ++stats.n_stored;
    ++stats.n_substeps;
  }
  stats.n_load_steps = static_cast<int>(request.load_steps.size());
  writer.set_count("frequencies", static_cast<long long>(points.size()));
  if (msup) writer.set_count("modes", static_cast<long long>(omega_modes.size()));
  stats.notes.push_back(fmt::format("{} frequencies from {:g} to {:g} Hz", points.size(),
                                    points.front().frequency, points.back().frequency));
}

}  // namespace impactfe
