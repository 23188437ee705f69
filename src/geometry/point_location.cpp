#include "geometry/point_location.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

#include "elements/quadratic_shapes.h"

namespace impactfe::geometry {

namespace {

/// Natural dimension of a locatable cell (2 area, 3 volume; 0 otherwise).
int natural_dimension(VtkCell cell) {
  switch (cell) {
    case VtkCell::Triangle:
    case VtkCell::Quad:
    case VtkCell::QuadraticTriangle:
    case VtkCell::QuadraticQuad:
      return 2;
    case VtkCell::Tetra:
    case VtkCell::Hexahedron:
    case VtkCell::QuadraticTetra:
    case VtkCell::QuadraticHexahedron:
      return 3;
    default:
      return 0;
  }
}

bool simplex(VtkCell cell) {
  return cell == VtkCell::Triangle || cell == VtkCell::QuadraticTriangle ||
         cell == VtkCell::Tetra || cell == VtkCell::QuadraticTetra;
}

/// Shape functions n and natural derivatives dn (row i = ∂/∂ξ_i; rows beyond the cell's
/// dimension zero) at ξ. Corner orders as in elements/cell_topology.h: the quadrilateral's
/// (−1,−1) (1,−1) (1,1) (−1,1), the hexahedron's bottom I..L then top M..P; the simplices in
/// area/volume coordinates L_I = 1 − Σξ.
void shapes(VtkCell cell, const Vec3& xi, Eigen::VectorXd& n, Eigen::Matrix3Xd& dn) {
  static constexpr std::array<std::array<double, 3>, 8> kHexCorners = {{{-1, -1, -1},
                                                                        {1, -1, -1},
                                                                        {1, 1, -1},
                                                                        {-1, 1, -1},
                                                                        {-1, -1, 1},
                                                                        {1, -1, 1},
                                                                        {1, 1, 1},
                                                                        {-1, 1, 1}}};
  switch (cell) {
    case VtkCell::Triangle:
      n.resize(3);
      dn.setZero(3, 3);
      n << 1.0 - xi[0] - xi[1], xi[0], xi[1];
      dn.row(0) << -1.0, 1.0, 0.0;
      dn.row(1) << -1.0, 0.0, 1.0;
      return;
    case VtkCell::Tetra:
      n.resize(4);
      dn.setZero(3, 4);
      n << 1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2];
      dn.row(0) << -1.0, 1.0, 0.0, 0.0;
      dn.row(1) << -1.0, 0.0, 1.0, 0.0;
      dn.row(2) << -1.0, 0.0, 0.0, 1.0;
      return;
    case VtkCell::Quad:
      n.resize(4);
      dn.setZero(3, 4);
      for (int i = 0; i < 4; ++i) {
        const double a = kHexCorners[i][0], b = kHexCorners[i][1];
        n[i] = 0.25 * (1.0 + a * xi[0]) * (1.0 + b * xi[1]);
        dn(0, i) = 0.25 * a * (1.0 + b * xi[1]);
        dn(1, i) = 0.25 * b * (1.0 + a * xi[0]);
      }
      return;
    case VtkCell::Hexahedron:
      n.resize(8);
      dn.setZero(3, 8);
      for (int i = 0; i < 8; ++i) {
        const double a = kHexCorners[i][0], b = kHexCorners[i][1], c = kHexCorners[i][2];
        const double fa = 1.0 + a * xi[0], fb = 1.0 + b * xi[1], fc = 1.0 + c * xi[2];
        n[i] = 0.125 * fa * fb * fc;
        dn(0, i) = 0.125 * a * fb * fc;
        dn(1, i) = 0.125 * b * fa * fc;
        dn(2, i) = 0.125 * c * fa * fb;
      }
      return;
    case VtkCell::QuadraticTriangle:
    case VtkCell::QuadraticQuad: {
      Eigen::Matrix<double, 2, Eigen::Dynamic> d2;
      Eigen::VectorXd corner;
      quadratic_face_shape(cell == VtkCell::QuadraticQuad ? 8 : 6, xi, n, d2, corner);
      dn.setZero(3, n.size());
      dn.topRows<2>() = d2;
      return;
    }
    case VtkCell::QuadraticTetra:
      quadratic_shape(QuadraticShape::Tet10, xi, n, dn);
      return;
    case VtkCell::QuadraticHexahedron:
      quadratic_shape(QuadraticShape::Hex20, xi, n, dn);
      return;
    default:
      n.resize(0);
      dn.resize(3, 0);
  }
}

/// The natural centre of the cell, Newton's start.
Vec3 centre(VtkCell cell) {
  if (!simplex(cell)) return Vec3::Zero();
  return natural_dimension(cell) == 2 ? Vec3(1.0 / 3.0, 1.0 / 3.0, 0.0) : Vec3::Constant(0.25);
}

/// Whether ξ lies in the reference cell, within `tol`.
bool inside(VtkCell cell, int dim, const Vec3& xi, double tol) {
  if (simplex(cell)) {
    double sum = 0.0;
    for (int i = 0; i < dim; ++i) {
      if (xi[i] < -tol) return false;
      sum += xi[i];
    }
    return sum <= 1.0 + tol;
  }
  for (int i = 0; i < dim; ++i)
    if (std::fabs(xi[i]) > 1.0 + tol) return false;
  return true;
}

}  // namespace

