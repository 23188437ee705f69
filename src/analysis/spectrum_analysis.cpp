// Single-point response spectrum analysis (ANTYPE,SPECTR + SPOPT,SPRS; MAPDL Theory Reference,
// spectrum analysis chapter; docs/spectrum_analysis.md). The modes are those of the modal
// analysis before it (the same model, constraints and MODOPT, solved again: the eigensolution
// is deterministic, so the shapes and their signs are the stored ones). For mode i with mass-
// normalised shape φi and circular frequency ωi:
//   participation factor  γi = φiᵀ M D   (D: the excitation direction on the translations)
//   effective damping     ξi = DMPRAT + MDAMP(i) + BETAD ωi / 2
//   mode coefficient      Ai = Sv γi / ωi, Sa γi / ωi², Su γi   (SVTYP 0, 2, 3)
// The modal responses Ai ωi^p φi (p = 0, 1, 2 for DISP, VELO, ACEL) of the significant modes
// are combined (mode_combination.cpp), and MMASS adds the missing mass response of the modes
// not extracted: F = S0 (M D − Σ γi M φi).
#include <cmath>

#include "analysis/analyses.h"
#include "analysis/mode_combination.h"
#include "core/log.h"
#include "linalg/linear_solver.h"

namespace impactfe {

namespace {

CombinationMethod combination_method(const std::string& name) {
  if (name == "CQC") return CombinationMethod::CQC;
  if (name == "GRP") return CombinationMethod::GRP;
  if (name == "DSUM") return CombinationMethod::DSUM;
  if (name == "NRLSUM") return CombinationMethod::NRLSUM;
  return CombinationMethod::SRSS;
}

/// The excitation direction on the active DOFs: the component of `direction` along each
/// translation (in the node's nodal axes when it is rotated), 0 on the rotations.
VectorXd direction_vector(const Structure& structure, const DofMap& dofs, const Vec3& direction) {
  VectorXd d = VectorXd::Zero(dofs.n_active());
  const auto& nodes = structure.model().nodes;
  for (int i = 0; i < dofs.n_active(); ++i) {
    const DofKey& key = dofs.key(i);
    const int axis = key.dof == Dof::UX ? 0 : key.dof == Dof::UY ? 1 : key.dof == Dof::UZ ? 2 : -1;
    if (axis < 0) continue;
    const auto it = nodes.find(key.node);
    d(i) = it != nodes.end() && it->second.rotated() ? it->second.axes().col(axis).dot(direction)
                                                     : direction(axis);
  }
  return d;
}

/// Combines the element results of the modal responses value by value (each family's table as
/// one row of values per mode).
std::map<std::string, ElementResultTable> combine_element_results(
    const std::vector<std::map<std::string, ElementResultTable>>& per_mode,
    CombinationMethod method, const VectorXd& omega, const VectorXd& zeta, double duration) {
  std::map<std::string, ElementResultTable> combined;
  if (per_mode.empty()) return combined;
  for (const auto& [family, first] : per_mode.front()) {
    const auto size = first.values.size();
    MatrixXd rows(static_cast<Eigen::Index>(per_mode.size()), size);
    for (std::size_t m = 0; m < per_mode.size(); ++m)
      rows.row(static_cast<Eigen::Index>(m)) =
          Eigen::Map<const Eigen::RowVectorXd>(per_mode[m].at(family).values.data(), size);
    ElementResultTable table = first;
    const VectorXd c = combine_modes(method, rows, omega, zeta, duration);
    table.values = Eigen::Map<const MatrixXd>(c.data(), first.values.rows(), first.values.cols());
    combined[family] = std::move(table);
  }
  return combined;
}

/// A response stored as a point at t = 0 of load step `load_step` (substep 1): the
/// displacement table, velocity, acceleration and reaction absent (NaN).
TimePoint response_point(int load_step, MatrixXd displacement) {
  TimePoint p;
  p.time = 0.0;
  p.load_step = load_step;
  p.substep = 1;
  p.displacement = std::move(displacement);
  p.velocity =
      MatrixXd::Constant(p.displacement.rows(), 6, std::numeric_limits<double>::quiet_NaN());
  p.acceleration = p.velocity;
  p.reaction = p.velocity;
  return p;
}

}  // namespace

void run_spectrum_analysis(Structure& structure, const AnalysisRequest& request,
                           ResultsWriter& writer, const RunSettings&, AnalysisStatistics& stats) {
  const AnalysisOptions& options = structure.options();
  const SpectrumOptions& sp = options.spectrum;
  if (!sp.single_point)
    throw InputError(request.where,
                     "spectrum analysis: give the spectrum type (SPOPT,SPRS) before SOLVE");
  if (sp.direction.norm() == 0.0)
    throw InputError(sp.where, "spectrum analysis: no excitation direction (SED) was given");
  if (sp.frequencies.empty() || sp.curves.empty())
    throw InputError(sp.where, "spectrum analysis: no spectrum table (FREQ and SV) was given");
  for (const auto& [id, mat] : structure.model().materials)
    if (mat.get("DMPR", 0.0) != 0.0)
      throw NotImplementedError(fmt::format(
          "spectrum analysis: material {} has a damping ratio (MP,DMPR); the modes' effective "
          "damping takes DMPRAT, MDAMP and BETAD only",
          id));
  stats.description = "single-point response spectrum";
  writer.begin_analysis(ResultsKind::Spectrum, "single-point response spectrum");

  const ModalSolution sol = solve_modes(structure, request, stats, "spectrum analysis");
  const DofMap& dofs = *sol.dofs;
  const int nf = dofs.n_free();
  const int na = dofs.n_active();
  const auto extracted = static_cast<int>(sol.frequencies.size());
  const int nm = sp.n_modes > 0 ? std::min(sp.n_modes, extracted) : extracted;
  if (sp.n_modes > extracted)
    stats.notes.push_back(
        fmt::format("SPOPT asks for {} modes; the modal analysis has {}", sp.n_modes, extracted));
  const MatrixXd phi = sol.shapes.leftCols(nm);
  const SparseMatrix m_full = sol.m_lower.selfadjointView<Eigen::Lower>();

  // Participation factors γ = Φᵀ M D (mass-normalised Φ), spectrum values and mode coefficients.
  const Vec3 direction = sp.direction.normalized();
  const VectorXd d_all = direction_vector(structure, dofs, direction);
  const VectorXd md = m_full * d_all.head(nf);
  const VectorXd gamma = phi.transpose() * md;
  SpectrumTable table;
  table.frequencies = sp.frequencies;
  table.linear = sp.linear_interpolation;
  for (const auto& [damping, values] : sp.curves) table.curves.push_back({damping, values});
  VectorXd omega(nm), zeta(nm), coefficient(nm), value(nm);
  for (int i = 0; i < nm; ++i) {
    omega(i) = 2.0 * M_PI * sol.frequencies[static_cast<std::size_t>(i)];
    double z = options.damping_ratio + 0.5 * options.beta_damping * omega(i);
    if (auto it = options.modal_damping.find(i + 1); it != options.modal_damping.end())
      z += it->second;
    zeta(i) = z;
    value(i) = sp.scale * spectrum_value(table, omega(i) / (2.0 * M_PI), z);
    const double w = omega(i);
    if (w <= 0.0 && sp.spectrum_type != 3) {
      // A rigid-body mode has no spectral response of velocity or acceleration type.
      stats.notes.push_back(fmt::format("mode {} is a rigid-body mode (0 Hz): not used", i + 1));
      coefficient(i) = 0.0;
      continue;
    }
    coefficient(i) = sp.spectrum_type == 0   ? value(i) * gamma(i) / w
                     : sp.spectrum_type == 2 ? value(i) * gamma(i) / (w * w)
                                             : value(i) * gamma(i);
  }

  // The significant modes: |Ai| / max |A| above SIGNIF (SRSS ... SIGNIF).
  const double largest = nm > 0 ? coefficient.cwiseAbs().maxCoeff() : 0.0;
  std::vector<int> significant;
  for (int i = 0; i < nm; ++i)
    if (largest > 0.0 && std::abs(coefficient(i)) / largest > sp.significance)
      significant.push_back(i);
  const auto ns = static_cast<Eigen::Index>(significant.size());
  const int power = sp.response == "ACEL" ? 2 : sp.response == "VELO" ? 1 : 0;
  const CombinationMethod method = combination_method(sp.combination);
  VectorXd omega_s(ns), zeta_s(ns);
  MatrixXd responses(ns, nf);
  for (Eigen::Index k = 0; k < ns; ++k) {
    const int i = significant[static_cast<std::size_t>(k)];
    omega_s(k) = omega(i);
    zeta_s(k) = zeta(i);
    responses.row(k) = coefficient(i) * std::pow(omega(i), power) * phi.col(i).transpose();
  }
  VectorXd combined = VectorXd::Zero(na);
  combined.head(nf) = combine_modes(method, responses, omega_s, zeta_s, sp.duration);
  // Element results of the combined response: those of each significant modal displacement,
  // combined value by value (DISP only: element results of a velocity or acceleration response
  // are not stresses).
  const bool element_results = sp.element_results && power == 0;
  std::map<std::string, ElementResultTable> combined_elements;
  const bool combine = !sp.combination.empty();
  if (element_results && combine) {
    std::vector<std::map<std::string, ElementResultTable>> per_mode;
    const VectorXd zero = VectorXd::Zero(na);
    for (Eigen::Index k = 0; k < ns; ++k) {
      VectorXd u = VectorXd::Zero(na);
      u.head(nf) = responses.row(k).transpose();
      per_mode.push_back(structure.element_results(*sol.assembler, u, zero));
    }
    combined_elements = combine_element_results(per_mode, method, omega_s, zeta_s, sp.duration);
  }

  // The missing mass response (MMASS): the part of the excitation's inertia load M D that the
  // modes used do not carry, at the zero period acceleration S0.
  std::optional<TimePoint> missing;
  if (sp.missing_mass && power == 1)
    throw InputError(sp.where,
                     "spectrum analysis: the missing mass response (MMASS) is a displacement or "
                     "an acceleration; combine with Label DISP or ACEL, not VELO");
  if (sp.missing_mass) {
    const double s0 = sp.zero_period_acceleration;
    const VectorXd rigid = d_all.head(nf) - phi * gamma;  // D − Σ γi φi
    VectorXd response = VectorXd::Zero(na);
    if (power == 2) {
      // Acceleration: the absolute acceleration of the rigid part, S0 (D − Σ γi φi); the
      // constrained DOFs move with the ground (S0 D).
      response.head(nf) = s0 * rigid;
      response.tail(na - nf) = s0 * d_all.tail(na - nf);
    } else {
      // Displacement: the static response K u = S0 (M D − Σ γi M φi) = S0 M (D − Σ γi φi).
      const VectorXd force = s0 * (m_full * rigid);
      auto solver = make_linear_solver(nf);
      solver->analyze_pattern(sol.k_lower);
      solver->factorize(sol.k_lower);
      response.head(nf) = solver->solve(force);
    }
    TimePoint p = response_point(2, structure.nodal_table(dofs, response));
    if (element_results)
      p.element_results = structure.element_results(*sol.assembler, response, VectorXd::Zero(na));
    // The periodic (modal) and the rigid (missing mass) parts combine by SRSS.
    combined = (combined.cwiseProduct(combined) + response.cwiseProduct(response)).cwiseSqrt();
    if (element_results)
      for (auto& [family, table] : combined_elements) {
        const auto it = p.element_results.find(family);
        if (it == p.element_results.end()) continue;
        table.values = (table.values.cwiseProduct(table.values) +
                        it->second.values.cwiseProduct(it->second.values))
                           .cwiseSqrt();
      }
    missing = std::move(p);
  }

  // The combined response (when a combination command was given; without one the analysis
  // gives the mode coefficients only): kept in the file at load step 0, which POST1 does not
  // list as a set (MAPDL writes it outside the results file, to Jobname.mcom).
  if (combine) {
    TimePoint c = response_point(0, structure.nodal_table(dofs, combined));
    c.element_results = std::move(combined_elements);
    writer.append(std::move(c));
  }
  if (missing) writer.append(std::move(*missing));

  // Per mode: what *GET,Par,MODE,n,MCOEF / PFACT / EFFM / DAMP read. The coefficient refers to
  // the stored shape (MODOPT Nrmkey ON scales it).
  for (int i = 0; i < nm; ++i) {
    const int n = i + 1;
    writer.set_attribute(fmt::format("mode_coefficient_{}", n),
                         coefficient(i) / sol.stored_scale(i));
    writer.set_attribute(fmt::format("participation_factor_{}", n), gamma(i));
    writer.set_attribute(fmt::format("effective_mass_{}", n), gamma(i) * gamma(i));
    writer.set_attribute(fmt::format("damping_ratio_{}", n), zeta(i));
    writer.set_attribute(fmt::format("spectrum_value_{}", n), value(i));
    stats.notes.push_back(
        fmt::format("mode {}: {:.6g} Hz, participation factor {:.6g}, spectrum value {:.6g}, mode "
                    "coefficient {:.6g}{}",
                    n, omega(i) / (2.0 * M_PI), gamma(i), value(i), coefficient(i),
                    std::find(significant.begin(), significant.end(), i) != significant.end()
                        ? ""
                        : " (not significant)"));
  }
  writer.set_count("modes", static_cast<long long>(nm));
  writer.set_count("significant_modes", static_cast<long long>(ns));
  writer.set_attribute("combination", sp.combination.empty() ? "SRSS" : sp.combination);
  writer.set_attribute("response", sp.response);
  stats.n_stored = (missing ? 1 : 0) + (combine ? 1 : 0);
}

}  // namespace impactfe
