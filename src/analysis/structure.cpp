#include "analysis/structure.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>

#include "assembly/element_adapters.h"
#include "core/files.h"
#include "core/log.h"
#include "core/thread_pool.h"
#include "elements/element_build_cache.h"

namespace impactfe {

namespace {

/// Superelement file of a MATRIX50 record: --se, else file<UNIT>.sub.h5 / <File>.sub.h5, else the
/// only *.sub.h5 in the working directory (spec §2.3).
std::string resolve_superelement(const ElementRecord& record, const RunSettings& settings) {
  namespace fs = std::filesystem;
  if (!settings.superelement_file.empty()) return settings.superelement_file;
  std::vector<std::string> candidates;
  const std::string& name = record.superelement_file;
  if (name.rfind("unit:", 0) == 0) {
    candidates.push_back("file" + name.substr(5) + ".sub.h5");
  } else if (!name.empty()) {
    candidates.push_back(name);
    candidates.push_back(name + ".sub.h5");
  }
  for (const auto& c : candidates)
    if (file_exists(c, true)) return c;
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(fs::current_path())) {
    const std::string file = entry.path().filename().string();
    if (file.size() > 7 && file.substr(file.size() - 7) == ".sub.h5") found.push_back(file);
  }
  if (found.size() == 1) return found.front();
  std::string listing;
  for (const auto& f : found) listing += " " + f;
  throw InputError(record.where,
                   fmt::format("element {}: superelement file not found (looked for{}{}; "
                               "*.sub.h5 here:{}); give it with --se FILE",
                               record.id, candidates.empty() ? "" : " ",
                               candidates.empty() ? std::string() : candidates.front(),
                               listing.empty() ? " none" : listing));
}

/// "UY@2 UY@3 ..." (at most 20 DOFs).
std::string dof_list(const std::set<DofKey>& keys) {
  std::string list;
  int shown = 0;
  for (const auto& key : keys)
    if (shown++ < 20) list += " " + std::string(dof_name(key.dof)) + "@" + std::to_string(key.node);
  return keys.size() > 20 ? list + " ..." : list;
}

/// True when every load step holds `key` with D (false without load steps).
bool held_in_every_step(const DofKey& key, const std::vector<LoadStep>* steps) {
  if (steps == nullptr || steps->empty()) return false;
  for (const auto& step : *steps)
    if (!step.constraints.count(key)) return false;
  return true;
}

/// What acts on a DOF (a force, an initial condition, a master designation of an analysis that
/// uses masters) and the command that put it there.
struct Demand {
  std::string what;
  SourceLocation where;
};

std::optional<Demand> force_on(const DofKey& key, const LoadStep& step) {
  if (step.constraints.count(key)) return std::nullopt;
  const auto w = step.force_where.find(key);
  const SourceLocation where = w != step.force_where.end() ? w->second : step.where;
  if (const auto t = step.force_tables.find(key); t != step.force_tables.end())
    return Demand{fmt::format("carries the force {} = %{}% (load step {})", force_name(key.dof),
                              t->second, step.number),
                  where};
  const auto f = step.forces.find(key);
  if (f == step.forces.end() || f->second == 0.0) return std::nullopt;
  return Demand{fmt::format("carries the force {} = {:g} (load step {})", force_name(key.dof),
                            f->second, step.number),
                where};
}

std::optional<Demand> demand_on(const DofKey& key, const Model& model,
                                const AnalysisOptions& options,
                                const std::vector<LoadStep>* steps) {
  if (steps)
    for (const auto& step : *steps)
      if (auto demand = force_on(key, step)) return demand;
  const bool held = steps && !steps->empty() && steps->front().constraints.count(key);
  const auto ic = model.initial_conditions.find(key);
  if (ic != model.initial_conditions.end() && !held &&
      (ic->second.displacement != 0.0 || ic->second.velocity != 0.0))
    return Demand{fmt::format("has the initial condition u = {:g}, v = {:g}",
                              ic->second.displacement, ic->second.velocity),
                  ic->second.where};
  const bool uses_masters =
      options.type == AnalysisType::Substructure ||
      (options.type == AnalysisType::Transient && options.method == TransientMethod::Reduced);
  if (uses_masters && !held &&
      std::find(model.masters.begin(), model.masters.end(), key) != model.masters.end()) {
    const auto w = model.master_where.find(key);
    return Demand{"is a master DOF (M)",
                  w != model.master_where.end() ? w->second : SourceLocation{}};
  }
  return std::nullopt;
}

[[noreturn]] void fail_mechanism(const DofKey& key, const Demand& demand) {
  throw ModelError(demand.where,
                   fmt::format("{} {} but has neither stiffness nor mass: the model is a "
                               "mechanism there (e.g. a spar or spring loaded across its axis, "
                               "or a zero real constant); connect it to an element that resists "
                               "it or restrain it with D",
                               describe(key), demand.what));
}

/// MP,DAMP: stiffness-proportional damping of each element's material, C_e += β K_e (MAPDL's
/// material BETD; APDL_MODELING §6.1, M6), element order; empty when no material has it. The
/// full (static/transient) solution assembles it element by element; the reduced drivers form C
/// from global ALPHAD/BETAD only, so there it is refused rather than ignored. The same holds for
/// MP,ALPD / MP,BETD (Element::material_damping, which the assembler adds).
std::vector<double> damping_of_materials(const Model& model, const AnalysisOptions& options) {
  std::vector<double> material_beta;
  const ElementRecord* damped = nullptr;  // the first element whose material is damped
  for (const auto& [id, record] : model.elements) {
    double beta = 0.0;
    bool material_damping = false;
    if (auto m = model.materials.find(record.mat); m != model.materials.end()) {
      beta = m->second.get("DAMP", 0.0);
      material_damping =
          beta != 0.0 || m->second.get("ALPD", 0.0) != 0.0 || m->second.get("BETD", 0.0) != 0.0;
    }
    if (material_damping && damped == nullptr) damped = &record;
    material_beta.push_back(beta);
  }
  if (std::all_of(material_beta.begin(), material_beta.end(), [](double b) { return b == 0.0; }))
    material_beta.clear();
  const bool reduced_damping =
      (options.type == AnalysisType::Transient && options.method != TransientMethod::Full) ||
      options.type == AnalysisType::Harmonic ||
      (options.type == AnalysisType::Substructure && options.superelement_matrices == 3);
  if (damped != nullptr && reduced_damping) {
    throw InputError(
        damped->where,
        fmt::format("element {}: its material {} has MP,DAMP/ALPD/BETD (material damping), which "
                    "only a full transient applies; for a reduced or mode-superposition transient, "
                    "a harmonic analysis or a superelement damping matrix use BETAD (global beta), "
                    "DMPRAT or DMPSTR",
                    damped->id, damped->mat));
  }
  return material_beta;
}

}  // namespace

