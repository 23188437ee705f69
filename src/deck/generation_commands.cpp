// Generation commands FILL, NGEN, EGEN, ENGEN (APDL_SUBSET §3.8, §3.9, §3.11, §3.12).
#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <optional>

#include "core/log.h"
#include "deck/deck_context.h"
#include "deck/post_support.h"
#include "elements/element_registry.h"
#include "geometry/line_geometry.h"
#include "geometry/spacing.h"

namespace impactfe::deck {

void check_model_size(const DeckReader& r, const Command& c, long long new_nodes,
                      long long new_elements) {
  const auto nodes = static_cast<long long>(r.model.nodes.size()) + std::max(0LL, new_nodes);
  const auto elements =
      static_cast<long long>(r.model.elements.size()) + std::max(0LL, new_elements);
  if (nodes > static_cast<long long>(r.options.max_nodes))
    r.fail(c, fmt::format("this would make {} nodes, more than the limit of {}", nodes,
                          r.options.max_nodes));
  if (elements > static_cast<long long>(r.options.max_elements))
    r.fail(c, fmt::format("this would make {} elements, more than the limit of {}", elements,
                          r.options.max_elements));
}

int checked_number(const DeckReader& r, const Command& c, long long number, const char* what) {
  if (number <= 0 || number > kMaxEntityNumber)
    r.fail(c,
           fmt::format("generated {} number {} is outside 1..{}", what, number, kMaxEntityNumber));
  return static_cast<int>(number);
}

namespace {

/// Existing ids of `map` in first, first + inc, ... up to last (inc != 0), in that order:
/// walks the map, never the (possibly huge) number range.
template <class Map>
std::vector<int> existing_in_range(const Map& map, long long first, long long last, long long inc) {
  std::vector<int> out;
  const long long lo = std::min(first, last), hi = std::max(first, last);
  for (auto it = map.lower_bound(static_cast<int>(std::max<long long>(lo, INT_MIN)));
       it != map.end() && it->first <= hi; ++it)
    if ((it->first - first) % inc == 0) out.push_back(it->first);
  if (inc < 0) std::reverse(out.begin(), out.end());
  return out;
}

/// Fractions 0 < f_1 < ... < f_n < 1 of n interior points; SPACE = ratio of the last division to
/// the first (1 = uniform), divisions in geometric progression.
std::vector<double> fill_fractions(int n, double space) {
  const std::vector<double> f = geometry::division_fractions(n + 1, space);
  return {f.begin() + 1, f.end() - 1};
}

void cmd_fill(DeckReader& r, const Command& c) {
  const auto& defined = r.modeling.defined_by_n;
  int node1 = 0;
  int node2 = 0;
  if (c.blank(1) || c.blank(2)) {
    if (defined.size() < 2) r.fail(c, "FILL needs two nodes: fewer than two nodes defined by N");
    node1 = defined[defined.size() - 2];
    node2 = defined[defined.size() - 1];
  }
  node1 = r.integer(c, 1, node1);
  node2 = r.integer(c, 2, node2);
  r.require_node(c, node1);
  r.require_node(c, node2);
  const long long nfill =
      r.integer(c, 3, static_cast<int>(std::abs(static_cast<long long>(node2) - node1) - 1));
  if (nfill <= 0) {
    r.warn(c, fmt::format("no node to fill between {} and {}", node1, node2));
    return;
  }
  long long ninc_default = (static_cast<long long>(node2) - node1) / (nfill + 1);
  if (ninc_default == 0) ninc_default = node2 >= node1 ? 1 : -1;
  const long long ninc = r.integer(c, 5, static_cast<int>(ninc_default));
  const long long nstrt = c.blank(4) ? node1 + ninc : r.integer(c, 4, 0);
  const int itime = std::max(1, r.integer(c, 6, 1));
  const long long inc = r.integer(c, 7, 1);
  const double space = r.real(c, 8, 1.0);
  check_model_size(r, c, nfill * itime, 0);
  const auto f = fill_fractions(static_cast<int>(nfill), space);
  for (int t = 0; t < itime; ++t) {
    const int a = checked_number(r, c, node1 + t * inc, "node");
    const int b = checked_number(r, c, node2 + t * inc, "node");
    r.require_node(c, a);
    r.require_node(c, b);
    const Node na = r.model.nodes.at(a);
    const Node nb = r.model.nodes.at(b);
    for (long long k = 0; k < nfill; ++k) {
      Node n;
      n.id = checked_number(r, c, nstrt + t * inc + k * ninc, "node");
      const double s = f[static_cast<std::size_t>(k)];
      // Interpolated in the active coordinate system (an arc in a cylindrical one).
      n.x = geometry::interpolate_in_system(r.model.coordinate_systems.active_system(), na.x, nb.x,
                                            s);
      n.angles_deg = na.angles_deg + s * (nb.angles_deg - na.angles_deg);
      r.model.nodes[n.id] = n;
    }
  }
}

void cmd_ngen(DeckReader& r, const Command& c) {
  const int itime = r.integer(c, 1, 1);
  const int inc = r.integer(c, 2, 0);
  if (itime < 2) {
    r.warn(c, "ITIME < 2: nothing generated");
    return;
  }
  if (inc == 0) r.fail(c, "node number increment INC is zero (copies would overwrite the pattern)");
  std::vector<int> pattern;
  if (r.label(c, 3) == "ALL") {
    for (const auto& [id, n] : r.model.nodes)
      if (r.model.selection.nodes.selected(id)) pattern.push_back(id);
  } else {
    const auto first = r.opt_int(c, 3);
    if (!first) r.fail(c, "NODE1 missing");
    const int last = r.integer(c, 4, *first);
    int ninc = r.integer(c, 5, 1);
    if (ninc == 0) ninc = 1;
    pattern = existing_in_range(r.model.nodes, *first, last, ninc);
  }
  if (pattern.empty()) r.fail(c, "no existing node in the pattern");
  check_model_size(r, c, static_cast<long long>(pattern.size()) * (itime - 1), 0);
  const Vec3 d(r.real(c, 6, 0.0), r.real(c, 7, 0.0), r.real(c, 8, 0.0));
  const double space = r.real(c, 9, 1.0);
  if (!(space > 0.0)) r.fail(c, fmt::format("SPACE {} must be positive", space));
  // Copy k sits at f_k (ITIME − 1) increments: the last set does not depend on SPACE, the
  // divisions between grow geometrically to SPACE times the first (NGEN notes).
  const std::vector<double> fraction = geometry::division_fractions(itime - 1, space);
  std::vector<Node> source;
  for (int id : pattern) source.push_back(r.model.nodes.at(id));
  const CoordinateSystem active = r.model.coordinate_systems.active_system();
  for (int k = 1; k < itime; ++k) {
    for (const Node& s : source) {
      Node n = s;
      n.id = checked_number(r, c, s.id + static_cast<long long>(k) * inc, "node");
      // DX, DY, DZ are increments in the active coordinate system (DR, Dθ, DZ when cylindrical).
      n.x = active.to_global(active.from_global(s.x) +
                             fraction[static_cast<std::size_t>(k)] * (itime - 1) * d);
      r.model.nodes[n.id] = n;
    }
  }
}

/// Pattern IEL1..IEL2 step IEINC (IEL1 = ALL: the selected elements; a component name: its
/// elements; IEL1 < 0: the last |IEL1| elements created).
std::vector<int> element_pattern(DeckReader& r, const Command& c, int f1) {
  std::vector<int> out;
  if (r.label(c, f1) == "ALL") {
    out = require_selected_elements(r, c);
  } else if (auto members = component_members(r, c, r.label(c, f1), "ELEM")) {
    out = *members;
  } else {
    const auto first = r.opt_int(c, f1);
    if (!first) r.fail(c, "IEL1 missing");
    if (*first < 0) {
      const auto& order = r.modeling.element_order;
      const std::size_t n = std::min(order.size(), static_cast<std::size_t>(-*first));
      for (std::size_t k = order.size() - n; k < order.size(); ++k)
        if (r.model.elements.count(order[k]) != 0) out.push_back(order[k]);
    } else {
      const int last = r.integer(c, f1 + 1, *first);
      int step = r.integer(c, f1 + 2, 1);
      if (step == 0) step = 1;
      out = existing_in_range(r.model.elements, *first, last, step);
    }
  }
  if (out.empty()) r.fail(c, "no existing element in the pattern");
  return out;
}

/// Copies `src` k times its increments; `id` is the new element number. `dxyz`: EGEN's DX,
/// DY, DZ when given: a node of the copy that does not exist yet is generated at the pattern
/// node moved by k (DX, DY, DZ) in the active system, as NGEN,ITIME,NINC,...,DX,DY,DZ before
/// the EGEN would (EGEN notes); without them a missing node is an error.
void copy_element(DeckReader& r, const Command& c, const ElementRecord& src, long long number,
                  long long k, long long ninc, long long minc, long long tinc, long long rinc,
                  long long sinc, const std::optional<Vec3>& dxyz = std::nullopt) {
  ElementRecord e = src;
  const int id = checked_number(r, c, number, "element");
  e.id = id;
  if (minc != 0) e.mat = checked_number(r, c, e.mat + k * minc, "material");
  if (tinc != 0) e.type = checked_number(r, c, e.type + k * tinc, "element type");
  if (rinc != 0) e.real = checked_number(r, c, e.real + k * rinc, "real constant set");
  if (sinc != 0) e.secnum = checked_number(r, c, e.secnum + k * sinc, "section");
  e.where = c.where;
  const auto t = r.model.element_types.find(e.type);
  if (t == r.model.element_types.end())
    r.fail(c, fmt::format("element type {} of generated element {} is not defined", e.type, id));
  const ElementTypeDescriptor& d = element_type_descriptor(t->second);
  if (d.defined_by_file)
    r.fail(c, fmt::format("element {} is a superelement and cannot be copied", src.id));
  for (int& n : e.nodes) {
    // A midside node not given yet (0, left to EMORE or EMID) stays missing in the copy.
    if (n == 0) continue;
    const int from = n;
    n = checked_number(r, c, n + k * ninc, "node");
    if (r.model.nodes.count(n) == 0 && dxyz && from != 0 && r.model.nodes.count(from) != 0) {
      const CoordinateSystem active = r.model.coordinate_systems.active_system();
      Node made = r.model.nodes.at(from);
      made.id = n;
      made.x = active.to_global(active.from_global(made.x) + static_cast<double>(k) * *dxyz);
      r.model.nodes[n] = made;
    }
    if (r.model.nodes.count(n) == 0)
      r.fail(c, fmt::format("node {} of generated element {} (copy of {}) is not defined", n, id,
                            src.id));
  }
  if (static_cast<int>(e.nodes.size()) < d.n_nodes ||
      static_cast<int>(e.nodes.size()) > d.max_nodes())
    r.fail(c, fmt::format("generated element {}: {} needs {} nodes, the pattern has {}", id,
                          t->second.ansys_name, d.n_nodes, e.nodes.size()));
  if (r.model.elements.count(id) == 0) r.modeling.element_order.push_back(id);
  r.model.elements[id] = std::move(e);
}

void cmd_egen(DeckReader& r, const Command& c) {
  // EGEN,ITIME,NINC,IEL1,IEL2,IEINC,MINC,TINC,RINC,CINC,SINC,DX,DY,DZ
  const int itime = r.integer(c, 1, 1);
  if (itime < 2) {
    r.warn(c, "ITIME < 2: nothing generated");
    return;
  }
  const int ninc = r.integer(c, 2, 0);
  const auto pattern = element_pattern(r, c, 3);
  const int minc = r.integer(c, 6, 0), tinc = r.integer(c, 7, 0), rinc = r.integer(c, 8, 0);
  const int sinc = r.integer(c, 10, 0);
  std::optional<Vec3> dxyz;
  if (!c.blank(11) || !c.blank(12) || !c.blank(13))
    dxyz = Vec3(r.real(c, 11, 0.0), r.real(c, 12, 0.0), r.real(c, 13, 0.0));
  check_model_size(r, c, 0, static_cast<long long>(pattern.size()) * (itime - 1));
  std::vector<ElementRecord> src;
  for (int id : pattern) src.push_back(r.model.elements.at(id));
  for (int k = 1; k < itime; ++k)
    for (const auto& e : src) {
      const long long id = static_cast<long long>(r.model.elements.rbegin()->first) + 1;
      copy_element(r, c, e, id, k, ninc, minc, tinc, rinc, sinc, dxyz);
    }
}

void cmd_engen(DeckReader& r, const Command& c) {
  // ENGEN,IINC,ITIME,NINC,IEL1,IEL2,IEINC,MINC,TINC,RINC,CINC,SINC,DX,DY,DZ
  const int iinc = r.integer(c, 1, 0);
  const int itime = r.integer(c, 2, 1);
  if (itime < 2) {
    r.warn(c, "ITIME < 2: nothing generated");
    return;
  }
  if (iinc == 0) r.fail(c, "element number increment IINC is zero");
  const int ninc = r.integer(c, 3, 0);
  const auto pattern = element_pattern(r, c, 4);
  const int minc = r.integer(c, 7, 0), tinc = r.integer(c, 8, 0), rinc = r.integer(c, 9, 0);
  const int sinc = r.integer(c, 11, 0);
  std::optional<Vec3> dxyz;
  if (!c.blank(12) || !c.blank(13) || !c.blank(14))
    dxyz = Vec3(r.real(c, 12, 0.0), r.real(c, 13, 0.0), r.real(c, 14, 0.0));
  check_model_size(r, c, 0, static_cast<long long>(pattern.size()) * (itime - 1));
  std::vector<ElementRecord> src;
  for (int id : pattern) src.push_back(r.model.elements.at(id));
  for (int k = 1; k < itime; ++k)
    for (const auto& e : src)
      copy_element(r, c, e, e.id + static_cast<long long>(k) * iinc, k, ninc, minc, tinc, rinc,
                   sinc, dxyz);
}

void cmd_emid(DeckReader& r, const Command& c) {
  // EMID,Key,Edges: midside nodes added to the selected elements whose (current) type has
  // them, at the middle of each straight edge and shared by the elements on that edge; a
  // collapsed edge (K = L) takes its corner as its midside node. Elements that already have
  // all their midside nodes are left as they are.
  const std::string key = r.label(c, 1), edges = r.label(c, 2);
  if (!key.empty() && key != "ADD")
    r.fail(c, fmt::format("Key '{}' is not supported (ADD: add midside nodes)", c.text(1)));
  if (!edges.empty() && edges != "BOTH")
    r.fail(c, fmt::format("Edges '{}' is not supported (BOTH)", c.text(2)));
  std::map<std::pair<int, int>, int> made;
  int added = 0;
  for (int id : require_selected_elements(r, c)) {
    ElementRecord& e = r.model.elements.at(id);
    const auto t = r.model.element_types.find(e.type);
    if (t == r.model.element_types.end()) continue;
    const CellTopology& cell = element_type_descriptor(t->second).topology();
    if (cell.midside_nodes == 0 || static_cast<int>(e.nodes.size()) < cell.corner_nodes) continue;
    e.nodes.resize(static_cast<std::size_t>(cell.n_nodes()), 0);
    for (int k = 0; k < cell.midside_nodes; ++k) {
      int& slot = e.nodes[static_cast<std::size_t>(cell.corner_nodes + k)];
      if (slot != 0) continue;
      const auto& edge = cell.edges[static_cast<std::size_t>(k)];
      const int a = e.nodes[static_cast<std::size_t>(edge[0])];
      const int b = e.nodes[static_cast<std::size_t>(edge[1])];
      if (a == b) {
        slot = a;
        continue;
      }
      const auto pair = std::minmax(a, b);
      auto it = made.find({pair.first, pair.second});
      if (it == made.end()) {
        Node n;
        n.id =
            checked_number(r, c, static_cast<long long>(r.model.nodes.rbegin()->first) + 1, "node");
        n.x = 0.5 * (r.model.node(a).x + r.model.node(b).x);
        r.model.nodes[n.id] = n;
        it = made.emplace(std::make_pair(pair.first, pair.second), n.id).first;
        ++added;
      }
      slot = it->second;
    }
  }
  Log::info("{}:{}: EMID: {} midside nodes added", c.where.file, c.where.line, added);
}

}  // namespace

void register_generation_commands(std::vector<CommandSpec>& t) {
  t.push_back({"EMID", cmd_emid, kPrep7});
  t.push_back({"FILL", cmd_fill, kPrep7});
  t.push_back({"NGEN", cmd_ngen, kPrep7});
  t.push_back({"EGEN", cmd_egen, kPrep7});
  t.push_back({"ENGEN", cmd_engen, kPrep7});
}

}  // namespace impactfe::deck
