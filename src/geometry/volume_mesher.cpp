// Mapped hexahedral meshing of 6-faced volumes (VMESH, VSWEEP; APDL_MODELING §4.5): the volume
// must have the topology of a cube (6 four-sided areas, 12 lines, 8 keypoints). Its lines fall
// into three classes of four parallel edges that must have equal divisions; the faces are meshed
// (or their existing meshes reused) and the interior filled by trivariate transfinite
// interpolation.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <set>

#include "core/log.h"
#include "elements/element_registry.h"
#include "geometry/mapped_mesh.h"
#include "geometry/mesher.h"

namespace impactfe::geometry {

/// A brick-like volume being meshed: its areas and lines, its corners, its divisions and the
/// (n1 + 1)(n2 + 1)(n3 + 1) lattice of node ids and positions.
struct Mesher::VolumeBlock {
  /// Volume parametrisation: corner (a, b, c) ∈ {0,1}³ → keypoint.
  using Corners = std::array<std::array<std::array<int, 2>, 2>, 2>;
  int id = 0;
  std::vector<int> areas;
  std::vector<int> lines;
  std::vector<int> bottom;   // keypoints of the bottom (source) area, in its order
  std::array<int, 4> top{};  // the keypoint above each bottom one
  Corners q{};
  int n1 = 0, n2 = 0, n3 = 0;
  std::vector<int> ids;
  std::vector<Vec3> xyz;
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i + (n1 + 1) * (j + (n2 + 1) * k));
  }
};

