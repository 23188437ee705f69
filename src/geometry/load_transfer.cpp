#include "geometry/load_transfer.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>

#include "geometry/element_faces.h"
#include "geometry/line_geometry.h"

namespace impactfe::geometry {

namespace {

/// Unit normal of an area from its corner loop (Newell's method).
Vec3 area_normal(const SolidModel& s, const Area& a) {
  Vec3 n = Vec3::Zero();
  const std::size_t k = a.keypoints.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& p = s.keypoints.at(a.keypoints[i]).x;
    const Vec3& q = s.keypoints.at(a.keypoints[(i + 1) % k]).x;
    n += p.cross(q);
  }
  return n.norm() > 0.0 ? Vec3(n.normalized()) : n;
}

struct Writer {
  Model& model;
  SolidLoads& loads;
  std::vector<std::string> notes;

  bool node_ok(int n) const {
    return n != 0 && model.nodes.count(n) != 0 && model.selection.nodes.selected(n);
  }
  void constrain(int node, Dof dof, const SolidDofLoad& v) {
    if (!node_ok(node)) return;
    const DofKey key{node, dof};
    model.current.constraints[key] = v.value;
    if (!v.table.empty())
      model.current.constraint_tables[key] = v.table;
    else
      model.current.constraint_tables.erase(key);
    loads.transferred_constraints.insert(key);
  }
  void force(int node, Dof dof, const SolidDofLoad& v) {
    if (!node_ok(node)) return;
    const DofKey key{node, dof};
    model.current.forces[key] = v.value;
    if (!v.table.empty())
      model.current.force_tables[key] = v.table;
    else
      model.current.force_tables.erase(key);
    loads.transferred_forces.insert(key);
  }
};

}  // namespace

std::vector<Dof> symmetry_dofs(const Vec3& normal, SymmetryKind kind, const SourceLocation& where,
                               const std::string& what) {
  int axis = -1;
  for (int i = 0; i < 3; ++i)
    if (std::fabs(std::fabs(normal(i)) - 1.0) < 1e-6) axis = i;
  if (axis < 0)
    throw InputError(where, fmt::format("{}: the symmetry plane is not normal to a global axis "
                                        "(normal {:.4g} {:.4g} {:.4g}); rotate the nodes "
                                        "(NROTAT) and constrain them with D",
                                        what, normal(0), normal(1), normal(2)));
  std::vector<Dof> dofs;
  for (int i = 0; i < 3; ++i) {
    const bool normal_axis = i == axis;
    if (kind == SymmetryKind::Symmetric ? normal_axis : !normal_axis)
      dofs.push_back(static_cast<Dof>(i));
    if (kind == SymmetryKind::Symmetric ? !normal_axis : normal_axis)
      dofs.push_back(static_cast<Dof>(3 + i));
  }
  return dofs;
}

namespace {

/// The element faces an SFA on area `a` loads: face `lkey` of each area element (shells) on it,
/// else the faces of selected elements of a meshed volume whose nodes all lie on the area (LKEY
/// names area-element faces only, as in MAPDL).
std::vector<FaceKey> area_faces(const Model& model, const Area& a, int lkey) {
  std::vector<FaceKey> faces;
  if (!a.elements.empty()) {
    for (int e : a.elements) faces.push_back(FaceKey{e, lkey});
    return faces;
  }
  const std::vector<int> nodes = area_nodes_with_midsides(model, a.grid.nodes);
  const std::set<int> on_area(nodes.begin(), nodes.end());
  return faces_on_nodes(
      model, [&](int n) { return on_area.count(n) != 0; },
      [&](int e) { return model.selection.elements.selected(e); });
}

}  // namespace

