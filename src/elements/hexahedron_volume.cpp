#include "elements/hexahedron_volume.h"

#include <algorithm>
#include <cmath>

namespace impactfe::hexahedron {

namespace {

/// The corner permutations of Flanagan & Belytschko (1981), Table: b_x of corner I is the
/// formula of corner 1 with the corners renumbered by row I.
constexpr int kPermutation[8][8] = {{0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 0, 5, 6, 7, 4},
                                    {2, 3, 0, 1, 6, 7, 4, 5}, {3, 0, 1, 2, 7, 4, 5, 6},
                                    {4, 7, 6, 5, 0, 3, 2, 1}, {5, 4, 7, 6, 1, 0, 3, 2},
                                    {6, 5, 4, 7, 2, 1, 0, 3}, {7, 6, 5, 4, 3, 2, 1, 0}};

/// FB eq. (79) for corner 1 with corners renumbered by p: ∂V/∂x_1 from the y and z of the
/// others (1-based in the paper: y2((z6−z3)−(z4−z5)) + y3(z2−z4) + ...).
inline double corner_derivative(const int* p, const double* y, const double* z) {
  const double y2 = y[p[1]], y3 = y[p[2]], y4 = y[p[3]], y5 = y[p[4]], y6 = y[p[5]], y8 = y[p[7]];
  const double z2 = z[p[1]], z3 = z[p[2]], z4 = z[p[3]], z5 = z[p[4]], z6 = z[p[5]], z8 = z[p[7]];
  return (y2 * ((z6 - z3) - (z4 - z5)) + y3 * (z2 - z4) + y4 * ((z3 - z8) - (z5 - z2)) +
          y5 * ((z8 - z6) - (z2 - z4)) + y6 * (z5 - z2) + y8 * (z4 - z5)) /
         12.0;
}

constexpr double kCornerXi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

/// det J and the shape functions at a natural point.
double jacobian_det(const double* x, const double* y, const double* z, const double* xi,
                    double* n) {
  double j[3][3] = {};
  for (int a = 0; a < 8; ++a) {
    const double f0 = 1.0 + xi[0] * kCornerXi[a][0];
    const double f1 = 1.0 + xi[1] * kCornerXi[a][1];
    const double f2 = 1.0 + xi[2] * kCornerXi[a][2];
    n[a] = 0.125 * f0 * f1 * f2;
    const double d[3] = {0.125 * kCornerXi[a][0] * f1 * f2, 0.125 * f0 * kCornerXi[a][1] * f2,
                         0.125 * f0 * f1 * kCornerXi[a][2]};
    for (int r = 0; r < 3; ++r) {
      j[r][0] += d[r] * x[a];
      j[r][1] += d[r] * y[a];
      j[r][2] += d[r] * z[a];
    }
  }
  return j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) -
         j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
         j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
}

}  // namespace

void volume_derivatives(const double* x, const double* y, const double* z, double* bx, double* by,
                        double* bz) {
  // b_y and b_z follow from b_x by the cyclic change x → y → z → x (FB eq. (79)).
  for (int a = 0; a < 8; ++a) {
    const int* p = kPermutation[a];
    bx[a] = corner_derivative(p, y, z);
    by[a] = corner_derivative(p, z, x);
    bz[a] = corner_derivative(p, x, y);
  }
}

void row_sum_volumes(const double* x, const double* y, const double* z, double* share) {
  const double g = 1.0 / std::sqrt(3.0);
  std::fill(share, share + 8, 0.0);
  double n[8];
  for (const auto& corner : kCornerXi) {
    const double xi[3] = {g * corner[0], g * corner[1], g * corner[2]};
    const double det = jacobian_det(x, y, z, xi, n);
    for (int a = 0; a < 8; ++a) share[a] += n[a] * det;
  }
}

void second_moment(const double* x, const double* y, const double* z, double* s) {
  // Gauss–Legendre, 3 points: ±√(3/5) with weight 5/9, 0 with weight 8/9.
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  std::fill(s, s + 9, 0.0);
  double n[8];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double xi[3] = {g[i], g[j], g[k]};
        const double dv = w[i] * w[j] * w[k] * jacobian_det(x, y, z, xi, n);
        double p[3] = {0.0, 0.0, 0.0};
        for (int a = 0; a < 8; ++a) {
          p[0] += n[a] * x[a];
          p[1] += n[a] * y[a];
          p[2] += n[a] * z[a];
        }
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) s[3 * r + c] += p[r] * p[c] * dv;
      }
}

double gauss_volume(const double* x, const double* y, const double* z) {
  double share[8];
  row_sum_volumes(x, y, z, share);
  double v = 0.0;
  for (double s : share) v += s;
  return v;
}

double largest_face_area(const double* x, const double* y, const double* z) {
  static constexpr int kFaces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  double largest = 0.0;
  for (const auto& f : kFaces) {
    const double d1[3] = {x[f[2]] - x[f[0]], y[f[2]] - y[f[0]], z[f[2]] - z[f[0]]};
    const double d2[3] = {x[f[3]] - x[f[1]], y[f[3]] - y[f[1]], z[f[3]] - z[f[1]]};
    const double cx = d1[1] * d2[2] - d1[2] * d2[1];
    const double cy = d1[2] * d2[0] - d1[0] * d2[2];
    const double cz = d1[0] * d2[1] - d1[1] * d2[0];
    largest = std::max(largest, cx * cx + cy * cy + cz * cz);
  }
  return 0.5 * std::sqrt(largest);
}

}  // namespace impactfe::hexahedron
