// Selection of nodes and elements (APDL_MODELING §1.2, §1.3, §1.5, §1.6), the subset that model
// building needs: NSEL (NODE, LOC in the active system, EXT), ESEL (ELEM, TYPE, MAT, REAL, SEC,
// ESYS, ENAME, CENT, LIVE), NSLE, ESLN, ALLSEL, NALL, EALL. Built on the shared Selection helper
// (core/selection.h); to be unified with the post-processing branch's selection at merge.
#include <fmt/format.h>

#include <cmath>
#include <set>

#include "deck/modeling_helpers.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

bool is_range_type(SelectType t) {
  return t == SelectType::Select || t == SelectType::Reselect || t == SelectType::Also ||
         t == SelectType::Unselect;
}

const ElementTypeDescriptor* descriptor_of(const DeckReader& r, const ElementRecord& e) {
  const auto it = r.model.element_types.find(e.type);
  return it == r.model.element_types.end() ? nullptr : &element_type_descriptor(it->second);
}

/// Node lists of the element's faces (3-D elements) or edges (area elements): an item shared by
/// no other selected element is exterior.
std::vector<std::vector<int>> boundary_items(const DeckReader& r, const ElementRecord& e) {
  std::vector<std::vector<int>> out;
  const ElementTypeDescriptor* d = descriptor_of(r, e);
  if (d == nullptr) return out;
  const CellTopology& cell = d->topology();
  if (cell.dimension == 3) {
    for (const auto& face : cell.faces) out.push_back(face_with_midsides(cell, face));
    for (auto& face : out)
      for (int& p : face) p = e.nodes[static_cast<std::size_t>(p)];
  } else if (cell.dimension == 2) {
    for (const auto& edge : cell.edges) {
      std::vector<int> nodes = {e.nodes[static_cast<std::size_t>(edge[0])],
                                e.nodes[static_cast<std::size_t>(edge[1])]};
      const int m = cell.midside_of(edge[0], edge[1]);
      if (m >= 0) nodes.push_back(e.nodes[static_cast<std::size_t>(m)]);
      if (nodes[0] != nodes[1]) out.push_back(nodes);
    }
  } else {
    for (int n : e.nodes) out.push_back({n});
  }
  return out;
}

std::set<int> exterior_nodes(const DeckReader& r) {
  std::map<std::set<int>, std::pair<int, std::vector<int>>> count;
  for (const auto& [id, e] : r.model.elements) {
    if (!r.model.selection.elements.selected(id)) continue;
    for (const auto& item : boundary_items(r, e)) {
      auto& entry = count[std::set<int>(item.begin(), item.end())];
      ++entry.first;
      entry.second = item;
    }
  }
  std::set<int> out;
  for (const auto& [key, entry] : count)
    if (entry.first == 1) out.insert(entry.second.begin(), entry.second.end());
  return out;
}

void cmd_nsel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  std::function<bool(int)> test;
  if (is_range_type(type)) {
    std::string item = r.label(c, 2);
    if (item.empty()) item = "NODE";
    const bool kabs = r.integer(c, 7, 0) == 1;
    if (item == "NODE") {
      const auto t = value_test(r, c, 4, true, kabs);
      test = [t](int id) { return t(id); };
    } else if (item == "LOC") {
      const std::string comp = r.label(c, 3);
      const int k = comp == "Y" ? 1 : comp == "Z" ? 2 : 0;
      if (!(comp.empty() || comp == "X" || comp == "Y" || comp == "Z"))
        r.fail(c, fmt::format("bad LOC component '{}' (X, Y, Z)", c.text(3)));
      const auto t = value_test(r, c, 4, false, kabs);
      const CoordinateSystem cs = r.model.coordinate_systems.active_system();
      test = [&r, t, k, cs](int id) { return t(cs.from_global(r.model.nodes.at(id).x)(k)); };
    } else if (item == "EXT") {
      const std::set<int> ext = exterior_nodes(r);
      test = [ext](int id) { return ext.count(id) != 0; };
    } else {
      r.fail(c, fmt::format("item '{}' not supported here (NODE, LOC, EXT)", c.text(2)));
    }
  }
  r.model.selection.nodes.apply(type, all_ids(r.model.nodes), test);
}

