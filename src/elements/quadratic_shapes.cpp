#include "elements/quadratic_shapes.h"

#include <cmath>

#include "core/errors.h"
#include "elements/cell_topology.h"

namespace impactfe {

namespace {

const CellTopology& cell_of(QuadraticShape shape) {
  return cell_topology(shape == QuadraticShape::Hex20 ? VtkCell::QuadraticHexahedron
                                                      : VtkCell::QuadraticTetra);
}

/// Corners of the natural cells: the cube's I..P (IJKL at ζ = −1) and the unit tetrahedron's.
std::vector<Eigen::Vector3d> corners_xi(QuadraticShape shape) {
  if (shape == QuadraticShape::Tet10) return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  return {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
          {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
}

/// The 20-node serendipity functions (Zienkiewicz & Taylor vol. 1 eq. 6.43): at a corner
/// N = ⅛ Π(1 + ξ_i ξ_ai) (Σ ξ_i ξ_ai − 2); at a midside node with ξ_ai = 0,
/// N = ¼ (1 − ξ_i²) Π_{j≠i} (1 + ξ_j ξ_aj).
void hex20(const std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& x, Eigen::VectorXd& n,
           Eigen::Matrix3Xd& dn) {
  for (int a = 0; a < 20; ++a) {
    const Eigen::Vector3d& c = nodes[static_cast<std::size_t>(a)];
    if (a < 8) {
      const double f0 = 1 + x(0) * c(0), f1 = 1 + x(1) * c(1), f2 = 1 + x(2) * c(2);
      const double s = x(0) * c(0) + x(1) * c(1) + x(2) * c(2);
      n(a) = 0.125 * f0 * f1 * f2 * (s - 2);
      // ∂/∂ξ of ⅛ f0 f1 f2 (s − 2) = ⅛ ξ_a f1 f2 (s − 2 + f0).
      dn(0, a) = 0.125 * c(0) * f1 * f2 * (s - 2 + f0);
      dn(1, a) = 0.125 * c(1) * f0 * f2 * (s - 2 + f1);
      dn(2, a) = 0.125 * c(2) * f0 * f1 * (s - 2 + f2);
      continue;
    }
    const int i = c(0) == 0 ? 0 : (c(1) == 0 ? 1 : 2);  // the coordinate along the edge
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double bubble = 1 - x(i) * x(i), fj = 1 + x(j) * c(j), fk = 1 + x(k) * c(k);
    n(a) = 0.25 * bubble * fj * fk;
    dn(i, a) = -0.5 * x(i) * fj * fk;
    dn(j, a) = 0.25 * bubble * c(j) * fk;
    dn(k, a) = 0.25 * bubble * fj * c(k);
  }
}

/// The 10-node tetrahedron (Zienkiewicz & Taylor vol. 1 eq. 6.40): corners L(2L − 1), midside
/// nodes 4 L_a L_b, with L_I = 1 − ξ − η − ζ.
void tet10(const Eigen::Vector3d& x, Eigen::VectorXd& n, Eigen::Matrix3Xd& dn) {
  const double l[4] = {1 - x(0) - x(1) - x(2), x(0), x(1), x(2)};
  static const double dl[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 4; ++a) {
    n(a) = l[a] * (2 * l[a] - 1);
    for (int i = 0; i < 3; ++i) dn(i, a) = (4 * l[a] - 1) * dl[a][i];
  }
  const auto& edges = cell_topology(VtkCell::QuadraticTetra).edges;
  for (int m = 0; m < 6; ++m) {
    const int a = edges[static_cast<std::size_t>(m)][0], b = edges[static_cast<std::size_t>(m)][1];
    n(4 + m) = 4 * l[a] * l[b];
    for (int i = 0; i < 3; ++i) dn(i, 4 + m) = 4 * (dl[a][i] * l[b] + l[a] * dl[b][i]);
  }
}

/// Gauss-Legendre points and weights on [-1, 1] (n = 1..4).
void gauss_1d(int n, std::vector<double>& x, std::vector<double>& w) {
  switch (n) {
    case 1:
      x = {0.0}, w = {2.0};
      return;
    case 2:
      x = {-1 / std::sqrt(3.0), 1 / std::sqrt(3.0)}, w = {1.0, 1.0};
      return;
    case 3:
      x = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w = {5.0 / 9, 8.0 / 9, 5.0 / 9};
      return;
    case 4: {
      const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(6.0 / 5));
      const double b = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(6.0 / 5));
      const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
      x = {-b, -a, a, b}, w = {wb, wa, wa, wb};
      return;
    }
    default:
      IMPACTFE_CHECK(false, "Gauss-Legendre rule of unsupported order");
  }
}

/// The same on [0, 1].
void gauss_unit(int n, std::vector<double>& x, std::vector<double>& w) {
  gauss_1d(n, x, w);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.5 * (x[i] + 1), w[i] *= 0.5;
}

}  // namespace

int quadratic_shape_nodes(QuadraticShape shape) {
  return shape == QuadraticShape::Hex20 ? 20 : 10;
}

std::vector<Eigen::Vector3d> quadratic_shape_nodes_xi(QuadraticShape shape) {
  std::vector<Eigen::Vector3d> xi = corners_xi(shape);
  for (const auto& e : cell_of(shape).edges)
    xi.push_back(0.5 * (xi[static_cast<std::size_t>(e[0])] + xi[static_cast<std::size_t>(e[1])]));
  return xi;
}

Eigen::Vector3d quadratic_shape_centre(QuadraticShape shape) {
  return shape == QuadraticShape::Hex20 ? Eigen::Vector3d::Zero() : Eigen::Vector3d::Constant(0.25);
}

void quadratic_shape(QuadraticShape shape, const Eigen::Vector3d& xi, Eigen::VectorXd& n,
                     Eigen::Matrix3Xd& dn) {
  const int nn = quadratic_shape_nodes(shape);
  n.resize(nn);
  dn.setZero(3, nn);
  if (shape == QuadraticShape::Tet10) {
    tet10(xi, n, dn);
    return;
  }
  static const std::vector<Eigen::Vector3d> nodes = quadratic_shape_nodes_xi(QuadraticShape::Hex20);
  hex20(nodes, xi, n, dn);
}

std::vector<QuadraturePoint> gauss_cube(int n) {
  std::vector<double> x, w;
  gauss_1d(n, x, w);
  std::vector<QuadraturePoint> out;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        out.push_back({Eigen::Vector3d(x[i], x[j], x[k]), w[i] * w[j] * w[k]});
  return out;
}

std::vector<QuadraturePoint> gauss_square(int n) {
  std::vector<double> x, w;
  gauss_1d(n, x, w);
  std::vector<QuadraturePoint> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) out.push_back({Eigen::Vector3d(x[i], x[j], 0.0), w[i] * w[j]});
  return out;
}

