#include "deck/element_forces.h"

#include <fmt/format.h>

#include <algorithm>

#include <cmath>

#include "deck/post_state.h"
#include "deck/post_support.h"
#include "elements/element.h"

namespace impactfe::deck {

namespace {

constexpr const char* kThermalExpansionLabels[] = {"ALPX", "ALPY", "ALPZ"};

/// Values of a nodal array (U, V or A) of the set at the element's DOFs; absent values are 0.
Eigen::VectorXd gather(const Eigen::MatrixXd& m, const std::vector<int>& node_ids,
                       const std::vector<DofKey>& dofs) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const int row = node_row(node_ids, dofs[k].node);
    if (row < 0 || row >= m.rows()) continue;
    const double v = m(row, static_cast<int>(dofs[k].dof));
    if (std::isfinite(v)) out[static_cast<Eigen::Index>(k)] = v;
  }
  return out;
}

/// Whether the element's material expands (ALPX, ALPY or ALPZ) in a model given temperatures.
bool heated_expanding(const DeckReader& r, const ElementRecord& e) {
  if (!r.model.current.gives_temperatures()) return false;
  const auto mat = r.model.materials.find(e.mat);
  if (mat == r.model.materials.end()) return false;
  return std::any_of(std::begin(kThermalExpansionLabels), std::end(kThermalExpansionLabels),
                     [&](const char* alpha) { return mat->second.get(alpha, 0.0) != 0.0; });
}

}  // namespace

std::map<int, std::vector<double>> element_nodal_results(DeckReader& r, const Command& c,
                                                         int element) {
  const auto rec = r.model.elements.find(element);
  if (rec == r.model.elements.end()) return {};
  // The element is rebuilt here without the temperatures of the solution: the extrapolated
  // values of an element whose material expands, in a model given temperatures, would miss its
  // thermal strain, so its stored (centroid) values stand for its nodes.
  if (heated_expanding(r, rec->second)) return {};
  const ResultsReader& reader = results(r, c);
  const SetData& set = current_set(r, c);
  const ElementBuildContext build{r.model, [&](const ElementRecord& e) -> std::string {
                                    throw InputError(c.where, "superelement");
                                  }};
  std::unique_ptr<Element> el;
  try {
    el = create_element(build, rec->second);
  } catch (const InputError&) {
    return {};  // the stored centroid values stand for the nodes
  }
  const AnalysisOptions& o = r.model.options;
  const ElementContext ctx{o.large_deflection, o.stress_stiffening, o.lumped_mass};
  const Eigen::VectorXd u = gather(set.point.displacement, reader.node_ids(), el->dofs());
  std::map<int, std::vector<double>> out;
  if (!el->nodal_results(ctx, u, out)) return {};
  return out;
}

const Mat3& element_result_axes(DeckReader& r, const Command& c, int element) {
  const SetData& set = current_set(r, c);  // first: a new set clears the cache
  PostState& ps = post_state(r);
  if (const auto hit = ps.result_axes.find(element); hit != ps.result_axes.end())
    return hit->second;
  Mat3 axes = Mat3::Identity();
  const auto rec = r.model.elements.find(element);
  if (rec != r.model.elements.end()) {
    const ElementBuildContext build{r.model, [&](const ElementRecord&) -> std::string {
                                      throw InputError(c.where, "superelement");
                                    }};
    try {
      const std::unique_ptr<Element> el = create_element(build, rec->second);
      const AnalysisOptions& o = r.model.options;
      const ElementContext ctx{o.large_deflection, o.stress_stiffening, o.lumped_mass};
      axes = el->result_axes(ctx,
                             gather(set.point.displacement, results(r, c).node_ids(), el->dofs()));
    } catch (const InputError&) {
      // An element that cannot be built from the model now: its values stay as stored.
    }
  }
  return ps.result_axes.emplace(element, axes).first->second;
}

