#pragma once
/// The reference cells of the elements (element_registry.h VtkCell): their corner nodes, faces
/// and edges, once for the whole program. The element registry names the cell of each element
/// type; the surface loads of the solid elements, the solid builder (V), the mesher, the VTK
/// export, the POST1 pictures and the report's 3-D view read the cell from here.
#include <array>
#include <vector>

namespace impactfe {

/// VTK cell types (VTK's vtkCellType.h numbering) of the full node list of an element.
enum class VtkCell : int {
  Vertex = 1,
  PolyVertex = 2,
  Line = 3,
  QuadraticEdge = 21,  // 3 nodes: ends I J, then the midside node K
  Triangle = 5,
  Quad = 9,
  QuadraticTriangle = 22,  // 6 nodes: corners I J K, then midsides of I-J J-K K-I
  QuadraticQuad = 23,      // 8 nodes: corners I J K L, then midsides of I-J J-K K-L L-I
  Tetra = 10,
  Hexahedron = 12,
  QuadraticTetra = 24,       // 10 nodes: corners I J K L, then midsides of I-J J-K K-I I-L J-L K-L
  QuadraticHexahedron = 25,  // 20 nodes: corners I..P, midsides of the edges in `edges` order
};

/// The topology of one reference cell. Node positions are 0-based in the element's node list,
/// corners first (I, J, K, L, M, N, O, P), then midside nodes.
struct CellTopology {
  VtkCell cell = VtkCell::PolyVertex;
  /// 0 point, 1 line, 2 area, 3 volume; -1 for a poly-vertex (a superelement's master nodes).
  int dimension = -1;
  /// Corner nodes: the first `corner_nodes` nodes of the element's list (0: all of them, a
  /// poly-vertex). Nodes beyond them that are not midside nodes are not part of the cell (a
  /// beam's orientation node K).
  int corner_nodes = 0;
  /// Midside nodes after the corners: midside node k (position corner_nodes + k) lies on
  /// edges[k] (VTK's quadratic cells and MAPDL's SOLID186/SOLID187 order alike).
  int midside_nodes = 0;
  /// The cell of the corners alone (a quadratic cell's linear counterpart; itself otherwise).
  VtkCell linear = VtkCell::PolyVertex;
  /// Faces of a volume cell as corner positions, outward by the right-hand rule for a positive
  /// volume (I J K L counter-clockwise seen from M N O P): the bottom I-L-K-J, the top
  /// M-N-O-P, then the sides I-J-N-M, J-K-O-N, K-L-P-O, L-I-M-P, each read from its bottom
  /// corner. The order in which V creates a volume's areas and pictures draw its faces. An
  /// area cell has one face, itself; lines and points have none.
  std::vector<std::vector<int>> faces;
  /// Edges as pairs of corner positions.
  std::vector<std::array<int, 2>> edges;

  int n_nodes() const { return corner_nodes + midside_nodes; }
  /// Position of the midside node on the edge between corner positions a and b (-1: none).
  int midside_of(int a, int b) const;
};

/// The topology of a cell type.
const CellTopology& cell_topology(VtkCell cell);

/// A drawable piece of a cell: its node ids in order.
struct CellPiece {
  enum class Kind { Point, Line, Polygon } kind = Kind::Point;
  std::vector<int> nodes;
};

/// The drawable pieces of an element with the given node ids, collapsed corners (a triangle
/// given as a quadrilateral with K = L, a wedge as a brick) removed: the points of a vertex or
/// poly-vertex, the line between the two corners of a line (none when they coincide), the
/// polygon of a triangle or quadrilateral (a line when it collapses to two nodes, a point when
/// one node is given: a target's pilot), the faces of a hexahedron (outward, in the cell's face
/// order; faces collapsed below three nodes left out).
std::vector<CellPiece> cell_pieces(VtkCell cell, const std::vector<int>& nodes);

/// The nodes of `face` (0-based in the cell's face list) of an element, in the face's order.
std::vector<int> face_nodes(const CellTopology& cell, int face, const std::vector<int>& nodes);

/// A face given by its corner positions (in order) followed by the positions of the midside
/// nodes of its sides c0-c1, c1-c2, ..., cn-c0 (8-node and 6-node faces of quadratic cells;
/// the corners alone for a linear cell): the face-node order of the surface loads.
std::vector<int> face_with_midsides(const CellTopology& cell, const std::vector<int>& corners);

}  // namespace impactfe
