#include "analysis/superelement_generation.h"

#include <fmt/format.h>

#include <chrono>
#include <set>

#include "assembly/loads.h"
#include "core/log.h"
#include "reduction/guyan.h"

namespace impactfe {

namespace {

/// Generation allows only zero D (spec §10.6) and one constraint set for all load steps: the
/// condensation is made once.
std::set<DofKey> generation_constraints(const AnalysisRequest& request) {
  if (request.load_steps.empty())
    throw InputError(request.where, "superelement generation: no load step was written");
  const std::set<DofKey> first = constrained_set(request.load_steps.front());
  for (const LoadStep& step : request.load_steps) {
    for (const auto& [key, value] : step.constraints)
      if (value != 0.0)
        throw InputError(step.where,
                         fmt::format("superelement generation: D on {} is {} — only zero "
                                     "constraints are allowed in a generation pass",
                                     describe(key), value));
    if (constrained_set(step) != first)
      throw InputError(step.where,
                       fmt::format("superelement generation: load step {} changes the "
                                   "constrained DOFs; all load steps must share one D set",
                                   step.number));
  }
  return first;
}

/// The free-DOF indices of the master DOFs (M), in the order given; a master that no element
/// carries or that is constrained is an input error at its M command.
std::vector<int> master_indices(const Structure& structure, const DofMap& dofs,
                                const AnalysisRequest& request) {
  const Model& model = structure.model();
  std::vector<int> masters;
  for (const DofKey& key : model.masters) {
    const int i = dofs.index(key);
    const auto defined = model.master_where.find(key);
    const SourceLocation& where =
        defined != model.master_where.end() ? defined->second : request.where;
    if (i < 0)
      throw InputError(where, fmt::format("master DOF {} is not a DOF of any element of the "
                                          "substructure",
                                          describe(key)));
    if (i >= dofs.n_free())
      throw InputError(
          where, fmt::format("master DOF {} is constrained{}; a master must be free", describe(key),
                             structure.automatic_constraints().count(key)
                                 ? " (it has neither stiffness nor mass)"
                                 : " by D"));
    masters.push_back(i);
  }

  return masters;
}

/// Status elements (gaps) enter with their matrices at u = 0, and stress stiffening (KAY(8) /
/// SESST) has no prestress to act on in a generation from the unloaded state: both are said.
void note_linearised_elements(const std::vector<std::unique_ptr<Element>>& elements,
                              const ElementContext& ctx) {
  bool has_status = false;
  for (const auto& e : elements) has_status |= e->has_status();
  if (has_status)
    Log::warn(
        "superelement generation: the substructure has status (gap) elements; the superelement "
        "is linear and uses their matrices at zero displacement");
  if (ctx.stress_stiffening)
    Log::info(
        "superelement generation: stress stiffening requested; the matrices are formed at "
        "the unloaded state (zero stress), so it does not change them");
}

/// K_ss⁻¹ f_s of a vector over the active DOFs: the slave part of a static correction.
VectorXd slave_response(const GuyanReduction& cond, const VectorXd& f) {
  const VectorXd u = cond.expand(VectorXd::Zero(cond.n_masters()), &f);
  VectorXd us(cond.n_slaves());
  for (int k = 0; k < cond.n_slaves(); ++k) us(k) = u(cond.slaves()[static_cast<std::size_t>(k)]);
  return us;
}

/// One reduced load vector per load step, from the loads at the end of the step, and its
/// static correction of the slaves.
void reduced_load_vectors(const Structure& structure, const DofMap& dofs,
                          const GuyanReduction& cond, const AnalysisRequest& request,
                          SuperelementData& se) {
  const auto& elements = structure.elements();
  const ElementContext& ctx = structure.context();
  const int n_ls = static_cast<int>(request.load_steps.size());
  se.load_vectors.setZero(cond.n_masters(), n_ls);
  se.load_correction.setZero(cond.n_slaves(), n_ls);
  for (int k = 0; k < n_ls; ++k) {
    const LoadPoint at{&request.load_steps[static_cast<std::size_t>(k)],
                       k > 0 ? &request.load_steps[static_cast<std::size_t>(k - 1)] : nullptr, 1.0};
    if (has_tabular_loads(request.load_steps[static_cast<std::size_t>(k)]))
      throw NotImplementedError(fmt::format(
          "load step {}: table (%TABLE%) loads in a superelement generation pass are not "
          "supported (a superelement load vector is constant)",
          k + 1));
    const VectorXd f = nodal_forces(dofs, at) +
                       inertia_load(elements, dofs, ctx, frame_acceleration(at)) +
                       pressure_forces(elements, dofs, ctx, at, VectorXd::Zero(dofs.n_active()));
    se.load_vectors.col(k) = cond.reduce_force(f);
    se.load_correction.col(k) = slave_response(cond, f);
  }
}

/// Unit-acceleration vectors g_d = Tᵀ M r_d, through the elements' frame-acceleration loads
/// (−M r a for a unit a), so a nested superelement contributes its own exact g_d; the total and
/// the reduced mass per direction go into the summary.
void unit_acceleration_vectors(const Structure& structure, const DofMap& dofs,
                               const GuyanReduction& cond, SuperelementData& se,
                               GenerationSummary& summary) {
  se.unit_acceleration.setZero(cond.n_masters(), 3);
  se.acceleration_correction.setZero(cond.n_slaves(), 3);
  const Eigen::MatrixXd unit_loads =
      inertia_loads(structure.elements(), dofs, structure.context(), Eigen::Matrix3d::Identity());
  for (int d = 0; d < 3; ++d) {
    const VectorXd p = -unit_loads.col(d);
    se.unit_acceleration.col(d) = cond.reduce_force(p);
    se.acceleration_correction.col(d) = slave_response(cond, p);
    double total = 0.0, reduced = 0.0;
    for (int i = 0; i < dofs.n_active(); ++i)
      if (static_cast<int>(dofs.key(i).dof) == d) total += p(i);
    for (int k = 0; k < cond.n_masters(); ++k)
      if (static_cast<int>(se.masters[static_cast<std::size_t>(k)].key.dof) == d)
        reduced += se.unit_acceleration(k, d);
    summary.total_mass[d] = total;
    summary.reduced_mass[d] = reduced;
  }
}

}  // namespace

SuperelementData generate_superelement(const Structure& structure, const AnalysisRequest& request,
                                       const std::string& name, GenerationSummary& summary) {
  const auto start = std::chrono::steady_clock::now();
  const Model& model = structure.model();
  const ElementContext& ctx = structure.context();
  const auto& elements = structure.elements();
  if (model.masters.empty())
    throw InputError(request.where, "superelement generation needs master DOFs (M)");

  generation_constraints(request);
  if (!model.coupled_sets.empty())
    throw NotImplementedError(model.coupled_sets.begin()->second.where,
                              "coupled DOF sets (CP) in a superelement generation pass are not "
                              "implemented");
  structure.refuse_constraint_equations("a superelement generation pass");
  const DofMap dofs(elements, structure.constraints_of(request.load_steps.front()));
  const Assembler assembler(elements, dofs, ctx);
  note_linearised_elements(elements, ctx);
  const std::vector<int> masters = master_indices(structure, dofs, request);

  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  const SparseMatrix K = assembler.stiffness_matrix(zero);
  const SparseMatrix M = assembler.mass_matrix();
  SparseMatrix C = assembler.damping_matrix(zero);
  const AnalysisOptions& o = structure.options();
  if (o.alpha_damping != 0.0) C += o.alpha_damping * M;
  if (o.beta_damping != 0.0) C += o.beta_damping * K;

  // Guyan condensation (src/reduction/guyan): one K_ss factorization, T = −K_ss⁻¹K_sm by a
  // multi-right-hand-side solve, reduced matrices TᵀAT.
  const bool has_mass = M.nonZeros() > 0 && M.coeffs().cwiseAbs().maxCoeff() > 0.0;
  const bool has_damping = C.nonZeros() > 0 && C.coeffs().cwiseAbs().maxCoeff() > 0.0;
  const GuyanReduction cond(K, M, has_damping ? &C : nullptr, dofs.n_free(), masters, &dofs);

  SuperelementData se;
  se.name = name;
  se.title = model.title;
  se.stiffness = cond.k();

  // Mass whenever the substructure has any (spec U5), damping whenever it has any (or SEMATR 3).
  int matrices = 1;
  if (o.superelement_matrices >= 2 || has_mass) {
    se.mass = cond.m();
    matrices = 2;
    if (o.superelement_matrices < 2)
      Log::info("superelement generation: the substructure has mass; M_r is generated too");
  }
  if (o.superelement_matrices >= 3 || has_damping) {
    se.damping = cond.c();
    matrices = 3;
  }
  se.matrices = matrices;

  for (std::size_t k = 0; k < masters.size(); ++k) {
    const DofKey& key = dofs.key(masters[k]);
    const Node& node = model.node(key.node);
    se.masters.push_back({key, node.x, node.angles_deg});
  }
  for (int i : cond.slaves()) se.slaves.push_back(dofs.key(i));
  for (int i = dofs.n_free(); i < dofs.n_active(); ++i) se.constrained.push_back(dofs.key(i));
  se.transformation = cond.transformation();

  reduced_load_vectors(structure, dofs, cond, request, se);

  unit_acceleration_vectors(structure, dofs, cond, se, summary);

  se.model_text = serialize_generation_model(model, ctx.lumped_mass, ctx.stress_stiffening);

  summary.n_masters = cond.n_masters();
  summary.n_slaves = cond.n_slaves();
  summary.n_constrained = dofs.n_constrained();
  summary.factorizations = cond.n_slaves() > 0 ? 1 : 0;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return se;
}

}  // namespace impactfe
