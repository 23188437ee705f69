#pragma once
/// Shape functions and quadrature rules of the quadratic solids (SOLID186, SOLID187) and of
/// their faces: the 20-node serendipity hexahedron and the 10-node tetrahedron in natural
/// coordinates, the 8-node serendipity quadrilateral and the 6-node triangle (Zienkiewicz &
/// Taylor vol. 1, §6.5 and §6.6), Gauss-Legendre products on the cube and Stroud's conical
/// products (collapsed Gauss rules) on the simplices. Node orders are those of the cells in
/// elements/cell_topology.h: corners, then one midside node per edge in the cell's edge order.
#include <Eigen/Core>

#include <vector>

namespace impactfe {

enum class QuadraticShape { Hex20, Tet10 };

/// Natural coordinates: the cube [-1, 1]³ for Hex20 (corners I..P as for the 8-node brick); the
/// unit tetrahedron for Tet10 (volume coordinates L_I = 1 − ξ − η − ζ, L_J = ξ, L_K = η, L_L = ζ).
int quadratic_shape_nodes(QuadraticShape shape);

/// Shape functions n (one per node) and their natural derivatives dn (row i = ∂/∂ξ_i) at xi.
void quadratic_shape(QuadraticShape shape, const Eigen::Vector3d& xi, Eigen::VectorXd& n,
                     Eigen::Matrix3Xd& dn);

/// Natural coordinates of the element's nodes.
std::vector<Eigen::Vector3d> quadratic_shape_nodes_xi(QuadraticShape shape);
/// The natural centre (ξ = 0 of the cube, L = 1/4 of the tetrahedron).
Eigen::Vector3d quadratic_shape_centre(QuadraticShape shape);

struct QuadraturePoint {
  Eigen::Vector3d xi;  // natural coordinates (the third is 0 on a face)
  double weight = 0.0;
};

/// n x n x n Gauss-Legendre product on [-1, 1]³ (exact to degree 2n − 1 in each coordinate).
std::vector<QuadraturePoint> gauss_cube(int n);
/// n x n Gauss-Legendre product on [-1, 1]².
std::vector<QuadraturePoint> gauss_square(int n);
/// The 4-point rule of the unit tetrahedron (exact to degree 2; Zienkiewicz & Taylor Table 6.4).
std::vector<QuadraturePoint> tetrahedron_4_point();
/// Stroud's conical product on the unit tetrahedron: n-point Gauss-Legendre rules on [0, 1]
/// through ξ = u, η = v(1 − u), ζ = w(1 − u)(1 − v), |J| = (1 − u)²(1 − v); exact to degree
/// 2n − 3 (n = 4: degree 5, enough for the consistent mass of the 10-node tetrahedron).
std::vector<QuadraturePoint> collapsed_tetrahedron(int n);
/// The same collapse on the unit triangle: ξ = u, η = v(1 − u), |J| = 1 − u (degree 2n − 2).
std::vector<QuadraturePoint> collapsed_triangle(int n);

/// A face of a quadratic solid: the 8-node quadrilateral (corners (−1,−1) (1,−1) (1,1) (−1,1),
/// then the midsides of sides 0-1 1-2 2-3 3-0) or the 6-node triangle (corners (0,0) (1,0) (0,1),
/// midsides of 0-1 1-2 2-0).
/// Shape functions, their derivatives (rows ∂/∂ξ, ∂/∂η) and the linear (triangle) or bilinear
/// (quadrilateral) corner functions that interpolate a pressure from its corner values.
void quadratic_face_shape(int face_nodes, const Eigen::Vector3d& xi, Eigen::VectorXd& n,
                          Eigen::Matrix<double, 2, Eigen::Dynamic>& dn, Eigen::VectorXd& corner);

}  // namespace impactfe
