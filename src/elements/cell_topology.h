#pragma once
/// Topology of the element cells (element_registry.h VtkCell) that pictures and selections need:
/// the drawable pieces of a cell and its boundary facets, with collapsed corners (a triangle
/// given as a quadrilateral with K = L, a wedge as a brick) removed.
#include <vector>

#include "elements/element_registry.h"

namespace impactfe {

/// A drawable piece of a cell: its node ids in order.
struct CellPiece {
  enum class Kind { Point, Line, Polygon } kind = Kind::Point;
  std::vector<int> nodes;
};

/// Points of a vertex or poly-vertex (superelement), the line of a line, the polygon of a
/// triangle or quadrilateral, the six faces of a hexahedron (outward for a positive volume).
std::vector<CellPiece> cell_pieces(VtkCell cell, const std::vector<int>& nodes);

/// Boundary facets, as sorted node-id lists: the end nodes of a line, the edges of a triangle or
/// quadrilateral, the faces of a hexahedron, the nodes of a (poly-)vertex. A facet that two
/// elements share is interior to them (NSEL,,EXT).
std::vector<std::vector<int>> cell_facets(VtkCell cell, const std::vector<int>& nodes);

}  // namespace impactfe
