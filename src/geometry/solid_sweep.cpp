#include "geometry/solid_sweep.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "geometry/solid_builder.h"

namespace impactfe::geometry {

namespace {

/// Rigid motion x → R x + t.
struct Motion {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  Vec3 operator()(const Vec3& x) const { return R * x + t; }
};

/// Sweeps the pattern through `nseg` segments; `motion(s)` places level s, `connect(a, b, x)`
/// creates the line from keypoint a (at level s − 1, position x) to b. `closed`: the last level
/// is the pattern itself (full revolution).
std::vector<SweptVolume> sweep(SolidModel& solid, const std::vector<int>& areas, int nseg,
                               bool closed, const std::function<Motion(int)>& motion,
                               const std::function<int(SolidBuilder&, int, int)>& connect,
                               const SourceLocation& where) {
  SolidBuilder b(solid, where);
  std::set<int> kp_set, line_set;
  for (int a : areas) {
    const auto it = solid.areas.find(a);
    if (it == solid.areas.end()) throw InputError(where, fmt::format("area {} is not defined", a));
    for (int sl : it->second.lines) line_set.insert(std::abs(sl));
    for (int k : it->second.keypoints) kp_set.insert(k);
  }
  // Level 0 is the pattern: keypoint, line and area numbers map to themselves.
  std::map<int, int> kp_prev, line_prev, area_prev;
  for (int k : kp_set) kp_prev[k] = k;
  for (int l : line_set) line_prev[l] = l;
  for (int a : areas) area_prev[a] = a;
  std::vector<SweptVolume> out;
  for (int s = 1; s <= nseg; ++s) {
    const bool last_closes = closed && s == nseg;
    const Motion m = motion(s);
    std::map<int, int> kp_next, line_next, area_next;
    for (int k : kp_set) kp_next[k] = last_closes ? k : b.keypoint(0, m(solid.keypoints.at(k).x));
    std::map<int, int> connector;
    for (int k : kp_set) connector[k] = connect(b, kp_prev[k], kp_next[k]);
    for (int l : line_set) {
      const Line& line = solid.lines.at(l);
      line_next[l] =
          last_closes ? l : b.moved_line(l, kp_next[line.kp1], kp_next[line.kp2], m.R, m.t);
    }
    for (int a : areas) {
      if (last_closes) {
        area_next[a] = a;
        continue;
      }
      std::vector<int> lines;
      for (int sl : solid.areas.at(a).lines)
        lines.push_back(sl > 0 ? line_next[sl] : -line_next[-sl]);
      area_next[a] = b.area_from_lines(lines);
    }
    // Side areas, one per pattern line (shared by the areas that share the line).
    std::map<int, int> side;
    for (int l : line_set) {
      const Line& line = solid.lines.at(l);
      side[l] = b.area_from_lines(
          {line_prev[l], connector[line.kp2], -line_next[l], -connector[line.kp1]});
    }
    for (int a : areas) {
      std::vector<int> bounding{area_prev[a], area_next[a]};
      for (int sl : solid.areas.at(a).lines) bounding.push_back(side[std::abs(sl)]);
      SweptVolume v;
      v.volume = b.volume_from_areas(bounding);
      v.source = area_prev[a];
      v.target = area_next[a];
      v.pattern = a;
      for (int sl : solid.areas.at(a).lines) {
        const Line& line = solid.lines.at(std::abs(sl));
        for (int k : {line.kp1, line.kp2})
          if (std::find(v.connectors.begin(), v.connectors.end(), connector[k]) ==
              v.connectors.end())
            v.connectors.push_back(connector[k]);
      }
      out.push_back(v);
    }
    kp_prev = kp_next;
    line_prev = line_next;
    area_prev = area_next;
  }
  return out;
}

}  // namespace

std::vector<SweptVolume> extrude_areas(SolidModel& solid, const std::vector<int>& areas,
                                       const Vec3& d, const SourceLocation& where) {
  return sweep(
      solid, areas, 1, false,
      [&](int) {
        return Motion{Mat3::Identity(), d};
      },
      [](SolidBuilder& b, int k0, int k1) { return b.line(k0, k1, CoordinateSystem{}); }, where);
}

std::vector<SweptVolume> revolve_areas(SolidModel& solid, const std::vector<int>& areas,
                                       const Vec3& p1, const Vec3& p2, double arc, int nseg,
                                       const SourceLocation& where) {
  const double length = (p2 - p1).norm();
  if (length <= 0.0) throw InputError(where, "the axis keypoints coincide");
  const Vec3 axis = (p2 - p1) / length;
  const double step = arc / nseg;
  for (int a : areas)
    if (solid.areas.count(a) != 0)
      for (int k : solid.areas.at(a).keypoints) {
        const Vec3 r = solid.keypoints.at(k).x - p1;
        if ((r - r.dot(axis) * axis).norm() <= 1e-9 * std::max(1.0, r.norm()))
          throw InputError(where, fmt::format("keypoint {} lies on the rotation axis: revolving "
                                              "areas that touch the axis is not supported",
                                              k));
      }
  auto motion = [&](int s) {
    const Mat3 R = Eigen::AngleAxisd(s * step * M_PI / 180.0, axis).toRotationMatrix();
    return Motion{R, p1 - R * p1};
  };
  auto connect = [&](SolidBuilder& b, int k0, int k1) {
    const Vec3 x = solid.keypoints.at(k0).x;
    const Vec3 centre = p1 + (x - p1).dot(axis) * axis;
    return b.arc(k0, k1, centre, axis, step);
  };
  return sweep(solid, areas, nseg, std::fabs(std::fabs(arc) - 360.0) < 1e-9, motion, connect,
               where);
}

void mesh_swept_volumes(Mesher& mesher, SolidModel& solid, const std::vector<SweptVolume>& made) {
  const MeshControls::Extopt& ext = solid.mesh.extopt;
  std::set<int> patterns;
  for (const SweptVolume& v : made) {
    if (solid.areas.at(v.pattern).grid.empty()) continue;  // unmeshed pattern: geometry only
    patterns.insert(v.pattern);
    for (int l : v.connectors) {
      Line& line = solid.lines.at(l);
      if (ext.ndiv > 0 && line.nodes.empty()) {
        line.ndiv = ext.ndiv;
        line.space = ext.space;
      }
    }
    // EXTOPT,ON / ATTR: MAT, REAL, ESYS of the pattern area instead of the current pointers.
    const EntityAttributes& pa = solid.areas.at(v.pattern).attr;
    EntityAttributes& va = solid.volumes.at(v.volume).attr;
    if (ext.on || ext.attr[0] == 1) va.mat = pa.mat;
    if (ext.on || ext.attr[1] == 1) va.real = pa.real;
    if (ext.on || ext.attr[2] == 1) va.esys = pa.esys;
    mesher.mesh_volume(v.volume, v.source, v.target);
  }
  if (ext.on || ext.aclear)
    for (int a : patterns) mesher.clear_area(a);
}

}  // namespace impactfe::geometry
