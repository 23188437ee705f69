#pragma once
/// Where a point lies in an element: the inverse of the isoparametric map x(ξ) = Σ N_i(ξ) x_i,
/// solved by Newton's method from the cell's centre (Zienkiewicz & Taylor vol. 1, §6.2: the
/// shape functions N_i then interpolate any nodal field at the point). Used by the path
/// operations of POST1 (PDEF), which interpolate nodal results at points along a line.
///
/// Cells: the linear and quadratic triangle, quadrilateral, tetrahedron and hexahedron of
/// elements/cell_topology.h (wedges and pyramids arrive as hexahedra with collapsed corners, and
/// are located as such). An area cell in 3-D space (a shell) takes the point closest to it,
/// within `tolerance` times the cell's size of its surface.
#include <optional>
#include <vector>

#include "core/coordinate_system.h"
#include "elements/cell_topology.h"

namespace impactfe::geometry {

/// Whether a cell of this kind can locate points (area and volume cells).
bool locatable_cell(VtkCell cell);

/// The shape-function values (one per node of `x`, in the cell's node order) at the point `p`
/// when it lies inside the cell or on its boundary, within `tolerance` relative to the cell's
/// natural size (0.001 = a thousandth of the element); nullopt when it lies outside or the map
/// does not converge (an inverted cell). `x` holds the cell's n_nodes() node positions.
std::optional<std::vector<double>> shape_values_at(VtkCell cell, const std::vector<Vec3>& x,
                                                   const Vec3& p, double tolerance = 1e-6);

}  // namespace impactfe::geometry