Structure::Structure(const Model& model, const AnalysisOptions& options,
                     const RunSettings& settings, const std::vector<LoadStep>* steps)
    : model_(model), options_(options) {
  context_.large_deflection = options.large_deflection;
  context_.stress_stiffening = options.stress_stiffening || options.large_deflection;
  context_.lumped_mass = options.lumped_mass;

  for (const auto& [id, node] : model.nodes) node_ids_.push_back(id);
  index_node_rows();

  ElementBuildContext build{
      model, [&settings](const ElementRecord& r) { return resolve_superelement(r, settings); }};
  build.large_deflection = options.large_deflection;
  // Rotated nodes (DOFs in nodal axes) enter through an element adapter, material damping as
  // data of the element (assembly/element_adapters.h).
  // Each element made is also handed to the build pass's cache: contact elements read their
  // body elements' stiffness and depth from it instead of making them again.
  for (const auto& [id, record] : model.elements) {
    std::unique_ptr<Element> element = create_element(build, record);
    build_cache(build).built[id] = element.get();
    elements_.push_back(std::move(element));
  }
  // The constraint equations read the elements as built (their DOFs, MPC184's equations); the
  // adapters then eliminate the slaves (assembly/constraint_equations.h).
  eliminate_constraint_equations(steps);
  {
    std::size_t e = 0;
    for (const auto& [id, record] : model.elements) {
      elements_[e] = adapt_element(std::move(elements_[e]), model, record, dependent_);
      ++e;
    }
  }
  std::map<std::string, std::vector<std::size_t>> members;
  for (std::size_t e = 0; e < elements_.size(); ++e)
    if (!elements_[e]->result_names().empty()) members[elements_[e]->family()].push_back(e);
  for (auto& [family, list] : members) {
    ResultFamily& f = result_families_.emplace_back();
    f.name = family;
    for (std::size_t e : list) f.element_ids.push_back(elements_[e]->id());
    f.members = std::move(list);
  }

  material_beta_ = damping_of_materials(model, options);

  // Automatic constraints: DOFs without stiffness and without mass (spec §10.1 item 5).
  // Status elements (gaps) count as stiffness: a gap may close later.
  DofMap all(elements_, {}, coupled_dofs(), dependent_);
  VectorXd stiff = VectorXd::Zero(all.n_active());
  VectorXd mass = VectorXd::Zero(all.n_active());
  Eigen::MatrixXd k, m;
  VectorXd zero, f;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Element& element = *elements_[e];
    const auto& idx = all.element_indices(e);
    zero.setZero(element.n_dofs());
    element.tangent(context_, zero, k, f);
    element.mass(context_, m);
    for (int a = 0; a < element.n_dofs(); ++a) {
      stiff(idx[a]) += std::abs(k(a, a)) + (element.has_status() ? 1.0 : 0.0);
      mass(idx[a]) += std::abs(m(a, a));
    }
  }
  for (int i = 0; i < all.n_active(); ++i)
    if (stiff(i) == 0.0 && mass(i) == 0.0) automatic_.insert(all.key(i));
  // Nothing acting on such a DOF may vanish with it: a load, an initial condition or a master
  // designation on it means the model is a mechanism there (issue 12: no silent wrong answer).
  for (const auto& key : automatic_)
    if (const auto demand = demand_on(key, model, options, steps)) fail_mechanism(key, *demand);
  // Report only the DOFs the deck leaves free in some load step: the others are held anyway.
  std::set<DofKey> reported;
  for (const auto& key : automatic_)
    if (!held_in_every_step(key, steps)) reported.insert(key);
  if (!reported.empty())
    Log::warn("{} DOF(s) have neither stiffness nor mass and are constrained to zero:{}",
              reported.size(), dof_list(reported));
  // A dynamic analysis: free translational DOFs with stiffness but no mass (no DENS, no MASS21)
  // carry no inertia; say which. Massless rotations are normal (lumped masses), and a reduced
  // transient's slaves are massless by design (its masters are checked by the driver).
  const bool dynamic =
      options.type == AnalysisType::Modal || options.type == AnalysisType::Spectrum ||
      (options.type == AnalysisType::Transient && options.method != TransientMethod::Reduced);
  if (dynamic) {
    std::set<DofKey> massless;
    for (int i = 0; i < all.n_active(); ++i) {
      const DofKey key = all.key(i);
      const bool translation = key.dof == Dof::UX || key.dof == Dof::UY || key.dof == Dof::UZ;
      if (translation && stiff(i) != 0.0 && mass(i) == 0.0 && !held_in_every_step(key, steps))
        massless.insert(key);
    }
    if (!massless.empty())
      Log::warn(
          "{} free translational DOF(s) have stiffness but no mass (is DENS missing, or a "
          "MASS21?): they carry no inertia (in a transient they follow the loads "
          "quasi-statically, in a modal analysis they have no mode):{}",
          massless.size(), dof_list(massless));
  }
}