void cmd_esel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  std::function<bool(int)> test;
  if (is_range_type(type)) {
    std::string item = r.label(c, 2);
    if (item.empty()) item = "ELEM";
    const auto& elements = r.model.elements;
    if (item == "ELEM" || item == "TYPE" || item == "MAT" || item == "REAL" || item == "SEC" ||
        item == "ESYS") {
      const auto t = value_test(r, c, 4, true);
      test = [&elements, item, t](int id) {
        const ElementRecord& e = elements.at(id);
        const int v = item == "ELEM"   ? id
                      : item == "TYPE" ? e.type
                      : item == "MAT"  ? e.mat
                      : item == "REAL" ? e.real
                      : item == "ESYS" ? e.esys
                                       : e.secnum;
        return t(v);
      };
    } else if (item == "ENAME") {
      const std::string wanted = r.label(c, 4);
      const ElementTypeDescriptor* d = find_element_type(wanted);
      if (d == nullptr) r.fail(c, fmt::format("unknown element name '{}'", c.text(4)));
      test = [&r, d](int id) { return descriptor_of(r, r.model.elements.at(id)) == d; };
    } else if (item == "CENT") {
      const std::string comp = r.label(c, 3);
      const int k = comp == "Y" ? 1 : comp == "Z" ? 2 : 0;
      const auto t = value_test(r, c, 4, false);
      const CoordinateSystem cs = r.model.coordinate_systems.active_system();
      test = [&r, t, k, cs](int id) {
        const auto& nodes = r.model.elements.at(id).nodes;
        Vec3 sum = Vec3::Zero();
        for (int n : nodes) sum += r.model.nodes.at(n).x;
        return !nodes.empty() && t(cs.from_global(sum / static_cast<double>(nodes.size()))(k));
      };
    } else if (item == "LIVE") {
      test = [](int) { return true; };
    } else {
      r.fail(c, fmt::format("item '{}' not supported here (ELEM, TYPE, MAT, REAL, SEC, ESYS, "
                            "ENAME, CENT, LIVE)",
                            c.text(2)));
    }
  }
  r.model.selection.elements.apply(type, all_ids(r.model.elements), test);
}

void cmd_nsle(DeckReader& r, const Command& c) {
  // NSLE,Type,NodeType,Num
  std::string node_type = r.label(c, 2);
  if (node_type.empty()) node_type = "ALL";
  const int num = r.integer(c, 3, 0);
  std::set<int> out;
  for (const auto& [id, e] : r.model.elements) {
    if (!r.model.selection.elements.selected(id)) continue;
    const ElementTypeDescriptor* d = descriptor_of(r, e);
    const int active = d != nullptr ? d->n_nodes : static_cast<int>(e.nodes.size());
    // Corner and midside nodes of the element's cell (a cell without corners: all active ones).
    const int corners =
        d != nullptr && d->topology().corner_nodes > 0 ? d->topology().corner_nodes : active;
    const int midside_end = d != nullptr ? corners + d->topology().midside_nodes : corners;
    for (std::size_t k = 0; k < e.nodes.size(); ++k) {
      const int position = static_cast<int>(k);
      const bool is_active = position < active;
      bool take = false;
      if (node_type == "ALL")
        take = true;
      else if (node_type == "CORNER")
        take = position < corners;
      else if (node_type == "ACTIVE")
        take = is_active;
      else if (node_type == "INACTIVE")
        take = !is_active;
      else if (node_type == "MID")
        take = position >= corners && position < midside_end;
      else if (node_type == "POS")
        take = static_cast<int>(k) + 1 == num;
      else if (node_type == "FACE") {
        if (d == nullptr || num < 1 || num > static_cast<int>(d->faces.size())) continue;
        const auto& face = d->faces[static_cast<std::size_t>(num - 1)];
        take = std::find(face.begin(), face.end(), static_cast<int>(k)) != face.end();
      } else {
        r.fail(c, fmt::format("bad NodeType '{}' (ALL, ACTIVE, INACTIVE, CORNER, MID, POS, FACE)",
                              c.text(2)));
      }
      if (take && e.nodes[k] > 0) out.insert(e.nodes[k]);
    }
  }
  r.model.selection.nodes.apply(select_type(r, c, 1, true), all_ids(r.model.nodes),
                                [&](int id) { return out.count(id) != 0; });
}

