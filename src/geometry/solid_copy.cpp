#include "geometry/solid_copy.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <optional>
#include <set>

#include "core/log.h"
#include "geometry/line_geometry.h"
#include "geometry/solid_builder.h"

namespace impactfe::geometry {

namespace {

struct Rigid {
  Mat3 R;
  Vec3 t;
};

/// The motion of k copy steps when it is rigid: a translation in a Cartesian system, a
/// rotation about (and translation along) the axis of a cylindrical one, a rotation about the
/// axis of a spherical one.
std::optional<Rigid> rigid_motion(const CopyRequest& q, int k) {
  const CoordinateSystem& cs = q.system;
  if (q.mirror >= 0) {
    // A reflection (det R = -1): a line's path system becomes left-handed, which maps the same
    // points (to_global / from_global only use R and its transpose), so arcs stay arcs.
    Mat3 flip = Mat3::Identity();
    flip(q.mirror, q.mirror) = -1.0;
    const Mat3 R = cs.axes * flip * cs.axes.transpose();
    return Rigid{R, cs.origin - R * cs.origin};
  }
  const Vec3 d = k * q.increment;
  if (cs.kind == CsysKind::Cartesian) return Rigid{Mat3::Identity(), cs.axes * d};
  if (d(0) != 0.0) return std::nullopt;
  if (cs.kind == CsysKind::Spherical && d(2) != 0.0) return std::nullopt;
  const Mat3 rz = Eigen::AngleAxisd(d(1) * M_PI / 180.0, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 R = cs.axes * rz * cs.axes.transpose();
  const Vec3 shift = cs.kind == CsysKind::Cylindrical ? Vec3(cs.axes.col(2) * d(2)) : Vec3::Zero();
  return Rigid{R, cs.origin - R * cs.origin + shift};
}

Vec3 moved_point(const CopyRequest& q, const Vec3& x, int k) {
  if (q.mirror >= 0) {
    Vec3 local = q.system.from_global(x);
    local(q.mirror) = -local(q.mirror);
    return q.system.to_global(local);
  }
  return q.system.to_global(q.system.from_global(x) + k * q.increment);
}

struct Closure {
  std::set<int> kps, lines, areas, volumes;
};

Closure closure(const SolidModel& s, const CopyRequest& q, const SourceLocation& where) {
  Closure c;
  auto need = [&](const auto& map, int id, const char* what) {
    if (map.count(id) == 0) throw InputError(where, fmt::format("{} {} is not defined", what, id));
  };
  for (int id : q.pattern) {
    switch (q.kind) {
      case SolidKind::Volume:
        need(s.volumes, id, "volume");
        c.volumes.insert(id);
        break;
      case SolidKind::Area:
        need(s.areas, id, "area");
        c.areas.insert(id);
        break;
      case SolidKind::Line:
        need(s.lines, id, "line");
        c.lines.insert(id);
        break;
      case SolidKind::Keypoint:
        need(s.keypoints, id, "keypoint");
        c.kps.insert(id);
        break;
    }
  }
  for (int v : c.volumes)
    c.areas.insert(s.volumes.at(v).areas.begin(), s.volumes.at(v).areas.end());
  for (int a : c.areas)
    for (int sl : s.areas.at(a).lines) c.lines.insert(std::abs(sl));
  for (int l : c.lines) {
    c.kps.insert(s.lines.at(l).kp1);
    c.kps.insert(s.lines.at(l).kp2);
  }
  return c;
}

void move_pattern(Model& model, const CopyRequest& q, const Closure& c) {
  SolidModel& s = model.solid;
  std::set<int> nodes;
  for (int k : c.kps) {
    Keypoint& kp = s.keypoints.at(k);
    kp.x = moved_point(q, kp.x, 1);
    if (kp.node != 0) nodes.insert(kp.node);
  }
  const auto rigid = rigid_motion(q, 1);
  for (int l : c.lines) {
    Line& line = s.lines.at(l);
    if (rigid) {
      line.path.origin = rigid->R * line.path.origin + rigid->t;
      line.path.axes = rigid->R * line.path.axes;
    } else {
      set_line_path(line, s.keypoints.at(line.kp1).x, s.keypoints.at(line.kp2).x, line.path);
    }
    nodes.insert(line.nodes.begin(), line.nodes.end());
  }
  for (int a : c.areas)
    nodes.insert(s.areas.at(a).grid.nodes.begin(), s.areas.at(a).grid.nodes.end());
  for (int v : c.volumes)
    nodes.insert(s.volumes.at(v).interior_nodes.begin(), s.volumes.at(v).interior_nodes.end());
  for (int n : nodes) {
    Node& node = model.nodes.at(n);
    node.x = moved_point(q, node.x, 1);
  }
}

/// The numbers of the copies of a pattern's entities and nodes (original → copy).
struct CopyMaps {
  std::map<int, int> kps, lines, areas, volumes, nodes;
};

/// Copy k of the pattern's keypoints, lines, areas and volumes, with their attributes and
/// sizes. `warned`: the warning about curved lines under a motion that is not rigid is given
/// once per command.
CopyMaps copy_entities(SolidModel& s, SolidBuilder& b, const CopyRequest& q, const Closure& c,
                       int k, const SourceLocation& where, bool& warned) {
  const auto rigid = rigid_motion(q, k);
  CopyMaps m;
  for (int id : c.kps) {
    const int wanted = q.kinc > 0 ? id + k * q.kinc : 0;
    if (wanted > 0 && s.keypoints.count(wanted) != 0)
      throw InputError(
          where, fmt::format("keypoint {} (copy {} of keypoint {}) already exists", wanted, k, id));
    const Keypoint original = s.keypoints.at(id);
    const int made = b.keypoint(wanted, moved_point(q, original.x, k));
    s.keypoints.at(made).attr = original.attr;
    s.keypoints.at(made).size = original.size;
    m.kps[id] = made;
  }
  for (int id : c.lines) {
    const Line original = s.lines.at(id);
    const int a = m.kps.at(original.kp1), bb = m.kps.at(original.kp2);
    int made = 0;
    if (rigid) {
      made = b.moved_line(id, a, bb, rigid->R, rigid->t);
    } else {
      if (original.path.curvilinear() && !warned) {
        Log::warn(
            "{}:{}: {}: the copy step is not a rigid motion: curved lines keep their "
            "path system between the copied keypoints",
            where.file, where.line, where.command);
        warned = true;
      }
      made = b.line(a, bb, original.path);
    }
    Line& l = s.lines.at(made);
    l.ndiv = original.ndiv;
    l.size = original.size;
    l.angle = original.angle;
    l.space = original.space;
    l.attr = original.attr;
    m.lines[id] = made;
  }
  for (int id : c.areas) {
    const Area original = s.areas.at(id);
    std::vector<int> lines;
    for (int sl : original.lines) lines.push_back(sl > 0 ? m.lines.at(sl) : -m.lines.at(-sl));
    const int made = b.area_from_lines(lines);
    s.areas.at(made).attr = original.attr;
    s.areas.at(made).size = original.size;
    m.areas[id] = made;
  }
  for (int id : c.volumes) {
    std::vector<int> areas;
    for (int a : s.volumes.at(id).areas) areas.push_back(m.areas.at(a));
    const int made = b.volume_from_areas(areas);
    s.volumes.at(made).attr = s.volumes.at(id).attr;
    m.volumes[id] = made;
  }
  return m;
}

/// Copy k of the pattern's mesh: nodes in the order keypoints, lines, areas, volumes; then
/// the elements of each entity.
void copy_mesh(Model& model, Mesher& mesher, const CopyRequest& q, const Closure& c, int k,
               CopyMaps& m) {
  SolidModel& s = model.solid;
  auto node = [&](int n) {
    const auto it = m.nodes.find(n);
    if (it != m.nodes.end()) return it->second;
    const Node& original = model.nodes.at(n);
    const int made = mesher.add_node(moved_point(q, original.x, k));
    model.nodes.at(made).angles_deg = original.angles_deg;
    m.nodes[n] = made;
    return made;
  };
  auto nodes_of = [&](const std::vector<int>& list) {
    std::vector<int> out;
    for (int n : list) out.push_back(node(n));
    return out;
  };
  auto copy_elements = [&](const std::vector<int>& list) {
    std::vector<int> out;
    for (int e : list) {
      const ElementRecord rec = model.elements.at(e);
      out.push_back(mesher.add_element({rec.type, rec.mat, rec.real, rec.secnum, rec.esys},
                                       nodes_of(rec.nodes)));
    }
    return out;
  };
  for (int id : c.kps) {
    const Keypoint& original = s.keypoints.at(id);
    if (original.node != 0 && model.nodes.count(original.node) != 0)
      s.keypoints.at(m.kps.at(id)).node = node(original.node);
  }
  for (int id : c.lines) s.lines.at(m.lines.at(id)).nodes = nodes_of(s.lines.at(id).nodes);
  for (int id : c.areas) {
    const Area& original = s.areas.at(id);
    Area& made = s.areas.at(m.areas.at(id));
    made.grid = original.grid;
    made.grid.nodes = nodes_of(original.grid.nodes);
    made.interior_nodes = nodes_of(original.interior_nodes);
  }
  for (int id : c.volumes)
    s.volumes.at(m.volumes.at(id)).interior_nodes = nodes_of(s.volumes.at(id).interior_nodes);
  for (const auto& [from, to] : m.kps)
    s.keypoints.at(to).elements = copy_elements(s.keypoints.at(from).elements);
  for (const auto& [from, to] : m.lines)
    s.lines.at(to).elements = copy_elements(s.lines.at(from).elements);
  for (const auto& [from, to] : m.areas)
    s.areas.at(to).elements = copy_elements(s.areas.at(from).elements);
  for (const auto& [from, to] : m.volumes)
    s.volumes.at(to).elements = copy_elements(s.volumes.at(from).elements);
}

/// A reflected meshed pattern is meshed again rather than copied (its elements' node order
/// would turn them inside out): each copied volume, area, line and keypoint whose original
/// carries elements gets their attributes and is meshed the way VMESH, AMESH, ... mesh it (a
/// mapped mesh comes out as the mirror image of the original; a free mesh is made anew).
void mesh_reflection(Model& model, Mesher& mesher, const CopyMaps& m) {
  SolidModel& s = model.solid;
  const auto attributes_of = [&model](const std::vector<int>& elements) {
    const ElementRecord& e = model.elements.at(elements.front());
    return EntityAttributes{
        .mat = e.mat, .real = e.real, .type = e.type, .esys = e.esys, .secnum = e.secnum};
  };
  const auto remesh = [&](const std::map<int, int>& copies, auto& entities, auto mesh) {
    for (const auto& [from, to] : copies)
      if (const auto& el = entities.at(from).elements; !el.empty()) {
        entities.at(to).attr = attributes_of(el);
        mesh(to);
      }
  };
  remesh(m.volumes, s.volumes, [&mesher](int id) { mesher.mesh_volume(id); });
  remesh(m.areas, s.areas, [&mesher](int id) { mesher.mesh_area(id); });
  remesh(m.lines, s.lines, [&mesher](int id) { mesher.mesh_line(id); });
  remesh(m.kps, s.keypoints, [&mesher](int id) { mesher.mesh_keypoint(id); });
}

}  // namespace

void copy_solid(Model& model, const CopyRequest& q, Mesher& mesher, const SourceLocation& where) {
  SolidModel& s = model.solid;
  const Closure c = closure(s, q, where);
  if (q.mirror >= 0) {
    if (q.system.kind != CsysKind::Cartesian)
      throw InputError(where,
                       "a reflection needs a Cartesian active coordinate system (CSYS,0 "
                       "or a Cartesian LOCAL)");
    // A mirrored copy of the elements would be inside out (negative Jacobians): the reflected
    // geometry is meshed again (mesh_reflection); a meshed pattern is not moved.
    bool meshed = false;
    for (int a : c.areas) meshed = meshed || !s.areas.at(a).elements.empty();
    for (int v : c.volumes) meshed = meshed || !s.volumes.at(v).elements.empty();
    for (int l : c.lines) meshed = meshed || !s.lines.at(l).elements.empty();
    if (meshed && q.move)
      throw InputError(where,
                       "moving a meshed pattern to its reflection is not supported (IMOVE = 1): "
                       "reflect the geometry before meshing it, or copy it (IMOVE = 0)");
  }
  if (q.move) {
    move_pattern(model, q, c);
    return;
  }
  SolidBuilder b(s, where);
  bool warned = false;
  for (int k = 1; k <= q.copies; ++k) {
    CopyMaps m = copy_entities(s, b, q, c, k, where, warned);
    if (q.copy_mesh && q.mirror >= 0)
      mesh_reflection(model, mesher, m);
    else if (q.copy_mesh)
      copy_mesh(model, mesher, q, c, k, m);
  }
}

}  // namespace impactfe::geometry