void Structure::check_load_step(const LoadStep& step) const {
  check_slaves_free(step);
  for (const auto& key : automatic_)
    if (const auto demand = force_on(key, step)) fail_mechanism(key, *demand);
}

void Structure::use_table_nodes(const std::vector<int>& ids) {
  if (ids == node_ids_) return;
  const std::set<int> table_ids(ids.begin(), ids.end());
  for (int id : node_ids_)
    if (table_ids.count(id) == 0)
      throw InputError(fmt::format(
          "node {} is not in the model of the results file: the model gained nodes after the job's "
          "first solution; start a new job for the new model (/CLEAR, /FILNAME)",
          id));
  node_ids_ = ids;
  index_node_rows();
}

void Structure::index_node_rows() {
  node_row_dense_.clear();
  node_row_sparse_.clear();
  if (node_ids_.empty()) return;
  const auto [lo, hi] = std::minmax_element(node_ids_.begin(), node_ids_.end());
  const long long span = static_cast<long long>(*hi) - *lo + 1;
  if (span <= 4 * static_cast<long long>(node_ids_.size()) + 1024) {
    node_id_base_ = *lo;
    node_row_dense_.assign(static_cast<std::size_t>(span), -1);
    for (std::size_t r = 0; r < node_ids_.size(); ++r)
      node_row_dense_[static_cast<std::size_t>(node_ids_[r] - node_id_base_)] = static_cast<int>(r);
  } else {
    for (std::size_t r = 0; r < node_ids_.size(); ++r)
      node_row_sparse_[node_ids_[r]] = static_cast<int>(r);
  }
}

int Structure::node_row(int id) const {
  if (node_row_dense_.empty()) return node_row_sparse_.at(id);
  const long long at = static_cast<long long>(id) - node_id_base_;
  const int row = at >= 0 && at < static_cast<long long>(node_row_dense_.size())
                      ? node_row_dense_[static_cast<std::size_t>(at)]
                      : -1;
  if (row < 0) throw std::out_of_range(fmt::format("node {} has no row in the nodal tables", id));
  return row;
}

