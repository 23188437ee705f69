// Selection of solid-model entities (APDL_MODELING §1.1, §1.4, §1.5): KSEL, LSEL, ASEL, VSEL
// and the associative selects NSLK, NSLL, NSLA, NSLV, ESLL, ESLA, ESLV, KSLL, KSLN, LSLK, LSLA,
// ASLL, ASLV, VSLA; KALL, LALL, AALL, VALL.
#include <fmt/format.h>

#include <cmath>
#include <set>
#include <utility>

#include "deck/modeling_helpers.h"
#include "elements/element_registry.h"
#include "geometry/line_geometry.h"
#include "geometry/mesher.h"

namespace impactfe::deck {

namespace {

SolidModel& solid(DeckReader& r) {
  return r.model.solid;
}

Vec3 in_active(DeckReader& r, const Vec3& x) {
  return r.model.coordinate_systems.active_system().from_global(x);
}

int component_index(DeckReader& r, const Command& c, int field) {
  const std::string comp = r.label(c, field);
  if (comp == "X" || comp.empty()) return 0;
  if (comp == "Y") return 1;
  if (comp == "Z") return 2;
  r.fail(c, fmt::format("bad LOC component '{}' (X, Y, Z)", c.text(field)));
}

/// Attribute items shared by KSEL/LSEL/ASEL/VSEL; nullptr when `item` is not one.
const int* attribute(const EntityAttributes& a, const std::string& item) {
  if (item == "MAT") return &a.mat;
  if (item == "TYPE") return &a.type;
  if (item == "REAL") return &a.real;
  if (item == "ESYS") return &a.esys;
  if (item == "SEC" || item == "SECN") return &a.secnum;
  return nullptr;
}

/// Entities of `boundary` kind lying on exactly one selected entity of the upper kind (EXT).
template <class Upper, class Members>
std::set<int> exterior(const Upper& upper, const Selection& sel, Members members) {
  std::map<int, int> count;
  for (const auto& [id, e] : upper)
    if (sel.selected(id))
      for (int m : members(e)) ++count[m];
  std::set<int> out;
  for (const auto& [m, n] : count)
    if (n == 1) out.insert(m);
  return out;
}

/// KSEL/LSEL/ASEL/VSEL: the candidate test of Item for an entity kind.
template <class Map, class Centroid>
std::function<bool(int)> entity_item(DeckReader& r, const Command& c, const Map& map,
                                     const std::string& number_item, Centroid centroid,
                                     std::function<std::set<int>()> ext) {
  std::string item = r.label(c, 2);
  if (item.empty()) item = number_item;
  if (item == number_item) {
    const auto test = value_test(r, c, 4, true);
    return [test](int id) { return test(id); };
  }
  if (item == "LOC") {
    const int k = component_index(r, c, 3);
    const auto test = value_test(r, c, 4, false);
    return [&r, &map, centroid, test, k](int id) {
      return test(in_active(r, centroid(map.at(id)))(k));
    };
  }
  if (item == "EXT") {
    if (!ext) r.fail(c, "EXT is not available for this entity kind");
    const std::set<int> set = ext();
    return [set](int id) { return set.count(id) != 0; };
  }
  if (attribute(EntityAttributes{}, item) != nullptr) {
    const auto test = value_test(r, c, 4, true);
    return [&map, item, test](int id) { return test(*attribute(map.at(id).attr, item)); };
  }
  return nullptr;
}

void finish_select(DeckReader& r, const Command& c, Selection& sel, const std::vector<int>& ids,
                   SelectType type, const std::function<bool(int)>& test, const char* below) {
  sel.apply(type, ids, test);
  // KSWP = 1 (field 8 of LSEL/ASEL/VSEL): also the lower entities and their mesh.
  if (below != nullptr && r.integer(c, 8, 0) == 1) {
    if (type != SelectType::Select) r.fail(c, "KSWP = 1 is valid only with Type = S");
    select_below(r, below);
  }
}

void cmd_ksel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  auto& map = solid(r).keypoints;
  std::function<bool(int)> test;
  if (type == SelectType::Select || type == SelectType::Reselect || type == SelectType::Also ||
      type == SelectType::Unselect) {
    test = entity_item(
        r, c, map, "KP", [](const Keypoint& k) { return k.x; },
        [&r]() {
          std::set<int> out;
          for (const auto& [id, l] : r.model.solid.lines)
            if (r.model.selection.lines.selected(id)) out.insert({l.kp1, l.kp2});
          return out;
        });
    if (!test)
      r.fail(c, fmt::format("item '{}' not supported (KP, LOC, EXT, MAT, TYPE, REAL, ESYS)",
                            c.text(2)));
  }
  finish_select(r, c, r.model.selection.keypoints, all_ids(map), type, test, nullptr);
}

void cmd_lsel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  auto& map = solid(r).lines;
  std::function<bool(int)> test;
  if (type == SelectType::Select || type == SelectType::Reselect || type == SelectType::Also ||
      type == SelectType::Unselect) {
    test = entity_item(
        r, c, map, "LINE", [](const Line& l) { return geometry::line_centroid(l); },
        [&r]() {
          return exterior(r.model.solid.areas, r.model.selection.areas, [](const Area& a) {
            std::vector<int> out;
            for (int sl : a.lines) out.push_back(std::abs(sl));
            return out;
          });
        });
    const std::string item = r.label(c, 2);
    if (!test && (item == "LENGTH" || item == "RADIUS" || item == "NDIV")) {
      const auto value = value_test(r, c, 4, item == "NDIV");
      geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
      test = [&map, item, value, mesher](int id) {
        const Line& l = map.at(id);
        if (item == "LENGTH") return value(geometry::line_length(l));
        if (item == "NDIV") return value(mesher.line_divisions(id));
        const bool arc =
            l.path.curvilinear() && std::fabs(l.c1(0) - l.c2(0)) <= 1e-9 * std::fabs(l.c1(0));
        return value(arc ? std::fabs(l.c1(0)) : 0.0);
      };
    }
    if (!test)
      r.fail(c, fmt::format("item '{}' not supported (LINE, LOC, EXT, MAT, TYPE, REAL, ESYS, SEC, "
                            "LENGTH, NDIV, RADIUS)",
                            c.text(2)));
  }
  finish_select(r, c, r.model.selection.lines, all_ids(map), type, test, "LINE");
}

