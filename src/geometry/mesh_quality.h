#pragma once
/// Shape measures of meshed elements, reported after each meshing command and by `impactfe mesh`
/// [A: impactfe's own measures and limits; MAPDL's SHPP tests differ in their definitions]:
///
/// * **edge ratio**: the longest corner-to-corner edge over the shortest (1 for a regular cell);
/// * **scaled Jacobian** (Knupp, "Achieving finite element mesh quality via optimization of the
///   Jacobian matrix norm", IJNME 2000): at each corner, the determinant of the unit edge vectors
///   that leave it (a volume cell: its three edges in right-handed order; an area cell: the sine
///   of the corner angle about the cell's normal), divided by that of the regular cell (regular
///   tetrahedron 1/√2, equilateral wedge and triangle √3/2, pyramid with equilateral sides 1/√2,
///   cube and square 1); the minimum over the corners. 1 for the regular cell, 0 for a corner
///   collapsed flat, negative for an inverted corner (a mesh an element would refuse, or solve
///   wrongly);
/// * **Jacobian ratio** of a quadratic cell (SOLID186, SOLID187 without collapsed corners, and the
///   8-node and 6-node area cells): the largest determinant of the isoparametric map over its
///   nodes and centre divided by the smallest; infinite when one is not positive (a midside node
///   placed so that the map folds over). Linear cells have none (their corner Jacobians are the
///   scaled Jacobian's).
///
/// Collapsed corners (a wedge, pyramid or tetrahedron given as a brick, a triangle as a
/// quadrilateral with K = L) are measured as the cell they collapse to.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "core/model.h"
#include "elements/cell_topology.h"

namespace impactfe::geometry {

struct ElementShape {
  double edge_ratio = 1.0;
  double scaled_jacobian = 1.0;
  /// Quadratic cells only (nullopt otherwise); +inf when a determinant is not positive.
  std::optional<double> jacobian_ratio;
};

/// The shape of an element of cell `cell` with node positions `x` and node numbers `nodes` (the
/// numbers tell collapsed corners apart: two corners with the same node). nullopt for cells
/// without a shape (points, lines, poly-vertices) and for corners collapsed below an area or a
/// volume.
std::optional<ElementShape> element_shape(const CellTopology& cell, const std::vector<int>& nodes,
                                          const std::vector<Vec3>& x);

/// Limits of the report's warnings [A]: an element past one of them is counted and named.
inline constexpr double kEdgeRatioWarning = 20.0;
inline constexpr double kScaledJacobianWarning = 0.2;
inline constexpr double kJacobianRatioWarning = 30.0;

struct MeshQuality {
  int measured = 0;  // elements with a shape
  double worst_edge_ratio = 1.0;
  int worst_edge_ratio_element = 0;
  double worst_scaled_jacobian = 1.0;
  int worst_scaled_jacobian_element = 0;
  double worst_jacobian_ratio = 1.0;  // over the quadratic cells
  int worst_jacobian_ratio_element = 0;
  int inverted = 0;           // scaled Jacobian ≤ 0 or a Jacobian ratio of +inf
  int first_inverted = 0;     // the lowest inverted element number
  int past_limits = 0;        // past one of the warning limits (inverted ones included)
  int first_past_limits = 0;  // the lowest such element number
};

/// The shapes of `elements` of `model` (their types' cells).
MeshQuality mesh_quality(const Model& model, const std::vector<int>& elements);

/// One line: "N elements: edge ratio ≤ a (element i), scaled Jacobian ≥ b (element j)[, Jacobian
/// ratio ≤ c (element k)]"; empty when nothing was measured.
std::string describe(const MeshQuality& q);

}  // namespace impactfe::geometry
