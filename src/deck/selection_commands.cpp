// Selection (APDL_MODELING §1): NSEL, ESEL, NSLE, ESLN, ALLSEL, NALL, EALL (components:
// component_commands.cpp). Valid in /PREP7, /SOLU and the postprocessors (MAPDL allows them
// there); the result-based items (NSEL U/ROT/..., ESEL ETAB) read the current POST1 set.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "deck/post_support.h"
#include "elements/cell_topology.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

SelectType select_type(DeckReader& r, const Command& c) {
  const auto t = parse_select_type(r.label(c, 1));
  if (!t)
    r.fail(c, fmt::format("unknown Type '{}' (S, R, A, U, ALL, NONE, INVE, STAT)", c.text(1)));
  return *t;
}

/// VMIN..VMAX step VINC of fields f, f+1, f+2.
IntRange int_range(DeckReader& r, const Command& c, int f) {
  const auto first = r.opt_int(c, f);
  if (!first) r.fail(c, fmt::format("field {}: VMIN missing", f));
  IntRange range{*first, r.integer(c, f + 1, *first), r.integer(c, f + 2, 1)};
  if (range.step < 0) r.fail(c, "VINC must not be negative");
  if (range.step == 0) range.step = 1;
  if (range.first > range.last) std::swap(range.first, range.last);
  return range;
}

RealWindow window(DeckReader& r, const Command& c, bool result_item) {
  const auto vmin = r.opt_real(c, 4);
  if (!vmin) r.fail(c, "VMIN missing");
  auto vmax = r.opt_real(c, 5);
  const bool kabs = r.integer(c, 7, 0) == 1;
  // Result items: a blank VMAX means +infinity above a positive VMIN, 0 below a negative one.
  if (!vmax && result_item && *vmin != 0.0)
    vmax = *vmin > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  return real_window(*vmin, vmax, kabs);
}

int coordinate_index(DeckReader& r, const Command& c, const std::string& comp) {
  if (comp == "X") return 0;
  if (comp == "Y") return 1;
  if (comp == "Z") return 2;
  r.fail(c, fmt::format("Comp '{}': X, Y or Z expected (the global Cartesian system)", comp));
}

void report(DeckReader& r, const Command& c, const char* what, std::size_t n, std::size_t of,
            SelectType type) {
  if (type == SelectType::Stat) {
    print(r, fmt::format(" {} SELECTED: {} of {}\n", what, n, of));
    return;
  }
  Log::info("{}:{}: {}: {} {} selected (of {})", c.where.file, c.where.line, c.name, n, what, of);
  if (n == 0 && of > 0 && type != SelectType::None) r.warn(c, fmt::format("no {} selected", what));
}

/// NSEL,,EXT: nodes on facets of the selected elements that no other selected element shares.
std::set<int> exterior_nodes(const DeckReader& r) {
  std::map<std::vector<int>, int> count;
  for (int id : selected_elements(r))
    for (auto& f : cell_facets(element_cell(r, id), r.model.elements.at(id).nodes)) ++count[f];
  std::set<int> out;
  for (const auto& [face, n] : count)
    if (n == 1) out.insert(face.begin(), face.end());
  return out;
}

void cmd_nsel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c);
  const std::vector<int> defined = ids_of(r.model.nodes);
  std::function<bool(int)> candidate = [](int) { return true; };
  if (type != SelectType::All && type != SelectType::None && type != SelectType::Inve &&
      type != SelectType::Stat) {
    std::string item = r.label(c, 2);
    if (item.empty()) item = "NODE";
    const std::string comp = r.label(c, 3);
    if (auto members = component_members(r, c, r.label(c, 4), "NODE")) {
      std::set<int> m(members->begin(), members->end());
      candidate = [m](int id) { return m.count(id) != 0; };
    } else if (item == "NODE") {
      const IntRange range = int_range(r, c, 4);
      candidate = [range](int id) { return range.contains(id); };
    } else if (item == "LOC") {
      const int k = coordinate_index(r, c, comp);
      const RealWindow w = window(r, c, false);
      candidate = [&r, w, k](int id) { return w.contains(r.model.node(id).x[k]); };
    } else if (item == "EXT") {
      std::set<int> ext = exterior_nodes(r);
      candidate = [ext](int id) { return ext.count(id) != 0; };
    } else if (item == "D" || item == "F") {
      const bool d = item == "D";
      const auto dof = d ? parse_dof_label(comp) : parse_force_label(comp);
      if (!dof)
        r.fail(c, fmt::format("{} needs a {} label in Comp, got '{}'", item,
                              d ? "DOF (UX..ROTZ)" : "force (FX..MZ)", comp));
      const RealWindow w = window(r, c, false);
      const auto& table = d ? r.model.current.constraints : r.model.current.forces;
      candidate = [&table, w, dof](int id) {
        const auto it = table.find(DofKey{id, *dof});
        return it != table.end() && w.contains(it->second);
      };
    } else if (const std::string lab = nodal_label_of(item, comp); !lab.empty()) {
      const RealWindow w = window(r, c, true);
      std::set<int> hit;
      for (int id : defined)
        if (w.contains(nodal_result(r, c, id, lab))) hit.insert(id);
      candidate = [hit](int id) { return hit.count(id) != 0; };
    } else {
      r.fail(c, fmt::format("item '{}{}{}' not supported (NODE, LOC, EXT, D, F, U, ROT, V, A, RF "
                            "or a component name in VMIN)",
                            item, comp.empty() ? "" : ",", comp));
    }
  }
  r.selection.nodes.apply(type, defined, candidate);
  report(r, c, "nodes", r.selection.nodes.count(defined), defined.size(), type);
}