void cmd_asel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  auto& map = solid(r).areas;
  std::function<bool(int)> test;
  if (type == SelectType::Select || type == SelectType::Reselect || type == SelectType::Also ||
      type == SelectType::Unselect) {
    const SolidModel& s = solid(r);
    test = entity_item(
        r, c, map, "AREA", [&s](const Area& a) { return geometry::area_centroid(s, a); },
        [&r]() {
          return exterior(r.model.solid.volumes, r.model.selection.volumes,
                          [](const Volume& v) { return v.areas; });
        });
    if (!test)
      r.fail(c, fmt::format("item '{}' not supported (AREA, LOC, EXT, MAT, TYPE, REAL, ESYS, SECN)",
                            c.text(2)));
  }
  finish_select(r, c, r.model.selection.areas, all_ids(map), type, test, "AREA");
}

void cmd_vsel(DeckReader& r, const Command& c) {
  const SelectType type = select_type(r, c, 1);
  auto& map = solid(r).volumes;
  std::function<bool(int)> test;
  if (type == SelectType::Select || type == SelectType::Reselect || type == SelectType::Also ||
      type == SelectType::Unselect) {
    const SolidModel& s = solid(r);
    test = entity_item(r, c, map, "VOLU",
                       [&s](const Volume& v) { return geometry::volume_centroid(s, v); }, {});
    if (!test)
      r.fail(c, fmt::format("item '{}' not supported (VOLU, LOC, MAT, TYPE, REAL, ESYS, SEC)",
                            c.text(2)));
  }
  finish_select(r, c, r.model.selection.volumes, all_ids(map), type, test, "VOLU");
}

// ---- associative selects (§1.5) -----------------------------------------------------------------

void associative(DeckReader& r, const Command& c, Selection& target, const std::vector<int>& ids,
                 const std::set<int>& candidates) {
  target.apply(select_type(r, c, 1, true), ids, [&](int id) { return candidates.count(id) != 0; });
}

/// Nodes owned by the selected entities of each kind (interior), and with `boundary` also the
/// nodes of their boundary entities.
std::set<int> nodes_of_keypoints(DeckReader& r) {
  std::set<int> out;
  for (const auto& [id, k] : solid(r).keypoints)
    if (r.model.selection.keypoints.selected(id) && k.node != 0) out.insert(k.node);
  return out;
}

