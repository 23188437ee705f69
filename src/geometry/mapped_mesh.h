#pragma once
/// Node positions of mapped meshes (APDL_MODELING §4.5) by discrete transfinite interpolation
/// (Coons patches; Gordon & Hall 1973, Thompson et al. "Numerical Grid Generation" ch. 8): the
/// interior of a 4-sided patch or a 6-faced block from the nodes already placed on its
/// boundary, and the triangular lattice of a 3-sided patch. Pure functions of positions.
#include <vector>

#include "core/coordinate_system.h"

namespace impactfe::geometry {

/// Normalised cumulative chord lengths (0 … 1) of a chain of points.
std::vector<double> chain_fractions(const std::vector<Vec3>& points);

/// Quadrilateral patch: (n1 + 1) x (n2 + 1) positions, index i + j (n1 + 1), from its sides
/// bottom (j = 0, i = 0..n1), right (i = n1, j = 0..n2), top (j = n2, i = 0..n1) and left
/// (i = 0, j = 0..n2). Boundary entries are the given points, interior ones the Coons blend
/// P = (1−v) B(i) + v T(i) + (1−u) L(j) + u R(j) − bilinear(corners), with u, v the mean chord
/// fractions of the opposite sides.
std::vector<Vec3> coons_quad(const std::vector<Vec3>& bottom, const std::vector<Vec3>& right,
                             const std::vector<Vec3>& top, const std::vector<Vec3>& left);

/// Triangular lattice of a 3-sided patch with n divisions per side, indexed like AreaGrid
/// (rows j = 0..n of n − j + 1 points; corner 0 at (0, 0), corner 1 at (n, 0), corner 2 at
/// (0, n)). Sides: s0 corner 0 → 1, s1 corner 1 → 2, s2 corner 2 → 0 (n + 1 points each).
/// Interior points average the three interpolations along the lattice lines parallel to the
/// sides (exact for straight, uniformly divided sides).
std::vector<Vec3> triangle_lattice(const std::vector<Vec3>& s0, const std::vector<Vec3>& s1,
                                   const std::vector<Vec3>& s2);

/// Block: fills the interior of `grid` ((n1 + 1)(n2 + 1)(n3 + 1) positions, index
/// i + (n1 + 1)(j + (n2 + 1) k)) whose six faces are already set, by trivariate transfinite
/// interpolation (Boolean sum of the three linear projectors).
void transfinite_block(std::vector<Vec3>& grid, int n1, int n2, int n3);

/// Signed volume of the hexahedron I..P (sum of six tetrahedra): positive for the MAPDL node
/// order (I J K L counter-clockwise seen from M N O P).
double hexahedron_volume(const std::vector<Vec3>& corners);

}  // namespace impactfe::geometry
