#include "elements/cell_topology.h"

#include <algorithm>
#include <array>

namespace impactfe {

namespace {

/// ANSYS brick node order I J K L M N O P; faces outward for a positive volume.
constexpr std::array<std::array<int, 4>, 6> kHexFaces = {
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};

std::vector<int> unique_in_order(const std::vector<int>& nodes) {
  std::vector<int> out;
  for (int n : nodes)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

std::vector<CellPiece> cell_pieces(VtkCell cell, const std::vector<int>& nodes) {
  std::vector<CellPiece> out;
  if (nodes.empty()) return out;
  switch (cell) {
    case VtkCell::Line:
      if (nodes.front() != nodes.back())
        out.push_back({CellPiece::Kind::Line, {nodes.front(), nodes.back()}});
      break;
    case VtkCell::Triangle:
    case VtkCell::Quad: {
      auto ring = unique_in_order(nodes);
      if (ring.size() >= 3) out.push_back({CellPiece::Kind::Polygon, std::move(ring)});
      break;
    }
    case VtkCell::Hexahedron:
      if (nodes.size() < 8) break;
      for (const auto& f : kHexFaces) {
        auto face = unique_in_order({nodes[f[0]], nodes[f[1]], nodes[f[2]], nodes[f[3]]});
        if (face.size() >= 3) out.push_back({CellPiece::Kind::Polygon, std::move(face)});
      }
      break;
    default:
      for (int n : unique_in_order(nodes)) out.push_back({CellPiece::Kind::Point, {n}});
  }
  return out;
}

std::vector<std::vector<int>> cell_facets(VtkCell cell, const std::vector<int>& nodes) {
  std::vector<std::vector<int>> out;
  for (const auto& piece : cell_pieces(cell, nodes)) {
    if (cell == VtkCell::Line) {
      out.push_back({piece.nodes.front()});
      out.push_back({piece.nodes.back()});
    } else if (cell == VtkCell::Triangle || cell == VtkCell::Quad) {
      const auto& ring = piece.nodes;
      for (std::size_t k = 0; k < ring.size(); ++k)
        out.push_back(sorted({ring[k], ring[(k + 1) % ring.size()]}));
    } else {
      out.push_back(sorted(piece.nodes));
    }
  }
  return out;
}

}  // namespace impactfe
