#pragma once
/// Geometry of the trilinear hexahedron for one-point (uniform-strain) integration, Flanagan &
/// Belytschko, "A uniform strain hexahedron and quadrilateral with orthogonal hourglass
/// control", IJNME 17 (1981) 679–706: the volume derivatives b_iI = ∂V/∂x_iI (their eq. (79),
/// closed form), so that the mean strain-rate operator is B_iI = b_iI / V and V = Σ_I x_I b_xI
/// exactly for any shape of the element; the lumped (row-sum) mass shares ∫N_I dV; and the
/// characteristic length V / A_max (the largest face) of the stable time step.
/// Corner order I..P: IJKL the bottom face counter-clockwise, MNOP above it (ANSYS and FB).
namespace impactfe::hexahedron {

/// b = ∂V/∂x of the 8 corners, each direction (bx, by, bz).
void volume_derivatives(const double* x, const double* y, const double* z, double* bx, double* by,
                        double* bz);
/// Volume from the derivatives: Σ_I x_I b_xI.
inline double volume(const double* x, const double* bx) {
  double v = 0.0;
  for (int a = 0; a < 8; ++a) v += x[a] * bx[a];
  return v;
}
/// ∫ N_I dV of the 8 corners (2x2x2 Gauss: exact for the trilinear element).
void row_sum_volumes(const double* x, const double* y, const double* z, double* share);
/// ∫ x xᵀ dV about the origin (row-major 3 × 3), by 3x3x3 Gauss quadrature: exact for a
/// parallelepiped, whose det J is constant (the rotational inertia of rigid bodies).
void second_moment(const double* x, const double* y, const double* z, double* s);
/// The volume by 2x2x2 Gauss quadrature of det J (exact; an independent check of volume()).
double gauss_volume(const double* x, const double* y, const double* z);
/// The largest of the six face areas (each face's area as half the cross product of its
/// diagonals, exact for a plane face).
double largest_face_area(const double* x, const double* y, const double* z);

}  // namespace impactfe::hexahedron
