// Free meshing through Gmsh (APDL_MODELING §4, MSHAPE, MSHKEY,0): areas that the mapped mesher
// cannot mesh get triangles or recombined quadrilaterals, volumes get tetrahedra.
//
// The program's own line meshing runs first (LESIZE, KESIZE, ESIZE, DESIZE decide the
// divisions, as for mapped meshing), so a free mesh shares its boundary nodes with every
// neighbour. Areas: a Gmsh built-in ("geo") model of the areas and their lines, each line a
// transfinite curve with the line's node count, is meshed in 2-D; the curve nodes are mapped
// back onto the line's nodes by their order along the curve. Volumes: the triangles of the
// volume's area meshes (new ones made as above, existing ones reused) bound a discrete Gmsh
// volume that Gmsh's Delaunay mesher fills; the mesh sizes inside grow from the boundary's.
// Gmsh runs with one thread and fixed options, so the same deck gives the same mesh.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "core/log.h"
#include "elements/element_registry.h"
#include "geometry/gmsh_session.h"
#include "geometry/line_geometry.h"
#include "geometry/mesher.h"

namespace impactfe::geometry {

namespace {

/// Centre of the circle through a, b and c (nullopt when they are collinear).
std::optional<Vec3> circle_centre(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  const Vec3 w = u.cross(v);
  const double w2 = w.squaredNorm();
  if (w2 <= 1e-24 * u.squaredNorm() * v.squaredNorm()) return std::nullopt;
  return a + (v.squaredNorm() * w.cross(u) + u.squaredNorm() * v.cross(w)) / (2.0 * w2);
}

/// Unit normal of a closed polygon by Newell's formula (zero vector when degenerate).
Vec3 newell_normal(const std::vector<Vec3>& p) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) n += p[i].cross(p[(i + 1) % p.size()]);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : n;
}

/// Line `l` as a curve of the Gmsh built-in model between its keypoints' points: straight, a
/// circular arc under 180 degrees, or a spline through samples; `extra_point` numbers the points
/// added (arc centres, spline samples).
void add_geo_curve(const Line& line, int l, int& extra_point) {
  namespace geo = gmsh::model::geo;
  const Vec3 a = line_point(line, 0.0), b = line_point(line, 1.0);
  const double len = std::max(line_length(line), 1e-30);
  // Straight: every sample on the chord at its own parameter.
  double off_chord = 0.0;
  for (int k = 1; k < 8; ++k) {
    const double s = k / 8.0;
    off_chord = std::max(off_chord, (line_point(line, s) - (a + s * (b - a))).norm());
  }
  if (off_chord <= 1e-9 * len) {
    geo::addLine(line.kp1, line.kp2, l);
    return;
  }
  // A circular arc under 180 degrees: Gmsh's exact circle; other paths: a spline through
  // samples of the line.
  const Vec3 m = line_point(line, 0.5);
  const auto c = circle_centre(a, m, b);
  bool arc = c.has_value();
  if (arc) {
    const double r = (a - *c).norm();
    for (int k = 1; k < 8 && arc; ++k)
      arc = std::abs((line_point(line, k / 8.0) - *c).norm() - r) <= 1e-9 * std::max(r, len);
    const double sweep = std::acos(std::clamp((a - *c).dot(b - *c) / (r * r), -1.0, 1.0));
    arc = arc && sweep < 0.99 * M_PI && (m - *c).dot((a + b) / 2.0 - *c) > 0.0;
  }
  if (arc) {
    geo::addPoint(c->x(), c->y(), c->z(), 0.0, ++extra_point);
    geo::addCircleArc(line.kp1, extra_point, line.kp2, l);
  } else {
    std::vector<int> pts{line.kp1};
    for (int k = 1; k < 32; ++k) {
      const Vec3 p = line_point(line, k / 32.0);
      pts.push_back(geo::addPoint(p.x(), p.y(), p.z(), 0.0, ++extra_point));
    }
    pts.push_back(line.kp2);
    geo::addSpline(pts, l);
  }
}

}  // namespace