std::map<int, NodalForce> element_nodal_forces(DeckReader& r, const Command& c, int element) {
  const auto rec = r.model.elements.find(element);
  if (rec == r.model.elements.end()) r.fail(c, fmt::format("element {} is not defined", element));
  // Rebuilt without the temperatures of the solution, K u would miss the thermal load.
  if (heated_expanding(r, rec->second))
    r.fail(c, fmt::format("element {}: its nodal forces (NFORCE, FSUM) under a thermal strain are "
                          "not available (the element is rebuilt without its temperatures)",
                          element));
  const ResultsReader& reader = results(r, c);
  const SetData& set = current_set(r, c);
  const ElementBuildContext build{
      r.model, [&](const ElementRecord& e) -> std::string {
        throw InputError(c.where, fmt::format("element {}: nodal forces of a superelement "
                                              "are not available",
                                              e.id));
      }};
  std::unique_ptr<Element> el;
  try {
    el = create_element(build, rec->second);
  } catch (const InputError& e) {
    r.fail(c,
           fmt::format("element {}: nodal forces need the element's data ({})", element, e.what()));
  }
  const AnalysisOptions& o = r.model.options;
  const ElementContext ctx{o.large_deflection, o.stress_stiffening, o.lumped_mass};
  const auto& ids = reader.node_ids();
  const Eigen::VectorXd u = gather(set.point.displacement, ids, el->dofs());
  const Eigen::VectorXd v = gather(set.point.velocity, ids, el->dofs());
  const Eigen::VectorXd a = gather(set.point.acceleration, ids, el->dofs());
  const std::string& kind = post_state(r).force_kind;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
  Eigen::MatrixXd K, M, C;
  Eigen::VectorXd f_int;
  if (el->has_status()) el->update_status(ctx, u);  // the status the displacement implies
  el->tangent(ctx, u, K, f_int);
  if (kind == "TOTAL" || kind == "STATIC") f += f_int;
  if (kind == "TOTAL" || kind == "DAMP") {
    // Element dampers and Rayleigh damping alpha M + beta K (ALPHAD, BETAD).
    if (el->has_damping()) {
      el->damping(ctx, u, C);
      f += C * v;
    }
    if (o.alpha_damping != 0.0 || o.beta_damping != 0.0) {
      el->mass(ctx, M);
      f += (o.alpha_damping * M + o.beta_damping * K) * v;
    }
  }
  if (kind == "TOTAL" || kind == "INERT") {
    el->mass(ctx, M);
    f += M * a;
    // The inertia of the rotational loads (OMEGA, DOMEGA, CGOMGA, DCGOMG) of the load state in
    // the database: M ā, the element's load −M ā taken back (MAPDL's element nodal forces
    // include the inertia of the acceleration effect; vm131 sums them at the support).
    if (const RotationalLoads& w = r.model.current.rotation; w.any()) {
      const auto position = [&](int node) { return r.model.nodes.at(node).x; };
      Eigen::MatrixXd inertia;
      el->acceleration_field_load(ctx, {rotational_acceleration(w)}, position, inertia);
      f -= inertia.col(0);
    }
  }
  std::map<int, NodalForce> out;
  for (std::size_t k = 0; k < el->dofs().size(); ++k) {
    const DofKey& d = el->dofs()[k];
    out[d.node][static_cast<std::size_t>(d.dof)] += f[static_cast<Eigen::Index>(k)];
  }
  for (int n : rec->second.nodes) out.try_emplace(n, NodalForce{});
  return out;
}

std::map<int, NodalForce> nodal_force_sums(DeckReader& r, const Command& c,
                                           const std::vector<int>& elements) {
  std::map<int, NodalForce> sums;
  for (int e : elements)
    for (const auto& [node, f] : element_nodal_forces(r, c, e))
      for (std::size_t k = 0; k < 6; ++k) sums[node][k] += f[k];
  return sums;
}

}  // namespace impactfe::deck