void Mesher::mesh_volume(int id, int source, int target) {
  Volume& volume = solid_.volumes.at(id);
  const Attributes attr = resolve(volume.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  if (d.topology().dimension != 3)
    fail(
        fmt::format("element type {} ({}) is not a solid element: VMESH needs a brick element "
                    "(SOLID185; set TYPE or VATT)",
                    attr.type, d.name));
  if (!volume.elements.empty()) {
    Log::info("{}:{}: {}: volume {} is already meshed", where_.file, where_.line, where_.command,
              id);
    return;
  }
  // Tetrahedra (a tetrahedral type, or MSHAPE,1,3D for a brick type: MAPDL's degenerate
  // bricks) come from the free mesher; VSWEEP makes bricks only.
  const bool tet_type = d.topology().linear == VtkCell::Tetra;
  if (tet_type || solid_.mesh.shape_3d == 1) {
    if (source != 0 || target != 0 || where_.command == "VSWEEP")
      fail(
          fmt::format("VSWEEP makes bricks: element type {} ({}) or MSHAPE,1,3D asks for "
                      "tetrahedra (use VMESH)",
                      attr.type, d.name));
    if (solid_.mesh.key == 1)
      fail("MSHKEY,1 asks for a mapped mesh, and tetrahedra are meshed free (MSHKEY,0)");
    mesh_volume_free(id);
    return;
  }
  if (d.topology().linear != VtkCell::Hexahedron)
    fail(fmt::format("element type {} ({}) is neither a hexahedron nor a tetrahedron", attr.type,
                     d.name));
  MeshControls& m = solid_.mesh;
  if (m.key == 0 && !m.free_warning_given) {
    Log::warn(
        "{}:{}: {}: MSHKEY,0 (free meshing): impactfe meshes brick-like volumes with the "
        "mapped mesher; MAPDL's free mesher may produce a different (tetrahedral) mesh",
        where_.file, where_.line, where_.command);
    m.free_warning_given = true;
  }
  VolumeBlock block = volume_block(id, source, target);
  volume_block_nodes(block);
  copy_face_grids(block);
  transfinite_block(block.xyz, block.n1, block.n2, block.n3);
  std::vector<int> interior;
  for (int k = 1; k < block.n3; ++k)
    for (int j = 1; j < block.n2; ++j)
      for (int i = 1; i < block.n1; ++i)
        interior.push_back(block.ids[block.index(i, j, k)] =
                               add_node(block.xyz[block.index(i, j, k)]));
  std::vector<int> elements = volume_block_elements(block, attr);
  for (int n : take_created_midside_nodes()) interior.push_back(n);
  Volume& stored = solid_.volumes.at(id);
  stored.interior_nodes = std::move(interior);
  stored.elements = std::move(elements);
}

Mesher::VolumeBlock Mesher::volume_block(int id, int source, int target) {
  VolumeBlock block;
  block.id = id;
  block.areas = solid_.volumes.at(id).areas;
  const std::vector<int>& areas = block.areas;
  if (areas.size() != 6)
    fail(
        fmt::format("volume {} has {} areas: mapped hexahedral meshing needs 6 (a brick-like "
                    "volume); free tetrahedral meshing is not supported",
                    id, areas.size()));
  std::set<int> lines_set;
  for (int a : areas) {
    const Area& area = solid_.areas.at(a);
    if (free_grid(area.grid))
      fail(
          fmt::format("volume {} cannot be mapped: its area {} has a free (Gmsh) mesh; mesh "
                      "it with tetrahedra (MSHAPE,1,3D) or ACLEAR the area first",
                      id, a));
    if (area.lines.size() != 4)
      fail(fmt::format("volume {} is not mappable: its area {} has {} sides (all six need 4)", id,
                       a, area.lines.size()));
    for (int sl : area.lines) lines_set.insert(std::abs(sl));
  }
  block.lines.assign(lines_set.begin(), lines_set.end());
  const std::vector<int>& lines = block.lines;
  if (lines.size() != 12)
    fail(fmt::format("volume {} is not mappable: it has {} lines (a brick-like volume has 12)", id,
                     lines.size()));
  if (source != 0 && std::find(areas.begin(), areas.end(), source) == areas.end())
    fail(fmt::format("source area {} is not an area of volume {}", source, id));
  const int bottom = source != 0 ? source : areas.front();
  block.bottom = solid_.areas.at(bottom).keypoints;
  const std::vector<int>& b = block.bottom;
  std::vector<int> bottom_lines;
  for (int sl : solid_.areas.at(bottom).lines) bottom_lines.push_back(std::abs(sl));
  // Each bottom corner has exactly one edge leaving the bottom face: it leads to the top corner.
  std::array<int, 4>& t = block.top;
  for (std::size_t k = 0; k < 4; ++k) {
    int found = 0;
    for (int l : lines) {
      if (std::find(bottom_lines.begin(), bottom_lines.end(), l) != bottom_lines.end()) continue;
      const Line& line = solid_.lines.at(l);
      if (line.kp1 != b[k] && line.kp2 != b[k]) continue;
      if (found != 0)
        fail(fmt::format("volume {} is not mappable: keypoint {} has more than three edges", id,
                         b[k]));
      found = line.kp1 == b[k] ? line.kp2 : line.kp1;
    }
    if (found == 0)
      fail(fmt::format("volume {} is not mappable: keypoint {} has no edge off area {}", id, b[k],
                       bottom));
    t[k] = found;
  }
  const std::set<int> top_set(t.begin(), t.end());
  int top = 0;
  for (int a : areas) {
    const auto& kps = solid_.areas.at(a).keypoints;
    if (std::set<int>(kps.begin(), kps.end()) == top_set) top = a;
  }
  if (top == 0 || top_set.size() != 4)
    fail(fmt::format("volume {} is not mappable: no area opposite to area {}", id, bottom));
  if (target != 0 && target != top)
    fail(
        fmt::format("VSWEEP: target area {} is not opposite to the source area {} in volume {} "
                    "(area {} is)",
                    target, bottom, id, top));
  VolumeBlock::Corners& q = block.q;
  q[0][0][0] = b[0], q[1][0][0] = b[1], q[1][1][0] = b[2], q[0][1][0] = b[3];
  q[0][0][1] = t[0], q[1][0][1] = t[1], q[1][1][1] = t[2], q[0][1][1] = t[3];
  return block;
}

void Mesher::volume_block_nodes(VolumeBlock& block) {
  const int id = block.id;
  const VolumeBlock::Corners& q = block.q;
  auto edge = [&](int a0, int b0, int c0, int a1, int b1, int c1) {
    const int l = line_joining(block.lines, q[a0][b0][c0], q[a1][b1][c1]);
    if (l == 0)
      fail(fmt::format("volume {} is not mappable: keypoints {} and {} are not joined by a line",
                       id, q[a0][b0][c0], q[a1][b1][c1]));
    return std::abs(l);
  };
  // The three classes of parallel edges (i, j, k directions).
  const std::vector<std::vector<int>> classes = {{edge(0, 0, 0, 1, 0, 0), edge(0, 1, 0, 1, 1, 0),
                                                  edge(0, 0, 1, 1, 0, 1), edge(0, 1, 1, 1, 1, 1)},
                                                 {edge(0, 0, 0, 0, 1, 0), edge(1, 0, 0, 1, 1, 0),
                                                  edge(0, 0, 1, 0, 1, 1), edge(1, 0, 1, 1, 1, 1)},
                                                 {edge(0, 0, 0, 0, 0, 1), edge(1, 0, 0, 1, 0, 1),
                                                  edge(1, 1, 0, 1, 1, 1), edge(0, 1, 0, 0, 1, 1)}};
  plan_divisions(classes, fmt::format("volume {}", id), std::nullopt);

  // Nodes: lines (each with its end keypoints first, as area_nodes), areas (ascending numbers),
  // then the interior.
  std::vector<int> sorted_lines(block.lines.begin(), block.lines.end());
  std::sort(sorted_lines.begin(), sorted_lines.end());
  for (int l : sorted_lines) line_nodes(l);
  std::vector<int> sorted_areas = block.areas;
  std::sort(sorted_areas.begin(), sorted_areas.end());
  for (int a : sorted_areas) area_nodes(a, false);

  auto divisions = [&](int l) { return static_cast<int>(solid_.lines.at(l).nodes.size()) - 1; };
  block.n1 = divisions(classes[0][0]), block.n2 = divisions(classes[1][0]),
  block.n3 = divisions(classes[2][0]);
  check_new_nodes(
      (block.n1 - 1.0) * (block.n2 - 1.0) * (block.n3 - 1.0),
      fmt::format("volume {} ({} x {} x {} divisions)", id, block.n1, block.n2, block.n3));
  const std::size_t size =
      static_cast<std::size_t>((block.n1 + 1) * (block.n2 + 1) * (block.n3 + 1));
  block.ids.assign(size, 0);
  block.xyz.assign(size, Vec3::Zero());
}

void Mesher::copy_face_grids(VolumeBlock& block) {
  // Copy each face grid into the block: the face fixes one parameter; its area grid axes are
  // matched to the block axes through the corner keypoints.
  const int id = block.id;
  const VolumeBlock::Corners& q = block.q;
  const int n[3] = {block.n1, block.n2, block.n3};
  for (int a : block.areas) {
    const Area& area = solid_.areas.at(a);
    const std::set<int> face(area.keypoints.begin(), area.keypoints.end());
    int axis = -1, level = 0;
    for (int ax = 0; ax < 3 && axis < 0; ++ax)
      for (int lv = 0; lv < 2 && axis < 0; ++lv) {
        std::set<int> corners;
        for (int u = 0; u < 2; ++u)
          for (int v = 0; v < 2; ++v) {
            std::array<int, 3> c{};
            c[static_cast<std::size_t>(ax)] = lv;
            c[static_cast<std::size_t>((ax + 1) % 3)] = u;
            c[static_cast<std::size_t>((ax + 2) % 3)] = v;
            corners.insert(q[c[0]][c[1]][c[2]]);
          }
        if (corners == face) axis = ax, level = lv;
      }
    if (axis < 0)
      fail(fmt::format("volume {}: area {} is not a face of its brick topology", id, a));
    const int ax_u = (axis + 1) % 3, ax_v = (axis + 2) % 3;
    const int nu = n[ax_u], nv = n[ax_v];
    auto corner_kp = [&](int u, int v) {
      std::array<int, 3> c{};
      c[static_cast<std::size_t>(axis)] = level;
      c[static_cast<std::size_t>(ax_u)] = u;
      c[static_cast<std::size_t>(ax_v)] = v;
      return q[c[0]][c[1]][c[2]];
    };
    int u0 = -1, v0 = -1;
    for (int u = 0; u < 2; ++u)
      for (int v = 0; v < 2; ++v)
        if (corner_kp(u, v) == area.keypoints[0]) u0 = u, v0 = v;
    const bool i_along_u = corner_kp(1 - u0, v0) == area.keypoints[1];
    const AreaGrid& g = area.grid;
    if ((i_along_u ? g.n1 != nu || g.n2 != nv : g.n1 != nv || g.n2 != nu))
      fail(
          fmt::format("volume {}: the mesh of area {} does not match the volume divisions", id, a));
    for (int v = 0; v <= nv; ++v)
      for (int u = 0; u <= nu; ++u) {
        const int pu = u0 == 0 ? u : nu - u, pv = v0 == 0 ? v : nv - v;
        const int node = i_along_u ? g.at(pu, pv) : g.at(pv, pu);
        std::array<int, 3> c{};
        c[static_cast<std::size_t>(axis)] = level * n[axis];
        c[static_cast<std::size_t>(ax_u)] = u;
        c[static_cast<std::size_t>(ax_v)] = v;
        block.ids[block.index(c[0], c[1], c[2])] = node;
        block.xyz[block.index(c[0], c[1], c[2])] = model_.nodes.at(node).x;
      }
  }
}

std::vector<int> Mesher::volume_block_elements(const VolumeBlock& block, const Attributes& attr) {
  const int n1 = block.n1, n2 = block.n2, n3 = block.n3;
  const auto& xyz = block.xyz;
  const auto& ids = block.ids;
  // Orientation: I J K L counter-clockwise seen from M N O P (positive volume).
  const std::vector<Vec3> box = {xyz[block.index(0, 0, 0)],    xyz[block.index(n1, 0, 0)],
                                 xyz[block.index(n1, n2, 0)],  xyz[block.index(0, n2, 0)],
                                 xyz[block.index(0, 0, n3)],   xyz[block.index(n1, 0, n3)],
                                 xyz[block.index(n1, n2, n3)], xyz[block.index(0, n2, n3)]};
  const bool mirrored = hexahedron_volume(box) < 0.0;
  std::vector<int> elements;
  for (int k = 0; k < n3; ++k)
    for (int j = 0; j < n2; ++j)
      for (int i = 0; i < n1; ++i) {
        std::vector<int> nodes;
        for (int c : {k, k + 1}) {
          std::array<int, 4> quad = {ids[block.index(i, j, c)], ids[block.index(i + 1, j, c)],
                                     ids[block.index(i + 1, j + 1, c)],
                                     ids[block.index(i, j + 1, c)]};
          if (mirrored) std::swap(quad[1], quad[3]);
          nodes.insert(nodes.end(), quad.begin(), quad.end());
        }
        elements.push_back(add_element(attr, nodes));
      }
  return elements;
}

}  // namespace impactfe::geometry