/// Unit normal of an area by its loop direction (Newell's formula over samples of its lines;
/// a hole's loop runs the other way round and takes away its own part).
Vec3 Mesher::area_normal(int id) const {
  std::vector<Vec3> p;
  Vec3 n = Vec3::Zero();
  for (int sl : solid_.areas.at(id).lines) {
    const Line& line = solid_.lines.at(std::abs(sl));
    for (int k = 0; k < 8; ++k) {
      const Vec3 x = line_point(line, sl > 0 ? k / 8.0 : 1.0 - k / 8.0);
      const Vec3 y = line_point(line, sl > 0 ? (k + 1) / 8.0 : 1.0 - (k + 1) / 8.0);
      n += x.cross(y);
    }
  }
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : n;
}

bool Mesher::area_needs_free_mesh(int id) const {
  const Area& area = solid_.areas.at(id);
  if (solid_.mesh.key == 1) return false;  // MSHKEY,1: mapped only (the mapped mesher refuses)
  const std::size_t sides = area.lines.size();
  if (sides != 3 && sides != 4) return true;
  if (sides == 3 && solid_.mesh.shape_2d != 1) return true;
  // A 3- or 4-sided area is meshed mapped unless the divisions given to its lines (LESIZE)
  // cannot map: opposite sides of a quadrilateral, or the three sides of a triangle pattern,
  // must have as many. Free meshing (MSHKEY,0) then meshes it as MAPDL does.
  const auto given = [&](std::size_t k) {
    return fixed_divisions(solid_.lines.at(std::abs(area.lines[k])));
  };
  const auto differ = [&](std::size_t a, std::size_t b) {
    return given(a) > 0 && given(b) > 0 && given(a) != given(b);
  };
  if (sides == 4) return differ(0, 2) || differ(1, 3);
  return differ(0, 1) || differ(1, 2) || differ(0, 2);
}

