#include "deck/model_changes.h"

#include <fmt/format.h>

namespace impactfe::deck {

namespace {

bool same(const MaterialTable& a, const MaterialTable& b) {
  if (a.label != b.label || a.option != b.option || a.temperatures.size() != b.temperatures.size())
    return false;
  for (std::size_t k = 0; k < a.temperatures.size(); ++k) {
    const auto& x = a.temperatures[k];
    const auto& y = b.temperatures[k];
    if (x.temperature != y.temperature || x.constants != y.constants || x.points != y.points)
      return false;
  }
  return true;
}

/// The first id whose entry differs in the two maps (added, removed or changed), by `equal`.
template <typename Map, typename Equal>
std::optional<typename Map::key_type> first_difference(const Map& a, const Map& b, Equal equal) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() || j != b.end()) {
    if (i == a.end()) return j->first;
    if (j == b.end() || i->first < j->first) return i->first;
    if (j->first < i->first) return j->first;
    if (!equal(i->second, j->second)) return i->first;
    ++i;
    ++j;
  }
  return std::nullopt;
}

std::string element_change(const Model& began, const Model& now) {
  // The elements an analysis solves are the selected ones when it began (solution_model).
  auto i = began.elements.begin();
  for (const auto& [id, e] : now.elements) {
    if (!now.selection.elements.selected(id)) continue;
    if (i == began.elements.end() || i->first != id)
      return fmt::format("the elements solved changed (element {} selected or added)", id);
    const ElementRecord& b = i->second;
    if (b.type != e.type || b.real != e.real || b.mat != e.mat || b.secnum != e.secnum ||
        b.esys != e.esys || b.nodes != e.nodes || b.superelement_file != e.superelement_file)
      return fmt::format(
          "element {} changed (type, real constants, material, section, ESYS or nodes)", id);
    ++i;
  }
  if (i != began.elements.end())
    return fmt::format("the elements solved changed (element {} unselected or deleted)", i->first);
  return {};
}

}  // namespace

std::string model_change(const Model& began, const Model& now) {
  if (const auto id = first_difference(
          began.element_types, now.element_types, [](const ElementType& a, const ElementType& b) {
            return a.ansys_name == b.ansys_name && a.keyopt == b.keyopt;
          }))
    return fmt::format("element type {} changed (ET, KEYOPT)", *id);
  if (const auto id =
          first_difference(began.real_sets, now.real_sets,
                           [](const RealSet& a, const RealSet& b) { return a.values == b.values; }))
    return fmt::format("real constant set {} changed (R, RMORE, RMODIF)", *id);
  if (const auto id =
          first_difference(began.materials, now.materials,
                           [](const Material& a, const Material& b) { return a.props == b.props; }))
    return fmt::format("material {} changed (MP, MPDATA)", *id);
  if (const auto key = first_difference(
          began.material_tables, now.material_tables,
          [](const MaterialTable& a, const MaterialTable& b) { return same(a, b); }))
    return fmt::format("TB table {} of material {} changed (TB, TBDATA, TBPT)", key->second,
                       key->first);
  if (const auto id =
          first_difference(began.sections, now.sections, [](const Section& a, const Section& b) {
            return a.type == b.type && a.subtype == b.subtype && a.data == b.data;
          }))
    return fmt::format("section {} changed (SECTYPE, SECDATA)", *id);
  if (const auto id = first_difference(began.nodes, now.nodes, [](const Node& a, const Node& b) {
        return a.x == b.x && a.angles_deg == b.angles_deg;
      }))
    return fmt::format("node {} changed (N, NMODIF, added or deleted)", *id);
  return element_change(began, now);
}

}  // namespace impactfe::deck