void cmd_esln(DeckReader& r, const Command& c) {
  // ESLN,Type,EKEY,NodeType
  const int ekey = r.integer(c, 2, 0);
  if (ekey != 0 && ekey != 1) r.fail(c, fmt::format("EKEY {} must be 0 or 1", ekey));
  std::string node_type = r.label(c, 3);
  if (node_type.empty()) node_type = "ALL";
  if (node_type != "ALL" && node_type != "ACTIVE" && node_type != "INACTIVE" &&
      node_type != "CORNER" && node_type != "MID")
    r.fail(c, fmt::format("bad NodeType '{}' (ALL, ACTIVE, INACTIVE, CORNER, MID)", c.text(3)));
  const Selection& nodes = r.model.selection.nodes;
  auto candidate = [&](int id) {
    const ElementRecord& e = r.model.elements.at(id);
    const ElementTypeDescriptor* d = descriptor_of(r, e);
    const int active = d != nullptr ? d->n_nodes : static_cast<int>(e.nodes.size());
    int counted = 0, selected = 0;
    for (std::size_t k = 0; k < e.nodes.size(); ++k) {
      const bool is_active = static_cast<int>(k) < active;
      const bool counts = node_type == "ALL" ||
                          ((node_type == "ACTIVE" || node_type == "CORNER") && is_active) ||
                          (node_type == "INACTIVE" && !is_active);
      if (!counts) continue;
      ++counted;
      selected += nodes.selected(e.nodes[k]) ? 1 : 0;
    }
    return counted > 0 && (ekey == 1 ? selected == counted : selected > 0);
  };
  r.model.selection.elements.apply(select_type(r, c, 1, true), all_ids(r.model.elements),
                                   candidate);
}

void cmd_allsel(DeckReader& r, const Command& c) {
  // ALLSEL,LabT,Entity
  std::string lab = r.label(c, 1);
  std::string entity = r.label(c, 2);
  if (lab.empty()) lab = "ALL";
  if (entity.empty()) entity = "ALL";
  static const std::vector<std::string> order = {"VOLU", "AREA", "LINE", "KP", "ELEM", "NODE"};
  const auto it = std::find(order.begin(), order.end(), entity);
  if (entity != "ALL" && it == order.end())
    r.fail(c, fmt::format("bad Entity '{}' (ALL, VOLU, AREA, LINE, KP, ELEM, NODE)", c.text(2)));
  ModelSelection& s = r.model.selection;
  if (lab == "ALL") {
    if (entity == "ALL") {
      s.select_everything();
      return;
    }
    Selection* kinds[] = {&s.volumes, &s.areas, &s.lines, &s.keypoints, &s.elements, &s.nodes};
    for (auto k = it; k != order.end(); ++k) kinds[k - order.begin()]->select_all();
  } else if (lab == "BELOW") {
    if (entity == "ALL" || entity == "NODE")
      r.fail(c, "ALLSEL,BELOW needs an entity kind above NODE (VOLU, AREA, LINE, KP, ELEM)");
    select_below(r, entity);
  } else {
    r.fail(c, fmt::format("bad LabT '{}' (ALL, BELOW)", c.text(1)));
  }
}

void cmd_select_all(DeckReader& r, const Command& c) {
  Log::info("{}:{}: {}: legacy short form of {}SEL,ALL", c.where.file, c.where.line, c.name,
            c.name.substr(0, 1));
  if (c.name == "NALL")
    r.model.selection.nodes.select_all();
  else
    r.model.selection.elements.select_all();
}

}  // namespace

void register_mesh_selection_commands(std::vector<CommandSpec>& t) {
  const unsigned where = kPrep7 | kSolu | kPost1;
  t.push_back({"NSEL", cmd_nsel, where | kPost});
  t.push_back({"ESEL", cmd_esel, where | kPost});
  t.push_back({"NSLE", cmd_nsle, where | kPost});
  t.push_back({"ESLN", cmd_esln, where | kPost});
  t.push_back({"ALLSEL", cmd_allsel, where | kPost});
  t.push_back({"NALL", cmd_select_all, where});
  t.push_back({"EALL", cmd_select_all, where});
}

}  // namespace impactfe::deck