std::set<int> nodes_of_lines(DeckReader& r, bool ends) {
  std::set<int> out;
  std::set<std::pair<int, int>> edges;  // consecutive nodes of the selected lines
  for (const auto& [id, l] : solid(r).lines) {
    if (!r.model.selection.lines.selected(id) || l.nodes.empty()) continue;
    const std::size_t skip = ends ? 0 : 1;
    out.insert(l.nodes.begin() + static_cast<long>(skip), l.nodes.end() - static_cast<long>(skip));
    for (std::size_t k = 0; k + 1 < l.nodes.size(); ++k)
      edges.insert(std::minmax(l.nodes[k], l.nodes[k + 1]));
  }
  if (edges.empty()) return out;
  // The midside nodes of quadratic elements on those edges lie on the lines too (MAPDL's NSLL
  // selects them; a pressure on the edge of a PLANE183 needs all three nodes).
  for (const auto& [id, e] : r.model.elements) {
    const auto t = r.model.element_types.find(e.type);
    if (t == r.model.element_types.end()) continue;
    const CellTopology& cell = element_type_descriptor(t->second).topology();
    for (int k = 0; k < cell.midside_nodes && cell.n_nodes() <= static_cast<int>(e.nodes.size());
         ++k) {
      const auto& edge = cell.edges[static_cast<std::size_t>(k)];
      const int p = e.nodes[static_cast<std::size_t>(edge[0])];
      const int q = e.nodes[static_cast<std::size_t>(edge[1])];
      if (edges.count(std::minmax(p, q)) != 0)
        out.insert(e.nodes[static_cast<std::size_t>(cell.corner_nodes + k)]);
    }
  }
  return out;
}

std::set<int> nodes_of_areas(DeckReader& r, bool boundary) {
  std::set<int> out;
  for (const auto& [id, a] : solid(r).areas) {
    if (!r.model.selection.areas.selected(id)) continue;
    const auto& list = boundary ? a.grid.nodes : a.interior_nodes;
    out.insert(list.begin(), list.end());
  }
  return out;
}

std::set<int> nodes_of_volumes(DeckReader& r, bool boundary) {
  std::set<int> out;
  for (const auto& [id, v] : solid(r).volumes) {
    if (!r.model.selection.volumes.selected(id)) continue;
    out.insert(v.interior_nodes.begin(), v.interior_nodes.end());
    if (boundary)
      for (int a : v.areas)
        out.insert(solid(r).areas.at(a).grid.nodes.begin(), solid(r).areas.at(a).grid.nodes.end());
  }
  return out;
}

template <class Map>
std::set<int> elements_of(const Map& map, const Selection& sel) {
  std::set<int> out;
  for (const auto& [id, e] : map)
    if (sel.selected(id)) out.insert(e.elements.begin(), e.elements.end());
  return out;
}

int key_field(DeckReader& r, const Command& c, int field) {
  const int k = r.integer(c, field, 0);
  if (k != 0 && k != 1) r.fail(c, fmt::format("field {}: key {} must be 0 or 1", field, k));
  return k;
}

void cmd_nslk(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.nodes, all_ids(r.model.nodes), nodes_of_keypoints(r));
}
void cmd_nsll(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.nodes, all_ids(r.model.nodes),
              nodes_of_lines(r, key_field(r, c, 2) == 1));
}
void cmd_nsla(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.nodes, all_ids(r.model.nodes),
              nodes_of_areas(r, key_field(r, c, 2) == 1));
}
void cmd_nslv(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.nodes, all_ids(r.model.nodes),
              nodes_of_volumes(r, key_field(r, c, 2) == 1));
}
void cmd_esll(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.elements, all_ids(r.model.elements),
              elements_of(solid(r).lines, r.model.selection.lines));
}
void cmd_esla(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.elements, all_ids(r.model.elements),
              elements_of(solid(r).areas, r.model.selection.areas));
}
void cmd_eslv(DeckReader& r, const Command& c) {
  associative(r, c, r.model.selection.elements, all_ids(r.model.elements),
              elements_of(solid(r).volumes, r.model.selection.volumes));
}

void cmd_ksll(DeckReader& r, const Command& c) {
  std::set<int> out;
  for (const auto& [id, l] : solid(r).lines)
    if (r.model.selection.lines.selected(id)) out.insert({l.kp1, l.kp2});
  associative(r, c, r.model.selection.keypoints, all_ids(solid(r).keypoints), out);
}

void cmd_ksln(DeckReader& r, const Command& c) {
  std::set<int> out;
  for (const auto& [id, k] : solid(r).keypoints)
    if (k.node != 0 && r.model.nodes.count(k.node) != 0 && r.model.selection.nodes.selected(k.node))
      out.insert(id);
  associative(r, c, r.model.selection.keypoints, all_ids(solid(r).keypoints), out);
}