std::vector<QuadraturePoint> tetrahedron_4_point() {
  // a = (5 + 3√5)/20, b = (5 − √5)/20: the points on the lines from the centroid to the corners.
  const double a = (5 + 3 * std::sqrt(5.0)) / 20, b = (5 - std::sqrt(5.0)) / 20;
  return {{Eigen::Vector3d(b, b, b), 1.0 / 24},
          {Eigen::Vector3d(a, b, b), 1.0 / 24},
          {Eigen::Vector3d(b, a, b), 1.0 / 24},
          {Eigen::Vector3d(b, b, a), 1.0 / 24}};
}

std::vector<QuadraturePoint> collapsed_tetrahedron(int n) {
  std::vector<double> x, w;
  gauss_unit(n, x, w);
  std::vector<QuadraturePoint> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double u = x[i], v = x[j], s = x[k];
        out.push_back({Eigen::Vector3d(u, v * (1 - u), s * (1 - u) * (1 - v)),
                       w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v)});
      }
  return out;
}

std::vector<QuadraturePoint> collapsed_triangle(int n) {
  std::vector<double> x, w;
  gauss_unit(n, x, w);
  std::vector<QuadraturePoint> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      out.push_back({Eigen::Vector3d(x[i], x[j] * (1 - x[i]), 0.0), w[i] * w[j] * (1 - x[i])});
  return out;
}

void quadratic_face_shape(int face_nodes, const Eigen::Vector3d& xi, Eigen::VectorXd& n,
                          Eigen::Matrix<double, 2, Eigen::Dynamic>& dn, Eigen::VectorXd& corner) {
  const double s = xi(0), t = xi(1);
  n.resize(face_nodes);
  dn.setZero(2, face_nodes);
  if (face_nodes == 6) {
    const double l[3] = {1 - s - t, s, t};
    static const double dl[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    corner.resize(3);
    for (int a = 0; a < 3; ++a) {
      corner(a) = l[a];
      n(a) = l[a] * (2 * l[a] - 1);
      for (int i = 0; i < 2; ++i) dn(i, a) = (4 * l[a] - 1) * dl[a][i];
      const int b = (a + 1) % 3;
      n(3 + a) = 4 * l[a] * l[b];
      for (int i = 0; i < 2; ++i) dn(i, 3 + a) = 4 * (dl[a][i] * l[b] + l[a] * dl[b][i]);
    }
    return;
  }
  IMPACTFE_CHECK(face_nodes == 8, "a quadratic face has 6 or 8 nodes");
  static const double cs[8] = {-1, 1, 1, -1, 0, 1, 0, -1}, ct[8] = {-1, -1, 1, 1, -1, 0, 1, 0};
  corner.resize(4);
  for (int a = 0; a < 8; ++a) {
    const double fs = 1 + s * cs[a], ft = 1 + t * ct[a];
    if (a < 4) {
      corner(a) = 0.25 * fs * ft;
      n(a) = 0.25 * fs * ft * (s * cs[a] + t * ct[a] - 1);
      dn(0, a) = 0.25 * cs[a] * ft * (2 * s * cs[a] + t * ct[a]);
      dn(1, a) = 0.25 * ct[a] * fs * (s * cs[a] + 2 * t * ct[a]);
    } else if (cs[a] == 0) {
      n(a) = 0.5 * (1 - s * s) * ft;
      dn(0, a) = -s * ft;
      dn(1, a) = 0.5 * (1 - s * s) * ct[a];
    } else {
      n(a) = 0.5 * fs * (1 - t * t);
      dn(0, a) = 0.5 * cs[a] * (1 - t * t);
      dn(1, a) = -t * fs;
    }
  }
}

}  // namespace impactfe