bool locatable_cell(VtkCell cell) {
  return natural_dimension(cell) != 0;
}

std::optional<std::vector<double>> shape_values_at(VtkCell cell, const std::vector<Vec3>& x,
                                                   const Vec3& p, double tolerance) {
  const int dim = natural_dimension(cell);
  if (dim == 0 || x.empty()) return std::nullopt;
  // Bounding-box rejection: the cheap test that discards almost every element of a mesh (a
  // quadratic cell's curved edges stay inside its nodes' hull in any mesh a solver accepts).
  Vec3 lo = x.front(), hi = x.front();
  for (const Vec3& xi : x) {
    lo = lo.cwiseMin(xi);
    hi = hi.cwiseMax(xi);
  }
  const double size = (hi - lo).norm();
  if (!(size > 0.0)) return std::nullopt;
  const double margin = std::max(tolerance, 1e-9) * size;
  if ((p.array() < lo.array() - margin).any() || (p.array() > hi.array() + margin).any())
    return std::nullopt;

  Eigen::Matrix3Xd nodes(3, static_cast<Eigen::Index>(x.size()));
  for (std::size_t k = 0; k < x.size(); ++k) nodes.col(static_cast<Eigen::Index>(k)) = x[k];
  Eigen::VectorXd n;
  Eigen::Matrix3Xd dn;
  Vec3 xi = centre(cell);
  bool converged = false;
  for (int it = 0; it < 40 && !converged; ++it) {
    shapes(cell, xi, n, dn);
    if (n.size() != nodes.cols()) return std::nullopt;
    const Vec3 r = nodes * n - p;
    const Eigen::MatrixXd j = nodes * dn.topRows(dim).transpose();  // 3 x dim
    // Volume cells: Newton on x(ξ) = p; area cells: Gauss-Newton on |x(ξ) − p|², the
    // closest point of the surface (the two coincide for a point in the cell's plane).
    const Eigen::VectorXd step = (j.transpose() * j).ldlt().solve(-(j.transpose() * r));
    if (!step.allFinite()) return std::nullopt;
    xi.head(dim) += step;
    if (xi.head(dim).cwiseAbs().maxCoeff() > 10.0) return std::nullopt;  // far outside
    converged = step.norm() < 1e-12;
  }
  shapes(cell, xi, n, dn);
  if (!inside(cell, dim, xi, std::max(tolerance, 1e-9))) return std::nullopt;
  // Newton's last step may stall short of 1e-12 on a distorted cell; the residual decides.
  if ((nodes * n - p).norm() > margin) return std::nullopt;
  return std::vector<double>(n.data(), n.data() + n.size());
}

}  // namespace impactfe::geometry