std::vector<std::vector<DofKey>> Structure::coupled_dofs() const {
  std::vector<std::vector<DofKey>> sets;
  for (const auto& [id, set] : model_.coupled_sets) {
    std::vector<DofKey> keys;
    for (int node : set.nodes) keys.push_back(DofKey{node, set.dof});
    sets.push_back(std::move(keys));
  }
  return sets;
}

std::set<DofKey> Structure::constraints_of(const LoadStep& step) const {
  std::set<DofKey> out = automatic_;
  for (const auto& entry : step.constraints) out.insert(entry.first);
  return out;
}

Eigen::MatrixXd Structure::dof_table(const DofMap& dofs, const VectorXd& values, int first, int end,
                                     bool with_constants) const {
  Eigen::MatrixXd table = Eigen::MatrixXd::Constant(static_cast<int>(node_ids_.size()), 6,
                                                    std::numeric_limits<double>::quiet_NaN());
  // A node's DOFs are mostly consecutive in the map: its row is looked up once per run of them
  // (a lookup per DOF took about 13 ms per stored point of the 155 522-DOF shell dome).
  int node = 0, row = -1;
  for (int i = first; i < end; ++i) {
    const DofKey& key = dofs.key(i);
    if (row < 0 || key.node != node) {
      node = key.node;
      row = node_row(node);
    }
    table(row, static_cast<int>(key.dof)) = values(i);
  }
  // The eliminated DOFs of coupled sets (CP) carry their prime DOF's value; they have no
  // reaction of their own (the table of the constrained DOFs, first > 0, leaves them out).
  if (first == 0)
    for (const auto& [key, index] : dofs.aliases())
      if (index < end) table(node_row(key.node), static_cast<int>(key.dof)) = values(index);
  // The slaves of constraint equations: u_s = Σ a_j u_j (+ g for total displacements); a
  // master no element carries counts as zero. No reaction of their own either.
  if (first == 0 && dofs.dependent() != nullptr)
    for (const auto& [key, dep] : dofs.dependent()->slaves()) {
      double value = with_constants ? dep.constant : 0.0;
      for (const auto& [master, a] : dep.masters) {
        const int index = dofs.index(master);
        if (index >= 0 && index < end) value += a * values(index);
      }
      table(node_row(key.node), static_cast<int>(key.dof)) = value;
    }
  return table;
}

Eigen::MatrixXd Structure::nodal_table(const DofMap& dofs, const VectorXd& values) const {
  return dof_table(dofs, values, 0, dofs.n_active());
}

Eigen::MatrixXd Structure::displacement_table(const DofMap& dofs, const VectorXd& u) const {
  return dof_table(dofs, u, 0, dofs.n_active(), true);
}

Eigen::MatrixXd Structure::reaction_table(const DofMap& dofs, const VectorXd& reactions) const {
  return dof_table(dofs, reactions, dofs.n_free(), dofs.n_active());
}

std::map<std::string, ElementResultTable> Structure::element_results(const Assembler& assembler,
                                                                     const VectorXd& u,
                                                                     const VectorXd& v) const {
  std::map<std::string, ElementResultTable> tables;
  for (const ResultFamily& family : result_families_) {
    const std::vector<std::size_t>& list = family.members;
    ElementResultTable& table = tables[family.name];
    table.item_names = elements_[list.front()]->result_names();
    table.element_ids = family.element_ids;
    table.values.resize(static_cast<int>(list.size()), static_cast<int>(table.item_names.size()));
    // Rows in runs of kResultRun elements, each with its own scratch: in parallel when the family
    // has a few runs (a stored point of the dome's 25 600 shells took ~30 ms on one thread). An
    // element's results depend on its own DOF values and state only (as its tangent in the
    // assembler's parallel loop), so the table is the same on any thread count; an exception
    // comes back as the one of the lowest run, where a serial loop would throw it first.
    constexpr int kResultRun = 256;
    const int n_rows = static_cast<int>(list.size());
    const int n_runs = (n_rows + kResultRun - 1) / kResultRun;
    const auto run = [&](int k) {
      VectorXd ue, ve;
      ElementResultValues values;
      for (int r = k * kResultRun; r < std::min(n_rows, (k + 1) * kResultRun); ++r) {
        const std::size_t e = list[static_cast<std::size_t>(r)];
        assembler.gather(e, u, ue);
        assembler.gather(e, v, ve);
        elements_[e]->results(context_, ue, ve, values);
        for (std::size_t c = 0; c < values.size() && c < table.item_names.size(); ++c)
          table.values(r, static_cast<int>(c)) = values[c];
      }
    };
    if (n_runs >= 4) {
      threads::parallel_for(n_runs, 1, run);
    } else {
      for (int k = 0; k < n_runs; ++k) run(k);
    }
  }
  return tables;
}

}  // namespace impactfe
