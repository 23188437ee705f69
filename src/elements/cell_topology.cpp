#include "elements/cell_topology.h"

#include <algorithm>

#include "core/errors.h"

namespace impactfe {

namespace {

CellTopology hexahedron() {
  CellTopology t;
  t.cell = VtkCell::Hexahedron;
  t.dimension = 3;
  t.corner_nodes = 8;
  // The one table of the hexahedron's faces (see CellTopology::faces).
  t.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int k = 0; k < 4; ++k) t.edges.push_back({k, (k + 1) % 4});          // bottom ring
  for (int k = 0; k < 4; ++k) t.edges.push_back({4 + k, 4 + (k + 1) % 4});  // top ring
  for (int k = 0; k < 4; ++k) t.edges.push_back({k, k + 4});                // I-M ... L-P
  t.linear = VtkCell::Hexahedron;
  return t;
}

/// The 20-node hexahedron: the hexahedron's corners, faces and edges, one midside node per edge
/// (Q R S T on the bottom ring, U V W X on the top ring, Y Z A B on I-M ... L-P).
CellTopology quadratic_hexahedron() {
  CellTopology t = hexahedron();
  t.cell = VtkCell::QuadraticHexahedron;
  t.midside_nodes = 12;
  return t;
}

/// The tetrahedron I J K L, L on the positive side of I J K (counter-clockwise seen from L).
/// Faces outward in MAPDL's numbering of SOLID187 / SOLID285 (J-I-K, I-J-L, J-K-L, K-I-L);
/// edges I-J J-K K-I I-L J-L K-L, the order of the 10-node tetrahedron's midside nodes.
CellTopology tetrahedron() {
  CellTopology t;
  t.cell = VtkCell::Tetra;
  t.dimension = 3;
  t.corner_nodes = 4;
  t.faces = {{1, 0, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  t.edges = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  t.linear = VtkCell::Tetra;
  return t;
}

CellTopology quadratic_tetrahedron() {
  CellTopology t = tetrahedron();
  t.cell = VtkCell::QuadraticTetra;
  t.midside_nodes = 6;
  return t;
}

/// A triangle or quadrilateral: its one face is itself, its edges its sides.
CellTopology polygon(VtkCell cell, int corners) {
  CellTopology t;
  t.cell = cell;
  t.dimension = 2;
  t.corner_nodes = corners;
  t.linear = cell;
  t.faces.emplace_back();
  for (int k = 0; k < corners; ++k) {
    t.faces.front().push_back(k);
    t.edges.push_back({k, (k + 1) % corners});
  }
  return t;
}

/// The 8-node quadrilateral and the 6-node triangle: a midside node on each side, in side order.
CellTopology quadratic_polygon(VtkCell cell, VtkCell linear, int corners) {
  CellTopology t = polygon(linear, corners);
  t.cell = cell;
  t.midside_nodes = corners;
  return t;
}

CellTopology simple(VtkCell cell, int dimension, int corners) {
  CellTopology t;
  t.cell = cell;
  t.dimension = dimension;
  t.corner_nodes = corners;
  t.linear = cell;
  if (dimension == 1) t.edges.push_back({0, 1});
  return t;
}

/// The 3-node line: ends I J and the midside node K on its one edge.
CellTopology quadratic_edge() {
  CellTopology t = simple(VtkCell::Line, 1, 2);
  t.cell = VtkCell::QuadraticEdge;
  t.midside_nodes = 1;
  return t;
}

std::vector<int> unique_in_order(const std::vector<int>& nodes) {
  std::vector<int> out;
  for (int n : nodes)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

}  // namespace

const CellTopology& cell_topology(VtkCell cell) {
  // Function-local statics: element registrations read them during static initialisation.
  static const CellTopology vertex = simple(VtkCell::Vertex, 0, 1);
  static const CellTopology poly_vertex = simple(VtkCell::PolyVertex, -1, 0);
  static const CellTopology line = simple(VtkCell::Line, 1, 2);
  static const CellTopology line3 = quadratic_edge();
  static const CellTopology triangle = polygon(VtkCell::Triangle, 3);
  static const CellTopology quad = polygon(VtkCell::Quad, 4);
  static const CellTopology triangle6 =
      quadratic_polygon(VtkCell::QuadraticTriangle, VtkCell::Triangle, 3);
  static const CellTopology quad8 = quadratic_polygon(VtkCell::QuadraticQuad, VtkCell::Quad, 4);
  static const CellTopology hex = hexahedron();
  static const CellTopology hex20 = quadratic_hexahedron();
  static const CellTopology tet = tetrahedron();
  static const CellTopology tet10 = quadratic_tetrahedron();
  switch (cell) {
    case VtkCell::Vertex:
      return vertex;
    case VtkCell::PolyVertex:
      return poly_vertex;
    case VtkCell::Line:
      return line;
    case VtkCell::QuadraticEdge:
      return line3;
    case VtkCell::Triangle:
      return triangle;
    case VtkCell::Quad:
      return quad;
    case VtkCell::QuadraticTriangle:
      return triangle6;
    case VtkCell::QuadraticQuad:
      return quad8;
    case VtkCell::Hexahedron:
      return hex;
    case VtkCell::QuadraticHexahedron:
      return hex20;
    case VtkCell::Tetra:
      return tet;
    case VtkCell::QuadraticTetra:
      return tet10;
  }
  IMPACTFE_CHECK(false, "unknown cell type");
  return poly_vertex;
}

int CellTopology::midside_of(int a, int b) const {
  if (midside_nodes == 0) return -1;
  for (std::size_t k = 0; k < edges.size(); ++k)
    if ((edges[k][0] == a && edges[k][1] == b) || (edges[k][0] == b && edges[k][1] == a))
      return corner_nodes + static_cast<int>(k);
  return -1;
}

std::vector<int> face_with_midsides(const CellTopology& cell, const std::vector<int>& corners) {
  std::vector<int> out = corners;
  if (cell.midside_nodes == 0) return out;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const int m = cell.midside_of(corners[k], corners[(k + 1) % corners.size()]);
    IMPACTFE_CHECK(m >= 0, "a face side that is not an edge of its cell");
    out.push_back(m);
  }
  return out;
}

std::vector<int> face_nodes(const CellTopology& cell, int face, const std::vector<int>& nodes) {
  std::vector<int> out;
  for (int p : cell.faces.at(static_cast<std::size_t>(face)))
    out.push_back(nodes.at(static_cast<std::size_t>(p)));
  return out;
}

std::vector<CellPiece> cell_pieces(VtkCell cell, const std::vector<int>& nodes) {
  std::vector<CellPiece> out;
  const CellTopology& t = cell_topology(cell);
  if (nodes.empty()) return out;
  switch (t.dimension) {
    case 1:
      // A quadratic line is drawn through its midside node: I-K, K-J.
      if (t.midside_nodes > 0 && nodes.size() >= 3 && nodes[2] != nodes[0] &&
          nodes[2] != nodes[1]) {
        out.push_back({CellPiece::Kind::Line, {nodes[0], nodes[2]}});
        out.push_back({CellPiece::Kind::Line, {nodes[2], nodes[1]}});
      } else if (nodes.size() >= 2 && nodes[0] != nodes[1]) {
        out.push_back({CellPiece::Kind::Line, {nodes[0], nodes[1]}});
      }
      break;
    case 2: {
      if (nodes.size() == 1) {
        out.push_back({CellPiece::Kind::Point, nodes});
        break;
      }
      // A quadratic polygon is drawn through its midside nodes: corner, midside, corner, ...
      std::vector<int> around = nodes;
      if (t.midside_nodes > 0 && static_cast<int>(nodes.size()) >= t.n_nodes()) {
        around.clear();
        for (int k = 0; k < t.corner_nodes; ++k) {
          around.push_back(nodes[static_cast<std::size_t>(k)]);
          around.push_back(nodes[static_cast<std::size_t>(t.corner_nodes + k)]);
        }
      }
      auto ring = unique_in_order(around);
      if (ring.size() >= 3)
        out.push_back({CellPiece::Kind::Polygon, std::move(ring)});
      else if (ring.size() == 2)
        out.push_back({CellPiece::Kind::Line, std::move(ring)});
      break;
    }
    case 3:
      if (static_cast<int>(nodes.size()) < t.corner_nodes) break;
      for (std::size_t f = 0; f < t.faces.size(); ++f) {
        auto face = unique_in_order(face_nodes(t, static_cast<int>(f), nodes));
        if (face.size() >= 3) out.push_back({CellPiece::Kind::Polygon, std::move(face)});
      }
      break;
    default:  // points: a vertex, a poly-vertex's nodes
      for (int n : unique_in_order(nodes)) out.push_back({CellPiece::Kind::Point, {n}});
  }
  return out;
}

}  // namespace impactfe
