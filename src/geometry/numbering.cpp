#include "geometry/numbering.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "geometry/line_geometry.h"

namespace impactfe::geometry {

namespace {

int mapped(const std::map<int, int>& map, int id) {
  const auto it = map.find(id);
  return it == map.end() ? id : it->second;
}

/// Renumbers the keys of a map of records with an `id` member; on a collision the record whose
/// old number equals the target is kept.
template <class Map>
void rekey(Map& items, const std::map<int, int>& map) {
  Map out;
  for (auto& [id, item] : items) {
    const int to = mapped(map, id);
    if (out.count(to) != 0 && id != to) continue;  // merged into an existing item
    item.id = to;
    out[to] = std::move(item);
  }
  items = std::move(out);
}

template <class Key, class Value>
void rekey_dof_map(std::map<Key, Value>& loads, const std::map<int, int>& map) {
  std::map<Key, Value> out;
  for (const auto& [key, value] : loads) {
    Key k = key;
    k.node = mapped(map, key.node);
    if (out.count(k) == 0 || k.node == key.node) out[k] = value;
  }
  loads = std::move(out);
}

template <class Value>
void rekey_entity_loads(std::map<std::pair<int, Dof>, Value>& loads,
                        const std::map<int, int>& map) {
  std::map<std::pair<int, Dof>, Value> out;
  for (const auto& [key, value] : loads) out[{mapped(map, key.first), key.second}] = value;
  loads = std::move(out);
}

void remap_list(std::vector<int>& list, const std::map<int, int>& map) {
  for (int& id : list) id = mapped(map, id);
}

/// Coincident points within `toler` (max coordinate difference) among `points` (id → x), by a
/// spatial hash of cell size `toler`: map each merged id to the kept one.
std::map<int, int> coincident(const std::vector<std::pair<int, Vec3>>& points, double toler,
                              bool keep_high) {
  const double cell = toler > 0.0 ? toler : 1e-12;
  std::map<std::array<long long, 3>, std::vector<std::size_t>> grid;
  auto key = [&](const Vec3& x) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(x(0) / cell)),
                                    static_cast<long long>(std::floor(x(1) / cell)),
                                    static_cast<long long>(std::floor(x(2) / cell))};
  };
  for (std::size_t i = 0; i < points.size(); ++i) grid[key(points[i].second)].push_back(i);
  // Union-find over the points within tolerance of each other.
  std::vector<std::size_t> parent(points.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto k = key(points[i].second);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (std::size_t j : it->second)
            if (j > i && (points[i].second - points[j].second).cwiseAbs().maxCoeff() <= toler)
              parent[find(j)] = find(i);
        }
  }
  std::map<std::size_t, int> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t root = find(i);
    const int id = points[i].first;
    const auto it = kept.find(root);
    if (it == kept.end())
      kept[root] = id;
    else
      it->second = keep_high ? std::max(it->second, id) : std::min(it->second, id);
  }
  std::map<int, int> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int to = kept.at(find(i));
    if (to != points[i].first) out[points[i].first] = to;
  }
  return out;
}

}  // namespace

void renumber_nodes(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  rekey(model.nodes, map);
  for (auto& [id, e] : model.elements) remap_list(e.nodes, map);
  LoadStep& s = model.current;
  rekey_dof_map(s.constraints, map);
  rekey_dof_map(s.forces, map);
  rekey_dof_map(s.constraint_tables, map);
  rekey_dof_map(s.force_tables, map);
  rekey_dof_map(model.initial_conditions, map);
  std::vector<DofKey> masters;
  for (DofKey k : model.masters) {
    k.node = mapped(map, k.node);
    if (std::find(masters.begin(), masters.end(), k) == masters.end()) masters.push_back(k);
  }
  model.masters = std::move(masters);
  for (auto& g : model.gap_conditions) {
    g.node_i = mapped(map, g.node_i);
    g.node_j = mapped(map, g.node_j);
  }
  SolidModel& solid = model.solid;
  for (auto& [id, k] : solid.keypoints) k.node = mapped(map, k.node);
  for (auto& [id, l] : solid.lines) remap_list(l.nodes, map);
  for (auto& [id, a] : solid.areas) {
    remap_list(a.grid.nodes, map);
    remap_list(a.interior_nodes, map);
  }
  for (auto& [id, v] : solid.volumes) remap_list(v.interior_nodes, map);
  model.selection.nodes.renumber(map);
}

