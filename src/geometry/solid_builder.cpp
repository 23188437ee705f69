#include "geometry/solid_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "elements/cell_topology.h"
#include "geometry/line_geometry.h"

namespace impactfe::geometry {

void SolidBuilder::fail(const std::string& message) const {
  throw InputError(where_, message);
}

const Keypoint& SolidBuilder::kp(int id) const {
  const auto it = s_.keypoints.find(id);
  if (it == s_.keypoints.end()) fail(fmt::format("keypoint {} is not defined", id));
  return it->second;
}

int SolidBuilder::keypoint(int id, const Vec3& x) {
  if (id < 0) fail(fmt::format("keypoint number {} must be positive", id));
  if (id == 0) id = lowest_free(s_.keypoints, s_.numstr.kp);
  if (s_.keypoints.count(id) != 0) {
    for (const auto& [lid, line] : s_.lines)
      if (line.kp1 == id || line.kp2 == id)
        fail(fmt::format("keypoint {} is used by line {} and cannot be redefined", id, lid));
  }
  Keypoint& k = s_.keypoints[id];
  k = Keypoint{};
  k.id = id;
  k.x = x;
  return id;
}

int SolidBuilder::line(int a, int b, const CoordinateSystem& path, int id) {
  const Vec3 xa = kp(a).x, xb = kp(b).x;
  if (a == b) fail(fmt::format("a line needs two different keypoints (got {} twice)", a));
  if ((xa - xb).norm() <= 1e-12 * std::max(1.0, xa.norm()))
    fail(fmt::format("keypoints {} and {} coincide: zero-length line", a, b));
  if (id == 0) id = lowest_free(s_.lines, s_.numstr.line);
  Line l;
  l.id = id;
  l.kp1 = a;
  l.kp2 = b;
  set_line_path(l, xa, xb, path);
  if (line_length(l) <= 1e-12 * std::max(1.0, xa.norm()))
    fail(fmt::format("line {}-{} has zero length in the active coordinate system", a, b));
  s_.lines[id] = l;
  return id;
}

int SolidBuilder::arc(int a, int b, const Vec3& centre, const Vec3& axis, double sweep_deg) {
  const Vec3 xa = kp(a).x;
  kp(b);
  if (a == b) fail(fmt::format("an arc needs two different keypoints (got {} twice)", a));
  const int id = lowest_free(s_.lines, s_.numstr.line);
  Line l;
  l.id = id;
  l.kp1 = a;
  l.kp2 = b;
  set_arc_path(l, xa, centre, axis, sweep_deg);
  s_.lines[id] = l;
  return id;
}

int SolidBuilder::moved_line(int line, int a, int b, const Mat3& R, const Vec3& t) {
  kp(a);
  kp(b);
  Line l = s_.lines.at(line);
  const int id = lowest_free(s_.lines, s_.numstr.line);
  l.id = id;
  l.kp1 = a;
  l.kp2 = b;
  l.path.origin = R * l.path.origin + t;
  l.path.axes = R * l.path.axes;
  l.nodes.clear();
  l.elements.clear();
  s_.lines[id] = l;
  return id;
}

int SolidBuilder::find_line(int a, int b) const {
  for (const auto& [id, l] : s_.lines) {
    if (l.kp1 == a && l.kp2 == b) return id;
    if (l.kp1 == b && l.kp2 == a) return -id;
  }
  return 0;
}

int SolidBuilder::line_between(int a, int b, const CoordinateSystem& path) {
  const int found = find_line(a, b);
  return found != 0 ? found : line(a, b, path);
}

std::vector<int> SolidBuilder::area_keypoints(const std::vector<int>& signed_lines) const {
  std::vector<int> kps;
  for (int sl : signed_lines) {
    const Line& l = s_.lines.at(std::abs(sl));
    kps.push_back(sl > 0 ? l.kp1 : l.kp2);
  }
  return kps;
}

int SolidBuilder::area_from_lines(std::vector<int> lines) {
  if (lines.size() < 3) fail(fmt::format("an area needs at least 3 lines, {} given", lines.size()));
  for (int sl : lines)
    if (s_.lines.count(std::abs(sl)) == 0)
      fail(fmt::format("line {} is not defined", std::abs(sl)));
  {
    std::set<int> unique;
    for (int sl : lines)
      if (!unique.insert(std::abs(sl)).second)
        fail(fmt::format("line {} is listed twice", std::abs(sl)));
  }
  // Chain the lines into one closed loop starting with the first one in its given direction.
  std::vector<int> loop{lines.front()};
  std::vector<int> rest(lines.begin() + 1, lines.end());
  auto start_of = [&](int sl) {
    const Line& l = s_.lines.at(std::abs(sl));
    return sl > 0 ? l.kp1 : l.kp2;
  };
  auto end_of = [&](int sl) {
    const Line& l = s_.lines.at(std::abs(sl));
    return sl > 0 ? l.kp2 : l.kp1;
  };
  while (!rest.empty()) {
    const int at = end_of(loop.back());
    auto it = std::find_if(rest.begin(), rest.end(), [&](int sl) {
      const Line& l = s_.lines.at(std::abs(sl));
      return l.kp1 == at || l.kp2 == at;
    });
    if (it == rest.end())
      fail(
          fmt::format("lines do not form one closed loop: nothing continues from keypoint {}", at));
    const Line& l = s_.lines.at(std::abs(*it));
    loop.push_back(l.kp1 == at ? l.id : -l.id);
    rest.erase(it);
  }
  if (end_of(loop.back()) != start_of(loop.front()))
    fail(fmt::format("lines do not form a closed loop (keypoint {} is not joined back to {})",
                     end_of(loop.back()), start_of(loop.front())));
  const int id = lowest_free(s_.areas, s_.numstr.area);
  Area a;
  a.id = id;
  a.lines = loop;
  a.keypoints = area_keypoints(loop);
  s_.areas[id] = a;
  return id;
}

int SolidBuilder::area_from_keypoints(const std::vector<int>& given, const CoordinateSystem& path) {
  // A keypoint repeated next to itself (A,1,2,5,5: MAPDL's triangle given with four) is one
  // corner; any other repeat is refused.
  std::vector<int> kps;
  for (int k : given)
    if (kps.empty() || kps.back() != k) kps.push_back(k);
  if (kps.size() > 1 && kps.back() == kps.front()) kps.pop_back();
  if (kps.size() < 3)
    fail(fmt::format("an area needs at least 3 distinct keypoints, {} given", kps.size()));
  for (int k : kps) kp(k);
  const std::set<int> wanted(kps.begin(), kps.end());
  if (wanted.size() != kps.size()) fail("a keypoint is listed twice");
  for (const auto& [id, a] : s_.areas)
    if (std::set<int>(a.keypoints.begin(), a.keypoints.end()) == wanted &&
        a.keypoints.size() == kps.size())
      return id;
  std::vector<int> lines;
  for (std::size_t k = 0; k < kps.size(); ++k)
    lines.push_back(line_between(kps[k], kps[(k + 1) % kps.size()], path));
  return area_from_lines(lines);
}

std::vector<int> SolidBuilder::lines_of_areas(const std::vector<int>& areas) const {
  std::set<int> out;
  for (int a : areas)
    for (int sl : s_.areas.at(a).lines) out.insert(std::abs(sl));
  return {out.begin(), out.end()};
}

int SolidBuilder::volume_from_areas(const std::vector<int>& areas) {
  if (areas.size() < 4)
    fail(fmt::format("a volume needs at least 4 areas, {} given", areas.size()));
  std::map<int, int> uses;
  for (int a : areas) {
    const auto it = s_.areas.find(a);
    if (it == s_.areas.end()) fail(fmt::format("area {} is not defined", a));
    for (int sl : it->second.lines) ++uses[std::abs(sl)];
  }
  for (const auto& [line, n] : uses)
    if (n != 2)
      fail(fmt::format("the areas do not enclose a volume: line {} bounds {} of them (must be 2)",
                       line, n));
  const int id = lowest_free(s_.volumes, s_.numstr.volu);
  Volume v;
  v.id = id;
  v.areas = areas;
  s_.volumes[id] = v;
  return id;
}

int SolidBuilder::volume_from_keypoints(const std::vector<int>& kps, const CoordinateSystem& path,
                                        FaceOrder order) {
  if (kps.size() != 8) fail(fmt::format("a volume needs 8 keypoints I..P, {} given", kps.size()));
  // The areas, outward: the hexahedron's face table is bottom, top, then the sides (BLOCK's
  // numbering); V numbers them as the brick element's faces 1-6, the top last (MAPDL's VM
  // decks mesh the top of V volumes as areas 6, 11 and 16 of three volumes in a row).
  auto faces = cell_topology(VtkCell::Hexahedron).faces;
  if (order == FaceOrder::BrickFaces)
    std::rotate(faces.begin() + 1, faces.begin() + 2, faces.end());
  std::vector<int> areas;
  for (const auto& f : faces) {
    std::vector<int> loop;
    for (int c : f) {
      const int k = kps[static_cast<std::size_t>(c)];
      if (std::find(loop.begin(), loop.end(), k) == loop.end()) loop.push_back(k);
    }
    if (loop.size() < 3) continue;  // a collapsed face (prism, pyramid)
    areas.push_back(area_from_keypoints(loop, path));
  }
  return volume_from_areas(areas);
}

int SolidBuilder::rectangle(const CoordinateSystem& wp, double x1, double x2, double y1,
                            double y2) {
  if (x1 > x2) std::swap(x1, x2);
  if (y1 > y2) std::swap(y1, y2);
  if (x2 - x1 <= 0.0 || y2 - y1 <= 0.0)
    fail(fmt::format("zero-area rectangle ({} x {})", x2 - x1, y2 - y1));
  const CoordinateSystem flat{CsysKind::Cartesian, wp.origin, wp.axes};
  std::vector<int> k;
  for (const auto& [x, y] : {std::pair{x1, y1}, {x2, y1}, {x2, y2}, {x1, y2}})
    k.push_back(keypoint(0, flat.to_global(Vec3(x, y, 0.0))));
  return area_from_keypoints(k, flat);
}

int SolidBuilder::block(const CoordinateSystem& wp, double x1, double x2, double y1, double y2,
                        double z1, double z2) {
  if (x1 > x2) std::swap(x1, x2);
  if (y1 > y2) std::swap(y1, y2);
  if (z1 > z2) std::swap(z1, z2);
  if (x2 - x1 <= 0.0 || y2 - y1 <= 0.0 || z2 - z1 <= 0.0)
    fail(fmt::format("zero-volume block ({} x {} x {})", x2 - x1, y2 - y1, z2 - z1));
  const CoordinateSystem flat{CsysKind::Cartesian, wp.origin, wp.axes};
  std::vector<int> k;
  for (double z : {z1, z2})
    for (const auto& [x, y] : {std::pair{x1, y1}, {x2, y1}, {x2, y2}, {x1, y2}})
      k.push_back(keypoint(0, flat.to_global(Vec3(x, y, z))));
  return volume_from_keypoints(k, flat, FaceOrder::Primitive);
}

int SolidBuilder::cylinder(const CoordinateSystem& wp, double xc, double yc, double r1, double r2,
                           double theta1, double theta2, double z1, double z2) {
  double r_in = std::min(std::fabs(r1), std::fabs(r2));
  const double r_out = std::max(std::fabs(r1), std::fabs(r2));
  if (r_out <= 0.0) fail("zero radius");
  if (std::fabs(r_in - r_out) <= 1e-12 * r_out) r_in = 0.0;  // equal radii: solid
  if (theta1 > theta2) std::swap(theta1, theta2);
  double sweep = theta2 - theta1;
  if (sweep <= 0.0 || sweep > 360.0 + 1e-9)
    fail(fmt::format("bad angle range {} to {} (0 < THETA2 − THETA1 ≤ 360)", theta1, theta2));
  const bool full = sweep >= 360.0 - 1e-9;
  if (full && r_in > 0.0)
    fail(
        "a full 360° annulus or hollow cylinder has two boundary loops, which this mesher "
        "cannot map; build it from sectors (THETA1, THETA2)");
  if (z1 > z2) std::swap(z1, z2);
  const bool volume = z2 > z1;
  const CoordinateSystem flat{CsysKind::Cartesian, wp.origin, wp.axes};
  const Vec3 axis = wp.axes.col(2);
  auto point = [&](double r, double t, double z) {
    const double a = t * M_PI / 180.0;
    return flat.to_global(Vec3(xc + r * std::cos(a), yc + r * std::sin(a), z));
  };
  auto centre = [&](double z) { return flat.to_global(Vec3(xc, yc, z)); };
  // Keypoints of one level (counter-clockwise about the WP Z axis) and its boundary loop.
  struct Level {
    std::vector<int> kps;
    std::vector<int> lines;
  };
  auto make_level = [&](double z) {
    Level lv;
    if (full) {
      for (int q = 0; q < 4; ++q) lv.kps.push_back(keypoint(0, point(r_out, theta1 + 90.0 * q, z)));
      for (int q = 0; q < 4; ++q)
        lv.lines.push_back(arc(lv.kps[static_cast<std::size_t>(q)],
                               lv.kps[static_cast<std::size_t>((q + 1) % 4)], centre(z), axis,
                               90.0));
    } else if (r_in == 0.0) {
      const int c = keypoint(0, centre(z));
      const int a = keypoint(0, point(r_out, theta1, z));
      const int b = keypoint(0, point(r_out, theta2, z));
      lv.kps = {c, a, b};
      lv.lines = {line(c, a, flat), arc(a, b, centre(z), axis, sweep), line(b, c, flat)};
    } else {
      const int a = keypoint(0, point(r_in, theta1, z));
      const int b = keypoint(0, point(r_out, theta1, z));
      const int c = keypoint(0, point(r_out, theta2, z));
      const int d = keypoint(0, point(r_in, theta2, z));
      // Lines numbered outer arc, radial edge at THETA2, inner arc, radial edge at THETA1, so
      // that the radial edges are the even lines as in MAPDL (vmr029-t9-185 sizes lines 2 and 4
      // of PCIRC,RM+T/2,RM-T/2,... to one division through the thickness).
      const int outer = arc(b, c, centre(z), axis, sweep);
      const int end_edge = line(c, d, flat);
      const int inner = arc(a, d, centre(z), axis, sweep);
      const int start_edge = line(a, b, flat);
      lv.kps = {b, c, d, a};
      lv.lines = {outer, end_edge, -inner, start_edge};
    }
    return lv;
  };
  const Level bottom = make_level(z1);
  const int bottom_area = area_from_lines(bottom.lines);
  if (!volume) return bottom_area;
  const Level top = make_level(z2);
  const int top_area = area_from_lines(top.lines);
  std::vector<int> areas{bottom_area, top_area};
  std::vector<int> verticals;
  for (std::size_t k = 0; k < bottom.kps.size(); ++k)
    verticals.push_back(line(bottom.kps[k], top.kps[k], flat));
  const std::size_t n = bottom.kps.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1) % n;
    areas.push_back(
        area_from_lines({bottom.lines[k], verticals[k1], -top.lines[k], -verticals[k]}));
  }
  return volume_from_areas(areas);
}

}  // namespace impactfe::geometry