void cmd_lslk(DeckReader& r, const Command& c) {
  const bool all = key_field(r, c, 2) == 1;
  const Selection& k = r.model.selection.keypoints;
  std::set<int> out;
  for (const auto& [id, l] : solid(r).lines) {
    const bool a = k.selected(l.kp1), b = k.selected(l.kp2);
    if (all ? (a && b) : (a || b)) out.insert(id);
  }
  associative(r, c, r.model.selection.lines, all_ids(solid(r).lines), out);
}

void cmd_lsla(DeckReader& r, const Command& c) {
  std::set<int> out;
  for (const auto& [id, a] : solid(r).areas)
    if (r.model.selection.areas.selected(id))
      for (int sl : a.lines) out.insert(std::abs(sl));
  associative(r, c, r.model.selection.lines, all_ids(solid(r).lines), out);
}

void cmd_asll(DeckReader& r, const Command& c) {
  const bool all = key_field(r, c, 2) == 1;
  std::set<int> out;
  for (const auto& [id, a] : solid(r).areas) {
    int n = 0;
    for (int sl : a.lines) n += r.model.selection.lines.selected(std::abs(sl)) ? 1 : 0;
    if (all ? n == static_cast<int>(a.lines.size()) : n > 0) out.insert(id);
  }
  associative(r, c, r.model.selection.areas, all_ids(solid(r).areas), out);
}

void cmd_aslv(DeckReader& r, const Command& c) {
  std::set<int> out;
  for (const auto& [id, v] : solid(r).volumes)
    if (r.model.selection.volumes.selected(id)) out.insert(v.areas.begin(), v.areas.end());
  associative(r, c, r.model.selection.areas, all_ids(solid(r).areas), out);
}

void cmd_vsla(DeckReader& r, const Command& c) {
  const bool all = key_field(r, c, 2) == 1;
  std::set<int> out;
  for (const auto& [id, v] : solid(r).volumes) {
    int n = 0;
    for (int a : v.areas) n += r.model.selection.areas.selected(a) ? 1 : 0;
    if (all ? n == static_cast<int>(v.areas.size()) : n > 0) out.insert(id);
  }
  associative(r, c, r.model.selection.volumes, all_ids(solid(r).volumes), out);
}

void cmd_xall(DeckReader& r, const Command& c) {
  Log::info("{}:{}: {}: legacy short form of xSEL,ALL", c.where.file, c.where.line, c.name);
  ModelSelection& s = r.model.selection;
  Selection* target = c.name == "KALL"   ? &s.keypoints
                      : c.name == "LALL" ? &s.lines
                      : c.name == "AALL" ? &s.areas
                      : c.name == "VALL" ? &s.volumes
                      : c.name == "NALL" ? &s.nodes
                                         : &s.elements;
  target->select_all();
}

}  // namespace

SelectType select_type(DeckReader& r, const Command& c, int field, bool associative_only) {
  const auto type = parse_select_type(r.label(c, field));
  if (!type)
    r.fail(c, fmt::format("bad selection type '{}' (S, R, A, U, ALL, NONE, INVE, STAT)",
                          c.text(field)));
  if (associative_only && *type != SelectType::Select && *type != SelectType::Reselect &&
      *type != SelectType::Also && *type != SelectType::Unselect)
    r.fail(c, fmt::format("bad selection type '{}' (S, R, A, U)", c.text(field)));
  if (*type == SelectType::Stat) Log::info("{}:{}: {},STAT", c.where.file, c.where.line, c.name);
  return *type;
}

std::function<bool(double)> value_test(DeckReader& r, const Command& c, int f, bool integer,
                                       bool absolute) {
  // A blank VMIN is 0, as any blank numeric field (NSEL,S,LOC,X: the nodes at x = 0); VMAX
  // defaults to VMIN.
  double vmin = r.real(c, f, 0.0);
  double vmax = r.real(c, f + 1, vmin);
  if (integer) {
    const auto inc = r.opt_int(c, f + 2);
    const int step = inc.value_or(1);
    if (step < 0) r.fail(c, fmt::format("VINC {} must not be negative", step));
    if (vmin > vmax) std::swap(vmin, vmax);
    const long lo = std::lround(vmin), hi = std::lround(vmax);
    const long s = std::max(1, step);
    return [lo, hi, s, absolute](double v) {
      const long x = std::lround(absolute ? std::fabs(v) : v);
      return x >= lo && x <= hi && (x - lo) % s == 0;
    };
  }
  double tol = 0.0;
  if (vmin == vmax)
    tol = vmin != 0.0 ? 0.005 * std::fabs(vmin) : 1e-6;
  else
    tol = 1e-8 * std::fabs(vmax - vmin);
  if (vmin > vmax) std::swap(vmin, vmax);
  return [vmin, vmax, tol, absolute](double v) {
    const double x = absolute ? std::fabs(v) : v;
    return x >= vmin - tol && x <= vmax + tol;
  };
}