std::map<int, std::vector<std::array<int, 4>>> Mesher::free_area_nodes(
    const std::vector<int>& areas, bool quads) {
  std::vector<int> todo;
  for (int a : areas)
    if (solid_.areas.at(a).grid.empty()) todo.push_back(a);
  if (todo.empty()) return {};
  std::sort(todo.begin(), todo.end());
  // Lines first, in line order (§4.6 numbering), with the program's division rules.
  std::set<int> lines, kps;
  for (int a : todo)
    for (int sl : solid_.areas.at(a).lines) {
      lines.insert(std::abs(sl));
      kps.insert(solid_.lines.at(std::abs(sl)).kp1);
      kps.insert(solid_.lines.at(std::abs(sl)).kp2);
    }
  for (int k : kps) keypoint_node(k);
  for (int a : todo)
    for (int sl : solid_.areas.at(a).lines) line_nodes(std::abs(sl), solid_.areas.at(a).size);

  const std::string what =
      todo.size() == 1 ? fmt::format("area {}", todo[0]) : fmt::format("{} areas", todo.size());
  // The node count is known only once Gmsh has meshed, and Gmsh's quadrilateral recombination
  // grows faster than the mesh (78,543 nodes in 43 s): a count far past the limits is refused
  // before, from the areas' size and their boundary divisions.
  double estimate = 0.0;
  for (int a : todo) estimate += estimated_free_nodes(a);
  check_new_nodes(estimate, what);
  GmshSession session("areas");
  namespace geo = gmsh::model::geo;
  std::map<int, std::vector<std::array<int, 4>>> faces_of;
  std::map<int, std::vector<int>> interior_of;
  with_gmsh(where_, "mesh " + what, [&] {
    int extra_point = 0;
    for (const auto& [id, k] : solid_.keypoints) extra_point = std::max(extra_point, id);
    double longest = 0.0;
    for (int l : lines) longest = std::max(longest, line_length(solid_.lines.at(l)));
    for (int k : kps) {
      const Vec3& x = solid_.keypoints.at(k).x;
      geo::addPoint(x.x(), x.y(), x.z(), 0.0, k);
    }
    for (int l : lines) add_geo_curve(solid_.lines.at(l), l, extra_point);
    int loop_tag = 0;
    for (int a : todo) add_free_surface(a, longest, loop_tag);
    geo::synchronize();
    for (int l : lines) {
      const Line& line = solid_.lines.at(l);
      const int n = static_cast<int>(line.nodes.size()) - 1;
      // A graded line (SPACE = last/first > 0): the same geometric ratio per division.
      const double q = line.space > 0.0 && n > 1 ? std::pow(line.space, 1.0 / (n - 1)) : 1.0;
      gmsh::model::mesh::setTransfiniteCurve(l, n + 1, "Progression", q);
    }
    if (quads) {
      // Frontal-Delaunay triangles recombined by Blossom matching (Gmsh 4.8's quadrilateral
      // algorithm 8 crashes in its cross-field background mesh on some planar areas).
      gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
      for (int a : todo) gmsh::model::mesh::setRecombine(2, a);
    }
    gmsh::model::mesh::generate(2);
    read_free_area_mesh(todo, lines, kps, faces_of, interior_of);
  });
  for (int a : todo) {
    Area& area = solid_.areas.at(a);
    AreaGrid grid;
    std::set<int> seen;
    for (int sl : area.lines)
      for (int n : solid_.lines.at(std::abs(sl)).nodes)
        if (seen.insert(n).second) grid.nodes.push_back(n);
    for (int n : interior_of[a]) grid.nodes.push_back(n);
    area.grid = std::move(grid);
    area.interior_nodes = std::move(interior_of[a]);
  }
  return faces_of;
}

double Mesher::estimated_free_nodes(int a) const {
  // The area of the polygon through the keypoints of its boundary (Newell; the chords of arcs)
  // over that of two equilateral triangles of the boundary's mean division h: a triangulation
  // has about twice as many triangles as nodes.
  const Area& area = solid_.areas.at(a);
  Vec3 twice_area = Vec3::Zero();
  double perimeter = 0.0;
  double divisions = 0.0;
  for (int sl : area.lines) {
    const Line& line = solid_.lines.at(std::abs(sl));
    const Vec3& from = solid_.keypoints.at(sl > 0 ? line.kp1 : line.kp2).x;
    const Vec3& to = solid_.keypoints.at(sl > 0 ? line.kp2 : line.kp1).x;
    twice_area += from.cross(to);
    perimeter += line_length(line);
    divisions += static_cast<double>(line.nodes.size()) - 1.0;
  }
  if (!(perimeter > 0.0) || !(divisions > 0.0)) return 0.0;
  const double h = perimeter / divisions;
  return 0.5 * twice_area.norm() / (0.5 * std::sqrt(3.0) * h * h);
}