void renumber_elements(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  rekey(model.elements, map);
  std::map<FaceKey, SurfaceLoad> pressures;
  for (const auto& [key, load] : model.current.pressures)
    pressures[FaceKey{mapped(map, key.element), key.face}] = load;
  model.current.pressures = std::move(pressures);
  auto remap_unique = [&](std::vector<int>& list) {
    remap_list(list, map);
    std::vector<int> out;
    for (int e : list)
      if (std::find(out.begin(), out.end(), e) == out.end()) out.push_back(e);
    list = std::move(out);
  };
  SolidModel& solid = model.solid;
  for (auto& [id, k] : solid.keypoints) remap_unique(k.elements);
  for (auto& [id, l] : solid.lines) remap_unique(l.elements);
  for (auto& [id, a] : solid.areas) remap_unique(a.elements);
  for (auto& [id, v] : solid.volumes) remap_unique(v.elements);
  model.selection.elements.renumber(map);
}

void renumber_keypoints(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  SolidModel& s = model.solid;
  rekey(s.keypoints, map);
  for (auto& [id, l] : s.lines) {
    l.kp1 = mapped(map, l.kp1);
    l.kp2 = mapped(map, l.kp2);
    if (l.orientation_kb > 0) l.orientation_kb = mapped(map, l.orientation_kb);
    if (l.orientation_ke > 0) l.orientation_ke = mapped(map, l.orientation_ke);
  }
  for (auto& [id, a] : s.areas) remap_list(a.keypoints, map);
  rekey_entity_loads(s.loads.keypoint_constraints, map);
  rekey_entity_loads(s.loads.keypoint_forces, map);
  model.selection.keypoints.renumber(map);
}

void renumber_lines(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  SolidModel& s = model.solid;
  // A merged line may run the other way than the kept one: flip the sign in area loops.
  std::map<int, bool> reversed;
  for (const auto& [from, to] : map)
    if (from != to && s.lines.count(to) != 0 && s.lines.count(from) != 0)
      reversed[from] = s.lines.at(from).kp1 != s.lines.at(to).kp1;
  for (auto& [id, a] : s.areas)
    for (int& sl : a.lines) {
      const int l = std::abs(sl);
      const int sign = (sl > 0 ? 1 : -1) * (reversed.count(l) != 0 && reversed.at(l) ? -1 : 1);
      sl = sign * mapped(map, l);
    }
  rekey(s.lines, map);
  rekey_entity_loads(s.loads.line_constraints, map);
  std::map<int, SymmetryKind> sym;
  for (const auto& [l, kind] : s.loads.line_symmetry) sym[mapped(map, l)] = kind;
  s.loads.line_symmetry = std::move(sym);
  model.selection.lines.renumber(map);
}

void renumber_areas(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  SolidModel& s = model.solid;
  rekey(s.areas, map);
  for (auto& [id, v] : s.volumes) remap_list(v.areas, map);
  rekey_entity_loads(s.loads.area_constraints, map);
  std::map<int, SymmetryKind> sym;
  for (const auto& [a, kind] : s.loads.area_symmetry) sym[mapped(map, a)] = kind;
  s.loads.area_symmetry = std::move(sym);
  std::map<std::pair<int, int>, SurfaceLoad> pressures;
  for (const auto& [key, load] : s.loads.area_pressures)
    pressures[{mapped(map, key.first), key.second}] = load;
  s.loads.area_pressures = std::move(pressures);
  model.selection.areas.renumber(map);
}

void renumber_volumes(Model& model, const std::map<int, int>& map) {
  if (map.empty()) return;
  rekey(model.solid.volumes, map);
  model.selection.volumes.renumber(map);
}

std::map<int, int> coincident_nodes(const Model& model, double toler, bool keep_high) {
  std::vector<std::pair<int, Vec3>> points;
  for (const auto& [id, n] : model.nodes)
    if (model.selection.nodes.selected(id)) points.emplace_back(id, n.x);
  return coincident(points, toler, keep_high);
}

std::map<int, int> coincident_keypoints(const Model& model, double toler) {
  std::vector<std::pair<int, Vec3>> points;
  for (const auto& [id, k] : model.solid.keypoints)
    if (model.selection.keypoints.selected(id)) points.emplace_back(id, k.x);
  return coincident(points, toler, false);
}

std::map<int, int> duplicate_lines(const Model& model) {
  std::map<int, int> out;
  std::map<std::pair<int, int>, std::vector<int>> by_ends;
  for (const auto& [id, l] : model.solid.lines)
    by_ends[{std::min(l.kp1, l.kp2), std::max(l.kp1, l.kp2)}].push_back(id);
  for (const auto& [ends, ids] : by_ends)
    for (std::size_t i = 1; i < ids.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        if (out.count(ids[j]) != 0) continue;
        const Line& a = model.solid.lines.at(ids[j]);
        const Line& b = model.solid.lines.at(ids[i]);
        const double scale = std::max(1.0, line_length(a));
        if ((line_point(a, 0.5) - line_point(b, 0.5)).norm() <= 1e-6 * scale) {
          out[ids[i]] = ids[j];
          break;
        }
      }
  return out;
}

