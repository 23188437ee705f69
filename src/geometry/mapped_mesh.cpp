#include "geometry/mapped_mesh.h"

#include <Eigen/Geometry>

namespace impactfe::geometry {

std::vector<double> chain_fractions(const std::vector<Vec3>& points) {
  std::vector<double> f(points.size(), 0.0);
  double total = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    total += (points[k] - points[k - 1]).norm();
    f[k] = total;
  }
  for (std::size_t k = 1; k < points.size(); ++k)
    f[k] = total > 0.0 ? f[k] / total : static_cast<double>(k) / (points.size() - 1);
  return f;
}

std::vector<Vec3> coons_quad(const std::vector<Vec3>& bottom, const std::vector<Vec3>& right,
                             const std::vector<Vec3>& top, const std::vector<Vec3>& left) {
  const int n1 = static_cast<int>(bottom.size()) - 1;
  const int n2 = static_cast<int>(right.size()) - 1;
  const auto fb = chain_fractions(bottom), ft = chain_fractions(top);
  const auto fl = chain_fractions(left), fr = chain_fractions(right);
  const Vec3 c00 = bottom.front(), c10 = bottom.back(), c11 = top.back(), c01 = top.front();
  std::vector<Vec3> out(static_cast<std::size_t>((n1 + 1) * (n2 + 1)));
  for (int j = 0; j <= n2; ++j)
    for (int i = 0; i <= n1; ++i) {
      const std::size_t si = static_cast<std::size_t>(i), sj = static_cast<std::size_t>(j);
      Vec3& p = out[static_cast<std::size_t>(i + j * (n1 + 1))];
      if (j == 0) {
        p = bottom[si];
      } else if (j == n2) {
        p = top[si];
      } else if (i == 0) {
        p = left[sj];
      } else if (i == n1) {
        p = right[sj];
      } else {
        const double u = 0.5 * (fb[si] + ft[si]);
        const double v = 0.5 * (fl[sj] + fr[sj]);
        p = (1 - v) * bottom[si] + v * top[si] + (1 - u) * left[sj] + u * right[sj] -
            ((1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + u * v * c11 + (1 - u) * v * c01);
      }
    }
  return out;
}

std::vector<Vec3> triangle_lattice(const std::vector<Vec3>& s0, const std::vector<Vec3>& s1,
                                   const std::vector<Vec3>& s2) {
  const int n = static_cast<int>(s0.size()) - 1;
  auto edge = [&](int i, int j) -> Vec3 {  // boundary point (i, j), i + j <= n on a side
    if (j == 0) return s0[static_cast<std::size_t>(i)];
    if (i == 0) return s2[static_cast<std::size_t>(n - j)];
    return s1[static_cast<std::size_t>(j)];  // i + j == n
  };
  std::vector<Vec3> out;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n - j; ++i) {
      const int k = n - i - j;
      if (i == 0 || j == 0 || k == 0) {
        out.push_back(edge(i, j));
        continue;
      }
      // Along the lattice line of constant j, of constant i, and of constant k.
      const double tj = static_cast<double>(i) / (n - j);
      const Vec3 pj = (1 - tj) * edge(0, j) + tj * edge(n - j, j);
      const double ti = static_cast<double>(j) / (n - i);
      const Vec3 pi = (1 - ti) * edge(i, 0) + ti * edge(i, n - i);
      const double tk = static_cast<double>(i) / (n - k);
      const Vec3 pk = (1 - tk) * edge(0, n - k) + tk * edge(n - k, 0);
      out.push_back((pj + pi + pk) / 3.0);
    }
  return out;
}

void transfinite_block(std::vector<Vec3>& g, int n1, int n2, int n3) {
  auto at = [&](int i, int j, int k) -> Vec3& {
    return g[static_cast<std::size_t>(i + (n1 + 1) * (j + (n2 + 1) * k))];
  };
  // Parameters: mean chord fractions of the four edges along each direction.
  auto fractions = [&](int n, auto point) {
    std::vector<double> f(static_cast<std::size_t>(n + 1), 0.0);
    for (int e = 0; e < 4; ++e) {
      std::vector<Vec3> chain;
      for (int m = 0; m <= n; ++m) chain.push_back(point(e, m));
      const auto fe = chain_fractions(chain);
      for (int m = 0; m <= n; ++m)
        f[static_cast<std::size_t>(m)] += 0.25 * fe[static_cast<std::size_t>(m)];
    }
    return f;
  };
  const auto fu = fractions(n1, [&](int e, int m) { return at(m, (e & 1) * n2, (e >> 1) * n3); });
  const auto fv = fractions(n2, [&](int e, int m) { return at((e & 1) * n1, m, (e >> 1) * n3); });
  const auto fw = fractions(n3, [&](int e, int m) { return at((e & 1) * n1, (e >> 1) * n2, m); });
  for (int k = 1; k < n3; ++k)
    for (int j = 1; j < n2; ++j)
      for (int i = 1; i < n1; ++i) {
        const double u = fu[static_cast<std::size_t>(i)], v = fv[static_cast<std::size_t>(j)],
                     w = fw[static_cast<std::size_t>(k)];
        const double U[2] = {1 - u, u}, V[2] = {1 - v, v}, W[2] = {1 - w, w};
        const int I[2] = {0, n1}, J[2] = {0, n2}, K[2] = {0, n3};
        Vec3 p = Vec3::Zero();
        for (int a = 0; a < 2; ++a) {
          p += U[a] * at(I[a], j, k) + V[a] * at(i, J[a], k) + W[a] * at(i, j, K[a]);
          for (int b = 0; b < 2; ++b) {
            p -= U[a] * V[b] * at(I[a], J[b], k) + V[a] * W[b] * at(i, J[a], K[b]) +
                 U[a] * W[b] * at(I[a], j, K[b]);
            for (int c = 0; c < 2; ++c) p += U[a] * V[b] * W[c] * at(I[a], J[b], K[c]);
          }
        }
        at(i, j, k) = p;
      }
}

double hexahedron_volume(const std::vector<Vec3>& x) {
  // Split into 6 tetrahedra sharing the diagonal I–O (corners 0 and 6).
  static const int tets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                 {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  double v = 0.0;
  for (const auto& t : tets) {
    const Vec3 a = x[static_cast<std::size_t>(t[1])] - x[static_cast<std::size_t>(t[0])];
    const Vec3 b = x[static_cast<std::size_t>(t[2])] - x[static_cast<std::size_t>(t[0])];
    const Vec3 c = x[static_cast<std::size_t>(t[3])] - x[static_cast<std::size_t>(t[0])];
    v += a.cross(b).dot(c) / 6.0;
  }
  return v;
}

}  // namespace impactfe::geometry