void select_below(DeckReader& r, const std::string& kind) {
  ModelSelection& sel = r.model.selection;
  SolidModel& s = solid(r);
  auto replace = [](Selection& target, const std::vector<int>& ids, const std::set<int>& set) {
    target.apply(SelectType::Select, ids, [&](int id) { return set.count(id) != 0; });
  };
  const int level = kind == "VOLU"   ? 4
                    : kind == "AREA" ? 3
                    : kind == "LINE" ? 2
                    : kind == "KP"   ? 1
                                     : 0;
  std::set<int> elements;
  if (level >= 4) {
    std::set<int> areas;
    for (const auto& [id, v] : s.volumes)
      if (sel.volumes.selected(id)) areas.insert(v.areas.begin(), v.areas.end());
    replace(sel.areas, all_ids(s.areas), areas);
    const auto e = elements_of(s.volumes, sel.volumes);
    elements.insert(e.begin(), e.end());
  }
  if (level >= 3) {
    std::set<int> lines;
    for (const auto& [id, a] : s.areas)
      if (sel.areas.selected(id))
        for (int sl : a.lines) lines.insert(std::abs(sl));
    replace(sel.lines, all_ids(s.lines), lines);
    const auto e = elements_of(s.areas, sel.areas);
    elements.insert(e.begin(), e.end());
  }
  if (level >= 2) {
    std::set<int> kps;
    for (const auto& [id, l] : s.lines)
      if (sel.lines.selected(id)) kps.insert({l.kp1, l.kp2});
    replace(sel.keypoints, all_ids(s.keypoints), kps);
    const auto e = elements_of(s.lines, sel.lines);
    elements.insert(e.begin(), e.end());
  }
  if (level >= 1) {
    const auto e = elements_of(s.keypoints, sel.keypoints);
    elements.insert(e.begin(), e.end());
    replace(sel.elements, all_ids(r.model.elements), elements);
  }
  // Nodes: those of the selected elements and those the selected entities own.
  std::set<int> nodes;
  for (const auto& [id, e] : r.model.elements)
    if (sel.elements.selected(id)) nodes.insert(e.nodes.begin(), e.nodes.end());
  if (level >= 1) {
    for (int n : nodes_of_keypoints(r)) nodes.insert(n);
    for (int n : nodes_of_lines(r, true)) nodes.insert(n);
    for (int n : nodes_of_areas(r, true)) nodes.insert(n);
    for (int n : nodes_of_volumes(r, true)) nodes.insert(n);
  }
  replace(sel.nodes, all_ids(r.model.nodes), nodes);
}

void register_entity_selection_commands(std::vector<CommandSpec>& t) {
  const unsigned where = kPrep7 | kSolu | kPost1;
  t.push_back({"KSEL", cmd_ksel, where});
  t.push_back({"LSEL", cmd_lsel, where});
  t.push_back({"ASEL", cmd_asel, where});
  t.push_back({"VSEL", cmd_vsel, where});
  t.push_back({"NSLK", cmd_nslk, where});
  t.push_back({"NSLL", cmd_nsll, where});
  t.push_back({"NSLA", cmd_nsla, where});
  t.push_back({"NSLV", cmd_nslv, where});
  t.push_back({"ESLL", cmd_esll, where});
  t.push_back({"ESLA", cmd_esla, where});
  t.push_back({"ESLV", cmd_eslv, where});
  t.push_back({"KSLL", cmd_ksll, where});
  t.push_back({"KSLN", cmd_ksln, where});
  t.push_back({"LSLK", cmd_lslk, where});
  t.push_back({"LSLA", cmd_lsla, where});
  t.push_back({"ASLL", cmd_asll, where});
  t.push_back({"ASLV", cmd_aslv, where});
  t.push_back({"VSLA", cmd_vsla, where});
  for (const char* name : {"KALL", "LALL", "AALL", "VALL"}) t.push_back({name, cmd_xall, where});
}

}  // namespace impactfe::deck