std::map<int, int> duplicate_areas(const Model& model) {
  std::map<int, int> out;
  std::map<std::set<int>, int> seen;
  for (const auto& [id, a] : model.solid.areas) {
    std::set<int> lines;
    for (int sl : a.lines) lines.insert(std::abs(sl));
    const auto [it, fresh] = seen.emplace(lines, id);
    if (!fresh) out[id] = it->second;
  }
  return out;
}

std::map<int, int> duplicate_volumes(const Model& model) {
  std::map<int, int> out;
  std::map<std::set<int>, int> seen;
  for (const auto& [id, v] : model.solid.volumes) {
    const auto [it, fresh] = seen.emplace(std::set<int>(v.areas.begin(), v.areas.end()), id);
    if (!fresh) out[id] = it->second;
  }
  return out;
}

std::map<int, int> duplicate_elements(const Model& model) {
  std::map<int, int> out;
  std::map<std::pair<int, std::set<int>>, int> seen;
  for (const auto& [id, e] : model.elements) {
    if (!model.selection.elements.selected(id) || e.nodes.empty()) continue;
    const auto [it, fresh] =
        seen.emplace(std::pair{e.type, std::set<int>(e.nodes.begin(), e.nodes.end())}, id);
    if (!fresh) out[id] = it->second;
  }
  return out;
}

namespace {

bool close(double a, double b, double toler) {
  return std::fabs(a - b) <= toler * std::max({std::fabs(a), std::fabs(b), 1e-300});
}

/// Merges identical definitions of `items` (equal(a, b)) into the lowest number and points the
/// element records and solid attributes (`field` of each) at the kept one.
template <class Map, class Equal, class Field, class AttrField>
int merge_definitions(Model& model, Map& items, Equal equal, Field field, AttrField attr_field) {
  std::map<int, int> map;
  for (auto it = items.begin(); it != items.end(); ++it)
    for (auto jt = items.begin(); jt != it; ++jt)
      if (map.count(jt->first) == 0 && equal(jt->second, it->second)) {
        map[it->first] = jt->first;
        break;
      }
  for (const auto& [from, to] : map) items.erase(from);
  for (auto& [id, e] : model.elements) field(e) = mapped(map, field(e));
  auto fix = [&](EntityAttributes& a) {
    int& v = attr_field(a);
    if (v > 0) v = mapped(map, v);
  };
  for (auto& [id, k] : model.solid.keypoints) fix(k.attr);
  for (auto& [id, l] : model.solid.lines) fix(l.attr);
  for (auto& [id, a] : model.solid.areas) fix(a.attr);
  for (auto& [id, v] : model.solid.volumes) fix(v.attr);
  return static_cast<int>(map.size());
}

}  // namespace

int merge_materials(Model& model, double toler) {
  return merge_definitions(
      model, model.materials,
      [&](const Material& a, const Material& b) {
        if (a.props.size() != b.props.size()) return false;
        for (const auto& [lab, v] : a.props) {
          const auto it = b.props.find(lab);
          if (it == b.props.end() || !close(v, it->second, toler)) return false;
        }
        return true;
      },
      [](ElementRecord& e) -> int& { return e.mat; },
      [](EntityAttributes& a) -> int& { return a.mat; });
}

int merge_element_types(Model& model) {
  return merge_definitions(
      model, model.element_types,
      [](const ElementType& a, const ElementType& b) {
        return a.ansys_name == b.ansys_name && a.keyopt == b.keyopt;
      },
      [](ElementRecord& e) -> int& { return e.type; },
      [](EntityAttributes& a) -> int& { return a.type; });
}

int merge_real_sets(Model& model, double toler) {
  return merge_definitions(
      model, model.real_sets,
      [&](const RealSet& a, const RealSet& b) {
        if (a.values.size() != b.values.size()) return false;
        for (std::size_t i = 0; i < a.values.size(); ++i)
          if (!close(a.values[i], b.values[i], toler)) return false;
        return true;
      },
      [](ElementRecord& e) -> int& { return e.real; },
      [](EntityAttributes& a) -> int& { return a.real; });
}

int merge_sections(Model& model, double toler) {
  return merge_definitions(
      model, model.sections,
      [&](const Section& a, const Section& b) {
        if (a.type != b.type || a.subtype != b.subtype || a.data.size() != b.data.size())
          return false;
        for (std::size_t i = 0; i < a.data.size(); ++i)
          if (!close(a.data[i], b.data[i], toler)) return false;
        return true;
      },
      [](ElementRecord& e) -> int& { return e.secnum; },
      [](EntityAttributes& a) -> int& { return a.secnum; });
}

}  // namespace impactfe::geometry