void Mesher::add_free_surface(int a, double longest, int& loop_tag) const {
  namespace geo = gmsh::model::geo;
  const Area& area = solid_.areas.at(a);
  // The boundary's closed loops (an area read from a CAD file may have holes): the one
  // with the largest extent is the outer one, Gmsh's first.
  std::vector<std::vector<int>> loops;
  std::vector<int> current;
  int start = 0;
  for (int sl : area.lines) {
    const Line& line = solid_.lines.at(std::abs(sl));
    const int from = sl > 0 ? line.kp1 : line.kp2, to = sl > 0 ? line.kp2 : line.kp1;
    if (current.empty()) start = from;
    current.push_back(sl);
    if (to == start) loops.push_back(std::exchange(current, {}));
  }
  if (!current.empty()) fail(fmt::format("area {}: its lines do not close into loops", a));
  auto extent = [&](const std::vector<int>& loop) {
    Eigen::AlignedBox3d box;
    for (int sl : loop) {
      const Line& line = solid_.lines.at(std::abs(sl));
      box.extend(solid_.keypoints.at(line.kp1).x);
      box.extend(solid_.keypoints.at(line.kp2).x);
    }
    return box.diagonal().norm();
  };
  std::stable_sort(loops.begin(), loops.end(),
                   [&](const auto& p, const auto& q) { return extent(p) > extent(q); });
  std::vector<int> wires;
  for (const auto& loop : loops) wires.push_back(geo::addCurveLoop(loop, ++loop_tag));
  // Planar (every boundary sample within 1e-9 of the longest line from the loop's plane):
  // a plane surface; otherwise a 3- or 4-sided area is the transfinite (Coons) patch of
  // its boundary, as the mapped mesher takes it.
  std::vector<Vec3> boundary;
  for (int sl : loops.front()) {
    const Line& line = solid_.lines.at(std::abs(sl));
    for (int k = 0; k < 8; ++k)
      boundary.push_back(line_point(line, sl > 0 ? k / 8.0 : 1.0 - k / 8.0));
  }
  const Vec3 n = newell_normal(boundary);
  double off_plane = 0.0;
  for (int sl : area.lines)
    for (int k = 0; k <= 8; ++k)
      off_plane = std::max(
          off_plane,
          std::abs(n.dot(line_point(solid_.lines.at(std::abs(sl)), k / 8.0) - boundary[0])));
  if (off_plane <= 1e-9 * std::max(longest, 1e-30)) {
    geo::addPlaneSurface(wires, a);
  } else if (loops.size() == 1 && area.lines.size() <= 4) {
    geo::addSurfaceFilling(wires, a);
  } else {
    fail(
        fmt::format("area {} is not planar and has {} sides: free meshing takes planar "
                    "areas or curved ones with 3 or 4 sides",
                    a, area.lines.size()));
  }
}

void Mesher::read_free_area_mesh(const std::vector<int>& todo, const std::set<int>& lines,
                                 const std::set<int>& kps,
                                 std::map<int, std::vector<std::array<int, 4>>>& faces_of,
                                 std::map<int, std::vector<int>>& interior_of) {
  std::map<std::size_t, int> node_of;  // Gmsh node tag -> program node
  std::vector<std::size_t> tags;
  std::vector<double> xyz, par;
  for (int k : kps) {
    gmsh::model::mesh::getNodes(tags, xyz, par, 0, k, false, false);
    for (std::size_t t : tags) node_of[t] = keypoint_node(k);
  }
  for (int l : lines) {
    gmsh::model::mesh::getNodes(tags, xyz, par, 1, l, false, true);
    const std::vector<int>& nodes = solid_.lines.at(l).nodes;
    if (tags.size() + 2 != nodes.size())
      fail(fmt::format("Gmsh put {} nodes inside line {}, which has {}", tags.size(), l,
                       nodes.size() - 2));
    std::vector<std::size_t> order(tags.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t i, std::size_t j) { return par[i] < par[j]; });
    for (std::size_t i = 0; i < order.size(); ++i) node_of[tags[order[i]]] = nodes[i + 1];
  }
  for (int a : todo) {
    gmsh::model::mesh::getNodes(tags, xyz, par, 2, a, false, false);
    for (std::size_t i = 0; i < tags.size(); ++i) {
      const int id = add_node(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
      node_of[tags[i]] = id;
      interior_of[a].push_back(id);
    }
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    gmsh::model::mesh::getElements(types, etags, enodes, 2, a);
    const Vec3 n = area_normal(a);
    for (std::size_t t = 0; t < types.size(); ++t) {
      const std::size_t nn = types[t] == 2 ? 3 : types[t] == 3 ? 4 : 0;
      if (nn == 0) fail(fmt::format("Gmsh made elements of type {} on area {}", types[t], a));
      for (std::size_t e = 0; e * nn < enodes[t].size(); ++e) {
        std::array<int, 4> f{};
        for (std::size_t k = 0; k < nn; ++k) f[k] = node_of.at(enodes[t][e * nn + k]);
        // Oriented by the area's loop (the element normal of MAPDL's area meshes).
        const Vec3 x0 = model_.nodes.at(f[0]).x, x1 = model_.nodes.at(f[1]).x,
                   x2 = model_.nodes.at(f[2]).x;
        if (n.squaredNorm() > 0.0 && (x1 - x0).cross(x2 - x0).dot(n) < 0.0) {
          if (nn == 3)
            std::swap(f[1], f[2]);
          else
            std::swap(f[1], f[3]);
        }
        faces_of[a].push_back(f);
      }
    }
  }
}

