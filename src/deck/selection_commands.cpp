// Selection and components (APDL_MODELING §1): NSEL, ESEL, NSLE, ESLN, ALLSEL, NALL, EALL, CM,
// CMSEL, CMDELE, CMLIST. Valid in /PREP7, /SOLU and the postprocessors (MAPDL allows them
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

std::string component_name(DeckReader& r, const Command& c, int field) {
  const std::string name = r.label(c, field);
  if (name.empty()) r.fail(c, "component name missing");
  const bool ok = std::isalpha(static_cast<unsigned char>(name[0])) != 0 &&
                  std::all_of(name.begin(), name.end(), [](unsigned char ch) {
                    return std::isalnum(ch) != 0 || ch == '_' || ch == '.';
                  });
  if (!ok || name.size() > 256)
    r.fail(c, fmt::format("'{}' is not a valid component name (a letter, then letters, digits, "
                          "'_' or '.')",
                          c.text(field)));
  if (name == "ALL" || name == "STAT" || name == "DEFA")
    r.fail(c, fmt::format("'{}' is reserved and cannot name a component", name));
  return name;
}

std::string component_entity(DeckReader& r, const Command& c, int field) {
  const std::string e = r.label(c, field);
  if (e == "NODE" || e == "ELEM") return e;
  if (e == "KP" || e == "LINE" || e == "AREA" || e == "VOLU")
    r.fail(c, fmt::format("{} components need the solid model, which this model does not have", e));
  r.fail(c, fmt::format("Entity '{}': NODE or ELEM expected", c.text(field)));
}

void cmd_cm(DeckReader& r, const Command& c) {
  // CM,Cname,Entity,--,KOPT
  const std::string name = component_name(r, c, 1);
  Component comp;
  comp.entity = component_entity(r, c, 2);
  comp.ids = comp.entity == "NODE" ? selected_nodes(r) : selected_elements(r);
  if (comp.ids.empty())
    r.fail(c, fmt::format("no {} selected: component {} would be empty",
                          comp.entity == "NODE" ? "nodes" : "elements", name));
  comp.where = c.where;
  Log::info("{}:{}: CM: component {} = {} {}", c.where.file, c.where.line, name, comp.ids.size(),
            comp.entity);
  r.model.components[name] = std::move(comp);
}

void cmd_cmsel(DeckReader& r, const Command& c) {
  // CMSEL,Type,Name,Entity
  std::string t = r.label(c, 1);
  if (t.empty()) t = "S";
  if (t == "ALL" || t == "NONE") {
    const std::string only = r.label(c, 3);
    for (const auto& [name, comp] : r.model.components) {
      if (!only.empty() && comp.entity != only) continue;
      EntitySelection& sel = comp.entity == "NODE" ? r.selection.nodes : r.selection.elements;
      const std::vector<int> defined =
          comp.entity == "NODE" ? ids_of(r.model.nodes) : ids_of(r.model.elements);
      std::set<int> m(comp.ids.begin(), comp.ids.end());
      sel.apply(t == "ALL" ? SelectType::A : SelectType::U, defined,
                [&](int id) { return m.count(id) != 0; });
    }
    return;
  }
  const auto type = parse_select_type(t);
  if (!type || (*type != SelectType::S && *type != SelectType::R && *type != SelectType::A &&
                *type != SelectType::U))
    r.fail(c, fmt::format("Type '{}': S, R, A, U, ALL or NONE expected", c.text(1)));
  const std::string name = r.label(c, 2);
  const auto it = r.model.components.find(name);
  if (it == r.model.components.end())
    r.fail(c, fmt::format("component '{}' is not defined (CM)", c.text(2)));
  const Component& comp = it->second;
  if (!r.label(c, 3).empty() && r.label(c, 3) != comp.entity)
    r.fail(c,
           fmt::format("component {} holds {} entities, not {}", name, comp.entity, r.label(c, 3)));
  const bool nodes = comp.entity == "NODE";
  EntitySelection& sel = nodes ? r.selection.nodes : r.selection.elements;
  const std::vector<int> defined = nodes ? ids_of(r.model.nodes) : ids_of(r.model.elements);
  std::set<int> m(comp.ids.begin(), comp.ids.end());
  sel.apply(*type, defined, [&](int id) { return m.count(id) != 0; });
  report(r, c, nodes ? "nodes" : "elements", sel.count(defined), defined.size(), *type);
}

void cmd_cmdele(DeckReader& r, const Command& c) {
  const std::string name = r.label(c, 1);
  if (name == "ALL" || name.empty()) {
    r.model.components.clear();
    return;
  }
  if (r.model.components.erase(name) == 0)
    r.fail(c, fmt::format("component '{}' is not defined", c.text(1)));
}

void cmd_cmlist(DeckReader& r, const Command& c) {
  // CMLIST,Name,Key (Key 1: list the members too)
  const std::string only = r.label(c, 1);
  const bool members = r.integer(c, 2, 0) == 1;
  if (!only.empty() && only != "ALL" && r.model.components.count(only) == 0)
    r.fail(c, fmt::format("component '{}' is not defined", c.text(1)));
  std::string out = "\n LIST COMPONENTS\n\n  NAME                             TYPE     SIZE\n";
  for (const auto& [name, comp] : r.model.components) {
    if (!only.empty() && only != "ALL" && name != only) continue;
    out += fmt::format("  {:<32} {:<8} {:>6}\n", name, comp.entity, comp.ids.size());
    if (members)
      for (std::size_t k = 0; k < comp.ids.size(); k += 8) {
        out += "   ";
        for (std::size_t j = k; j < std::min(k + 8, comp.ids.size()); ++j)
          out += fmt::format("{:>9}", comp.ids[j]);
        out += "\n";
      }
  }
  print(r, out);
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
  t.push_back({"CM", cmd_cm, where});
  t.push_back({"CMSEL", cmd_cmsel, where});
  t.push_back({"CMDELE", cmd_cmdele, where});
  t.push_back({"CMLIST", cmd_cmlist, kAnywhere});
}

}  // namespace impactfe::deck