void cmd_esel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c);
  const std::vector<int> defined = ids_of(r.model.elements);
  std::function<bool(int)> candidate = [](int) { return true; };
  if (type != SelectType::All && type != SelectType::None && type != SelectType::Inve &&
      type != SelectType::Stat) {
    std::string item = r.label(c, 2);
    if (item.empty()) item = "ELEM";
    const std::string comp = r.label(c, 3);
    auto attribute = [&](auto get) {
      const IntRange range = int_range(r, c, 4);
      candidate = [&r, range, get](int id) { return range.contains(get(r.model.elements.at(id))); };
    };
    if (auto members = component_members(r, c, r.label(c, 4), "ELEM")) {
      std::set<int> m(members->begin(), members->end());
      candidate = [m](int id) { return m.count(id) != 0; };
    } else if (item == "ELEM") {
      attribute([](const ElementRecord& e) { return e.id; });
    } else if (item == "TYPE") {
      attribute([](const ElementRecord& e) { return e.type; });
    } else if (item == "MAT") {
      attribute([](const ElementRecord& e) { return e.mat; });
    } else if (item == "REAL") {
      attribute([](const ElementRecord& e) { return e.real; });
    } else if (item == "SEC" || item == "SECN") {
      attribute([](const ElementRecord& e) { return e.secnum; });
    } else if (item == "ESYS") {
      attribute([](const ElementRecord&) { return 0; });  // element systems are global here
    } else if (item == "LIVE") {
      candidate = [](int) { return true; };  // no birth and death: every element is alive
    } else if (item == "ENAME") {
      const std::string v = r.label(c, 4);
      if (v.empty()) r.fail(c, "ENAME: VMIN (element name or number) missing");
      if (const ElementTypeDescriptor* d = find_element_type(v); d != nullptr && !r.params.get(v)) {
        const std::string name = d->name;
        candidate = [&r, name](int id) { return element_type_name(r, id) == name; };
      } else {
        const IntRange range = int_range(r, c, 4);
        candidate = [&r, range](int id) {
          const ElementTypeDescriptor* t = find_element_type(element_type_name(r, id));
          return t != nullptr && range.contains(t->number);
        };
      }
    } else if (item == "CENT") {
      const int k = coordinate_index(r, c, comp);
      const RealWindow w = window(r, c, false);
      candidate = [&r, w, k](int id) { return w.contains(element_centroid(r, id)[k]); };
    } else if (item == "ETAB") {
      const PostState& ps = post_state(r);
      const auto col = std::find_if(ps.etable.begin(), ps.etable.end(),
                                    [&](const EtableColumn& e) { return e.label == comp; });
      if (col == ps.etable.end())
        r.fail(c, fmt::format("ETAB: no element-table column '{}' (ETABLE first)", comp));
      const RealWindow w = window(r, c, true);
      const auto values = col->values;
      candidate = [values, w](int id) {
        const auto it = values.find(id);
        return it != values.end() && w.contains(it->second);
      };
    } else {
      r.fail(c, fmt::format("item '{}' not supported (ELEM, TYPE, MAT, REAL, SEC, ESYS, ENAME, "
                            "CENT, LIVE, ETAB or a component name in VMIN)",
                            item));
    }
  }
  r.selection.elements.apply(type, defined, candidate);
  report(r, c, "elements", r.selection.elements.count(defined), defined.size(), type);
}

SelectType associative_type(DeckReader& r, const Command& c) {
  const SelectType t = select_type(r, c);
  if (t != SelectType::S && t != SelectType::R && t != SelectType::A && t != SelectType::U)
    r.fail(c, fmt::format("Type '{}': S, R, A or U expected", c.text(1)));
  return t;
}

/// The nodes of an element a NodeType keeps: ALL, ACTIVE, CORNER (every node here: no element
/// has midside or orientation-only nodes), MID and INACTIVE (none), POS,n (the n-th node).
std::vector<int> element_nodes_of_kind(DeckReader& r, const Command& c, const ElementRecord& e,
                                       const std::string& kind, int position) {
  if (kind.empty() || kind == "ALL" || kind == "ACTIVE" || kind == "CORNER") return e.nodes;
  if (kind == "MID" || kind == "INACTIVE") return {};
  if (kind == "POS") {
    if (position < 1) r.fail(c, "POS: the node position Num must be 1 or more");
    if (position > static_cast<int>(e.nodes.size())) return {};
    return {e.nodes[static_cast<std::size_t>(position - 1)]};
  }
  r.fail(c, fmt::format("NodeType '{}' not supported (ALL, ACTIVE, INACTIVE, CORNER, MID, POS)",
                        kind));
}