std::vector<std::array<int, 4>> Mesher::existing_area_faces(int id) const {
  const Area& area = solid_.areas.at(id);
  std::vector<std::array<int, 4>> faces;
  auto corners = [&](const ElementRecord& e) {
    // Distinct corner nodes in order (a degenerate brick's I J K K L L L L gives I J K L).
    std::vector<int> c;
    const CellTopology& cell = descriptor(e.type).topology();
    for (int k = 0; k < cell.corner_nodes && k < static_cast<int>(e.nodes.size()); ++k)
      if (std::find(c.begin(), c.end(), e.nodes[static_cast<std::size_t>(k)]) == c.end())
        c.push_back(e.nodes[static_cast<std::size_t>(k)]);
    return c;
  };
  if (!area.elements.empty()) {
    for (int e : area.elements) {
      const std::vector<int> c = corners(model_.elements.at(e));
      if (c.size() == 3)
        faces.push_back({c[0], c[1], c[2], 0});
      else if (c.size() == 4)
        faces.push_back({c[0], c[1], c[2], c[3]});
    }
    return faces;
  }
  // Faces of the volumes' elements with every corner on the area: tetrahedra (4 distinct
  // corners, faces opposite each corner) and bricks (their quadrilateral faces).
  const std::set<int> on(area.grid.nodes.begin(), area.grid.nodes.end());
  std::set<std::set<int>> seen;
  for (const auto& [vid, v] : solid_.volumes) {
    if (std::find(v.areas.begin(), v.areas.end(), id) == v.areas.end()) continue;
    for (int e : v.elements) {
      const ElementRecord& rec = model_.elements.at(e);
      const std::vector<int> c = corners(rec);
      std::vector<std::vector<int>> candidates;
      if (c.size() == 4 && descriptor(rec.type).topology().linear != VtkCell::Quad &&
          (descriptor(rec.type).topology().linear == VtkCell::Tetra ||
           rec.nodes[2] == rec.nodes[3]))
        candidates = {
            {c[0], c[2], c[1]}, {c[0], c[1], c[3]}, {c[1], c[2], c[3]}, {c[0], c[3], c[2]}};
      else
        for (const auto& f : descriptor(rec.type).topology().faces) {
          std::vector<int> q;
          for (int k : f) q.push_back(rec.nodes[static_cast<std::size_t>(k)]);
          candidates.push_back(q);
        }
      for (const auto& f : candidates) {
        if (!std::all_of(f.begin(), f.end(), [&](int n) { return on.count(n) != 0; })) continue;
        if (!seen.insert(std::set<int>(f.begin(), f.end())).second) continue;
        faces.push_back({f[0], f[1], f[2], f.size() > 3 ? f[3] : 0});
      }
    }
  }
  return faces;
}