std::vector<std::string> transfer_solid_loads(Model& model, const SourceLocation& where) {
  SolidLoads& loads = model.solid.loads;
  LoadStep& current = model.current;
  for (const DofKey& k : loads.transferred_constraints) {
    current.constraints.erase(k);
    current.constraint_tables.erase(k);
  }
  for (const DofKey& k : loads.transferred_forces) {
    current.forces.erase(k);
    current.force_tables.erase(k);
  }
  for (const FaceKey& f : loads.transferred_pressures) current.pressures.erase(f);
  loads.transferred_constraints.clear();
  loads.transferred_forces.clear();
  loads.transferred_pressures.clear();
  Writer w{model, loads, {}};
  const SolidModel& s = model.solid;
  const ModelSelection& sel = model.selection;
  auto unmeshed = [&](const char* cmd, const char* kind, int id) {
    w.notes.push_back(fmt::format("{} on {} {}: not meshed, nothing transferred", cmd, kind, id));
  };

  for (const auto& [key, v] : loads.keypoint_constraints) {
    const auto it = s.keypoints.find(key.first);
    if (it == s.keypoints.end() || !sel.keypoints.selected(key.first)) continue;
    if (it->second.node == 0) unmeshed("DK", "keypoint", key.first);
    w.constrain(it->second.node, key.second, v);
  }
  for (const auto& [key, v] : loads.keypoint_forces) {
    const auto it = s.keypoints.find(key.first);
    if (it == s.keypoints.end() || !sel.keypoints.selected(key.first)) continue;
    if (it->second.node == 0) unmeshed("FK", "keypoint", key.first);
    w.force(it->second.node, key.second, v);
  }
  for (const auto& [key, v] : loads.line_constraints) {
    const auto it = s.lines.find(key.first);
    if (it == s.lines.end() || !sel.lines.selected(key.first)) continue;
    if (it->second.nodes.empty()) unmeshed("DL", "line", key.first);
    for (int n : line_nodes_with_midsides(model, it->second.nodes)) w.constrain(n, key.second, v);
  }
  for (const auto& [key, v] : loads.area_constraints) {
    const auto it = s.areas.find(key.first);
    if (it == s.areas.end() || !sel.areas.selected(key.first)) continue;
    if (it->second.grid.empty()) unmeshed("DA", "area", key.first);
    for (int n : area_nodes_with_midsides(model, it->second.grid.nodes))
      w.constrain(n, key.second, v);
  }
  for (const auto& [area, kind] : loads.area_symmetry) {
    const auto it = s.areas.find(area);
    if (it == s.areas.end() || !sel.areas.selected(area)) continue;
    const auto dofs =
        symmetry_dofs(area_normal(s, it->second), kind, where, fmt::format("DA on area {}", area));
    for (int n : area_nodes_with_midsides(model, it->second.grid.nodes))
      for (Dof d : dofs) w.constrain(n, d, SolidDofLoad{});
  }
  for (const auto& [line, kind] : loads.line_symmetry) {
    const auto it = s.lines.find(line);
    if (it == s.lines.end() || !sel.lines.selected(line)) continue;
    // The symmetry plane contains the line and the normal of the lowest selected area on it.
    const Area* owner = nullptr;
    for (const auto& [aid, a] : s.areas) {
      if (!sel.areas.selected(aid)) continue;
      for (int sl : a.lines)
        if (std::abs(sl) == line && owner == nullptr) owner = &a;
    }
    if (owner == nullptr)
      throw InputError(where,
                       fmt::format("DL symmetry on line {}: no selected area contains it", line));
    const Vec3 tangent = (line_point(it->second, 1.0) - line_point(it->second, 0.0)).normalized();
    const Vec3 normal = tangent.cross(area_normal(s, *owner)).normalized();
    const auto dofs = symmetry_dofs(normal, kind, where, fmt::format("DL on line {}", line));
    for (int n : line_nodes_with_midsides(model, it->second.nodes))
      for (Dof d : dofs) w.constrain(n, d, SolidDofLoad{});
  }
  for (const auto& [key, load] : loads.area_pressures) {
    const auto it = s.areas.find(key.first);
    if (it == s.areas.end() || !sel.areas.selected(key.first)) continue;
    const Area& a = it->second;
    if (a.grid.empty()) {
      unmeshed("SFA", "area", key.first);
      continue;
    }
    for (const FaceKey& f : area_faces(model, a, key.second)) {
      if (!model.selection.elements.selected(f.element)) continue;
      if (element_face_nodes(model, model.elements.at(f.element), f.face).empty())
        throw InputError(where, fmt::format("SFA on area {}: element {} has no face {}", key.first,
                                            f.element, f.face));
      current.pressures[f] = load;
      loads.transferred_pressures.insert(f);
    }
  }
  return w.notes;
}

}  // namespace impactfe::geometry