void cmd_nsle(DeckReader& r, const Command& c) {
  // NSLE,Type,NodeType,Num
  const SelectType type = associative_type(r, c);
  std::set<int> nodes;
  for (int id : selected_elements(r))
    for (int n :
         element_nodes_of_kind(r, c, r.model.elements.at(id), r.label(c, 2), r.integer(c, 3, 0)))
      nodes.insert(n);
  const std::vector<int> defined = ids_of(r.model.nodes);
  r.selection.nodes.apply(type, defined, [&](int id) { return nodes.count(id) != 0; });
  report(r, c, "nodes", r.selection.nodes.count(defined), defined.size(), type);
}

void cmd_esln(DeckReader& r, const Command& c) {
  // ESLN,Type,EKEY,NodeType: elements with any (EKEY 0) / all (1) of their nodes selected.
  const SelectType type = associative_type(r, c);
  const int ekey = r.integer(c, 2, 0);
  if (ekey != 0 && ekey != 1) r.fail(c, fmt::format("EKEY {} must be 0 or 1", ekey));
  const std::string kind = r.label(c, 3);
  if (kind == "POS") r.fail(c, "NodeType POS is not valid for ESLN");
  const std::vector<int> defined = ids_of(r.model.elements);
  std::set<int> hit;
  for (int id : defined) {
    const auto nodes = element_nodes_of_kind(r, c, r.model.elements.at(id), kind, 0);
    if (nodes.empty()) continue;
    const auto sel = [&](int n) { return r.selection.nodes.selected(n); };
    if (ekey == 1 ? std::all_of(nodes.begin(), nodes.end(), sel)
                  : std::any_of(nodes.begin(), nodes.end(), sel))
      hit.insert(id);
  }
  r.selection.elements.apply(type, defined, [&](int id) { return hit.count(id) != 0; });
  report(r, c, "elements", r.selection.elements.count(defined), defined.size(), type);
}

void cmd_allsel(DeckReader& r, const Command& c) {
  // ALLSEL,LabT,Entity (APDL_MODELING §1.6). Hierarchy VOLU ⊃ AREA ⊃ LINE ⊃ KP ⊃ ELEM ⊃ NODE.
  const std::string labt = r.label(c, 1).empty() ? "ALL" : r.label(c, 1);
  const std::string entity = r.label(c, 2).empty() ? "ALL" : r.label(c, 2);
  static const char* kEntities[] = {"ALL", "VOLU", "AREA", "LINE", "KP", "ELEM", "NODE"};
  if (std::find(std::begin(kEntities), std::end(kEntities), entity) == std::end(kEntities))
    r.fail(c, fmt::format("Entity '{}' unknown (ALL, VOLU, AREA, LINE, KP, ELEM, NODE)", entity));
  if (labt == "ALL") {
    r.selection.nodes.select_all();
    if (entity != "NODE") r.selection.elements.select_all();
  } else if (labt == "BELOW") {
    if (entity == "ELEM" || entity == "ALL") {
      std::set<int> nodes;
      for (int id : selected_elements(r))
        for (int n : r.model.elements.at(id).nodes) nodes.insert(n);
      r.selection.nodes.apply(SelectType::A, ids_of(r.model.nodes),
                              [&](int id) { return nodes.count(id) != 0; });
    } else if (entity != "NODE") {
      r.fail(c, fmt::format("ALLSEL,BELOW,{} needs the solid model, which this model does not "
                            "have",
                            entity));
    }
  } else {
    r.fail(c, fmt::format("LabT '{}' unknown (ALL or BELOW)", labt));
  }
  Log::info("{}:{}: ALLSEL: {} nodes, {} elements selected", c.where.file, c.where.line,
            selected_nodes(r).size(), selected_elements(r).size());
}

void cmd_nall(DeckReader& r, const Command& c) {
  // Legacy short forms (APDL_MODELING §1.8 [A]).
  Log::info("{}:{}: {} taken as {},ALL", c.where.file, c.where.line, c.name,
            c.name == "NALL" ? "NSEL" : "ESEL");
  if (c.name == "NALL")
    r.selection.nodes.select_all();
  else
    r.selection.elements.select_all();
}

}  // namespace

void register_selection_commands(std::vector<CommandSpec>& t) {
  constexpr unsigned where = kPrep7 | kSolu | kPost1 | kPost26;
  t.push_back({"NSEL", cmd_nsel, where});
  t.push_back({"ESEL", cmd_esel, where});
  t.push_back({"NSLE", cmd_nsle, where});
  t.push_back({"ESLN", cmd_esln, where});
  t.push_back({"ALLSEL", cmd_allsel, kAnywhere});
  t.push_back({"NALL", cmd_nall, where});
  t.push_back({"EALL", cmd_nall, where});
}

}  // namespace impactfe::deck