void Mesher::mesh_area_free(int id) {
  Area& area = solid_.areas.at(id);
  const Attributes attr = resolve(area.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  const bool triangles = solid_.mesh.shape_2d == 1;
  if (!area.grid.empty())
    fail(
        fmt::format("area {} already has a mesh (of a volume): AMESH of it is not supported; "
                    "mesh the area before the volume",
                    id));
  auto faces = free_area_nodes({id}, !triangles);
  if (d.topology().midside_nodes > 0)
    for (int line : solid_.areas.at(id).lines) index_line_edges(std::abs(line));
  std::vector<int> elements;
  for (const auto& f : faces[id]) {
    if (f[3] == 0) {
      if (d.least_nodes() > 3 && d.topology().midside_nodes == 0 &&
          d.topology().linear != VtkCell::Quad)
        fail(fmt::format("element type {} ({}) has no triangular form", attr.type, d.name));
      elements.push_back(add_element(attr, {f[0], f[1], f[2]}));
    } else {
      elements.push_back(add_element(attr, {f[0], f[1], f[2], f[3]}));
    }
  }
  Area& meshed = solid_.areas.at(id);
  meshed.elements = std::move(elements);
  for (int n : take_created_midside_nodes()) meshed.interior_nodes.push_back(n);
}

std::vector<std::array<int, 3>> Mesher::volume_boundary_triangles(int id) {
  const Volume& volume = solid_.volumes.at(id);
  // The boundary: every area meshed with triangles (new ones by Gmsh, existing ones reused).
  std::vector<int> meshed_before;
  for (int a : volume.areas)
    if (!solid_.areas.at(a).grid.empty()) meshed_before.push_back(a);
  auto faces = free_area_nodes(volume.areas, false);
  for (int a : meshed_before) {
    faces[a] = existing_area_faces(a);
    if (faces[a].empty())
      fail(
          fmt::format("area {} of volume {} has nodes but no elements on it to take its "
                      "triangles from (ACLEAR it first)",
                      a, id));
  }
  std::vector<std::array<int, 3>> triangles;
  for (int a : volume.areas)
    for (const auto& f : faces[a]) {
      if (f[3] != 0)
        fail(
            fmt::format("area {} of volume {} has a quadrilateral mesh: tetrahedra need "
                        "triangles on it (ACLEAR it first, or mesh it with MSHAPE,1,2D)",
                        a, id));
      triangles.push_back({f[0], f[1], f[2]});
    }
  return triangles;
}

void Mesher::fill_with_tetrahedra(int id, const std::vector<std::array<int, 3>>& triangles,
                                  std::vector<int>& interior,
                                  std::vector<std::array<int, 4>>& tets) {
  std::set<int> boundary_nodes;
  for (const auto& t : triangles) boundary_nodes.insert(t.begin(), t.end());
  GmshSession session("volume");
  with_gmsh(where_, fmt::format("mesh volume {}", id), [&] {
    gmsh::model::addDiscreteEntity(2, 1);
    std::vector<std::size_t> tags;
    std::vector<double> xyz;
    for (int n : boundary_nodes) {
      tags.push_back(static_cast<std::size_t>(n));
      const Vec3& x = model_.nodes.at(n).x;
      xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
    }
    gmsh::model::mesh::addNodes(2, 1, tags, xyz);
    std::vector<std::size_t> etags, enodes;
    for (const auto& t : triangles) {
      etags.push_back(etags.size() + 1);
      for (int n : t) enodes.push_back(static_cast<std::size_t>(n));
    }
    gmsh::model::mesh::addElementsByType(1, 2, etags, enodes);
    gmsh::model::geo::addSurfaceLoop({1}, 1);
    gmsh::model::geo::addVolume({1}, 1);
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::generate(3);

    std::vector<double> par;
    gmsh::model::mesh::getNodes(tags, xyz, par, 3, 1, false, false);
    check_new_nodes(static_cast<double>(tags.size()), fmt::format("volume {}", id));
    // The boundary nodes by their (unchanged) positions: Gmsh may renumber the node tags it
    // was given when it meshes.
    std::map<std::array<double, 3>, int> at_position;
    for (int n : boundary_nodes) {
      const Vec3& x = model_.nodes.at(n).x;
      at_position[{x.x(), x.y(), x.z()}] = n;
    }
    std::map<std::size_t, int> node_of;
    {
      std::vector<std::size_t> btags;
      std::vector<double> bxyz;
      gmsh::model::mesh::getNodes(btags, bxyz, par, 2, 1, false, false);
      for (std::size_t i = 0; i < btags.size(); ++i) {
        const auto it = at_position.find({bxyz[3 * i], bxyz[3 * i + 1], bxyz[3 * i + 2]});
        if (it == at_position.end())
          fail(
              fmt::format("Gmsh moved or added a node on the boundary of volume {} (its area "
                          "meshes do not close it up, or their triangles could not be "
                          "recovered)",
                          id));
        node_of[btags[i]] = it->second;
      }
    }
    {
      std::vector<std::size_t> all;
      std::vector<double> all_xyz;
      gmsh::model::mesh::getNodes(all, all_xyz, par, -1, -1, false, false);
      if (all.size() != node_of.size() + tags.size())
        fail(
            fmt::format("Gmsh put {} nodes on the boundary of volume {} (its area meshes do "
                        "not close it up, or their triangles could not be recovered)",
                        all.size() - node_of.size() - tags.size(), id));
    }
    for (std::size_t i = 0; i < tags.size(); ++i) {
      const int n = add_node(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
      node_of[tags[i]] = n;
      interior.push_back(n);
    }
    std::vector<std::size_t> tet_tags, tet_nodes;
    gmsh::model::mesh::getElementsByType(4, tet_tags, tet_nodes, 1);
    if (tet_tags.empty()) fail(fmt::format("Gmsh made no tetrahedra in volume {}", id));
    for (std::size_t e = 0; e < tet_tags.size(); ++e) {
      std::array<int, 4> t{};
      for (std::size_t k = 0; k < 4; ++k) t[k] = node_of.at(tet_nodes[4 * e + k]);
      // Positive volume: (J − I) × (K − I) · (L − I) > 0, I J K counter-clockwise seen from L.
      const Vec3 xi = model_.nodes.at(t[0]).x;
      const double v = (model_.nodes.at(t[1]).x - xi)
                           .cross(model_.nodes.at(t[2]).x - xi)
                           .dot(model_.nodes.at(t[3]).x - xi);
      if (v < 0.0) std::swap(t[1], t[2]);
      tets.push_back(t);
    }
  });
}

void Mesher::mesh_volume_free(int id) {
  const Volume& volume = solid_.volumes.at(id);
  const Attributes attr = resolve(volume.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  const VtkCell cell = d.topology().linear;
  if (cell != VtkCell::Tetra && cell != VtkCell::Hexahedron)
    fail(fmt::format("element type {} ({}) cannot be a tetrahedron", attr.type, d.name));
  const std::vector<std::array<int, 3>> triangles = volume_boundary_triangles(id);
  std::vector<int> interior;
  std::vector<std::array<int, 4>> tets;
  fill_with_tetrahedra(id, triangles, interior, tets);
  if (d.topology().midside_nodes > 0)
    for (int a : volume.areas)
      for (int line : solid_.areas.at(a).lines) index_line_edges(std::abs(line));
  std::vector<int> elements;
  for (const auto& t : tets) {
    if (cell == VtkCell::Tetra)
      elements.push_back(add_element(attr, {t[0], t[1], t[2], t[3]}));
    else  // MAPDL's degenerate brick: I J K K L L L L
      elements.push_back(add_element(attr, {t[0], t[1], t[2], t[2], t[3], t[3], t[3], t[3]}));
  }
  for (int n : take_created_midside_nodes()) interior.push_back(n);
  Volume& stored = solid_.volumes.at(id);
  stored.interior_nodes = std::move(interior);
  stored.elements = std::move(elements);
}

}  // namespace impactfe::geometry
