#include "deck/get_functions.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "deck/post_support.h"

namespace impactfe::deck {

namespace {

int as_id(double v) {
  return static_cast<int>(std::lround(v));
}

/// Selected node nearest `p` (lowest number on ties), 0 when none is selected; `skip` excluded.
int nearest_selected_node(const DeckReader& r, const Vec3& p, int skip) {
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int n : selected_nodes(r)) {
    if (n == skip) continue;
    const double d = (r.model.node(n).x - p).squaredNorm();
    if (d < best_d) {  // ascending ids: the first of equal distances is the lowest number
      best_d = d;
      best = n;
    }
  }
  return best;
}

}  // namespace

std::optional<double> model_get_function(DeckReader& r, const Command& c, const std::string& name,
                                         const std::vector<double>& args) {
  auto need = [&](std::size_t n) {
    if (args.size() != n)
      r.fail(c, fmt::format("{} takes {} argument{}", name, n, n == 1 ? "" : "s"));
  };
  auto node = [&](double v) -> const Node& {
    const int id = as_id(v);
    if (r.model.nodes.count(id) == 0)
      r.fail(c, fmt::format("{}: node {} is not defined", name, id));
    return r.model.node(id);
  };
  auto element = [&](double v) -> const ElementRecord& {
    const int id = as_id(v);
    const auto it = r.model.elements.find(id);
    if (it == r.model.elements.end())
      r.fail(c, fmt::format("{}: element {} is not defined", name, id));
    return it->second;
  };
  if (name == "NX" || name == "NY" || name == "NZ") {
    need(1);
    return node(args[0]).x[name[1] - 'X'];
  }
  if (name == "NODE") {
    need(3);
    return nearest_selected_node(r, Vec3(args[0], args[1], args[2]), 0);
  }
  if (name == "NNEAR") {
    need(1);
    return nearest_selected_node(r, node(args[0]).x, as_id(args[0]));
  }
  if (name == "DISTND") {
    need(2);
    return (node(args[0]).x - node(args[1]).x).norm();
  }
  if (name == "ENEARN") {
    need(1);
    const Vec3 p = node(args[0]).x;
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (int e : selected_elements(r)) {
      const double d = (element_centroid(r, e) - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = e;
      }
    }
    return best;
  }
  if (name == "CENTRX" || name == "CENTRY" || name == "CENTRZ") {
    need(1);
    const ElementRecord& e = element(args[0]);
    // From the element's selected nodes (all of them when none is selected).
    std::vector<int> nodes;
    for (int n : e.nodes)
      if (r.selection.nodes.selected(n) && std::find(nodes.begin(), nodes.end(), n) == nodes.end())
        nodes.push_back(n);
    if (nodes.empty()) return element_centroid(r, e.id)[name[5] - 'X'];
    double sum = 0.0;
    for (int n : nodes) sum += r.model.node(n).x[name[5] - 'X'];
    return sum / static_cast<double>(nodes.size());
  }
  if (name == "NELEM") {
    need(2);
    const ElementRecord& e = element(args[0]);
    const int k = as_id(args[1]);
    return k >= 1 && k <= static_cast<int>(e.nodes.size())
               ? e.nodes[static_cast<std::size_t>(k - 1)]
               : 0;
  }
  if (name == "NSEL") {
    need(1);
    const int id = as_id(args[0]);
    if (r.model.nodes.count(id) == 0) return 0.0;
    return r.selection.nodes.selected(id) ? 1.0 : -1.0;
  }
  if (name == "ESEL") {
    need(1);
    const int id = as_id(args[0]);
    if (r.model.elements.count(id) == 0) return 0.0;
    return r.selection.elements.selected(id) ? 1.0 : -1.0;
  }
  if (name == "NDNEXT" || name == "ELNEXT") {
    need(1);
    const auto sel = name == "NDNEXT" ? selected_nodes(r) : selected_elements(r);
    const auto it = std::upper_bound(sel.begin(), sel.end(), as_id(args[0]));
    return it == sel.end() ? 0 : *it;
  }
  if (parse_nodal_item(name) && parse_nodal_item(name)->dataset != 'R' &&
      parse_nodal_item(name)->column >= 0) {
    need(1);
    node(args[0]);
    return nodal_result(r, c, as_id(args[0]), name);
  }
  return std::nullopt;
}

}  // namespace impactfe::deck
