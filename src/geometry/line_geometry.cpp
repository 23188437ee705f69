#include "geometry/line_geometry.h"

#include "geometry/mapped_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace impactfe::geometry {

namespace {

constexpr double kDeg = M_PI / 180.0;

/// θ2 continued from θ1 the shorter way: θ1 + Δ with Δ in (−180, 180].
double continue_angle(double t1, double t2) {
  double d = std::fmod(t2 - t1, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return t1 + d;
}

}  // namespace

void set_line_path(Line& line, const Vec3& a, const Vec3& b, const CoordinateSystem& path) {
  line.path = path;
  line.c1 = path.from_global(a);
  line.c2 = path.from_global(b);
  if (!path.curvilinear()) return;
  const double scale = std::max({1.0, a.norm(), b.norm()});
  const bool axis1 = std::fabs(line.c1(0)) <= 1e-12 * scale;
  const bool axis2 = std::fabs(line.c2(0)) <= 1e-12 * scale;
  if (axis1) line.c1.tail<2>() = line.c2.tail<2>();
  if (axis2) line.c2.tail<2>() = line.c1.tail<2>();
  line.c2(1) = continue_angle(line.c1(1), line.c2(1));
  if (path.kind == CsysKind::Spherical) line.c2(2) = continue_angle(line.c1(2), line.c2(2));
}

void set_arc_path(Line& line, const Vec3& a, const Vec3& centre, const Vec3& axis,
                  double sweep_deg) {
  const Vec3 r = a - centre;
  const Vec3 z = axis.normalized();
  const Vec3 x = (r - r.dot(z) * z).normalized();
  CoordinateSystem cs;
  cs.kind = CsysKind::Cylindrical;
  cs.origin = centre;
  cs.axes.col(0) = x;
  cs.axes.col(1) = z.cross(x);
  cs.axes.col(2) = z;
  line.path = cs;
  line.c1 = cs.from_global(a);
  line.c2 = Vec3(line.c1(0), line.c1(1) + sweep_deg, line.c1(2));
}

Vec3 line_point(const Line& line, double s) {
  return line.path.to_global(line.c1 + s * (line.c2 - line.c1));
}

double line_parameter(const Line& line, const Vec3& x) {
  // The distance along a line straight in its path system has one minimum per sampling cell
  // near the node (arcs sweep at most 360°): 64 samples, then golden section in the best cell.
  const int samples = 64;
  int best = 0;
  double best_d = (line_point(line, 0.0) - x).squaredNorm();
  for (int k = 1; k <= samples; ++k) {
    const double d = (line_point(line, static_cast<double>(k) / samples) - x).squaredNorm();
    if (d < best_d) best_d = d, best = k;
  }
  double lo = std::max(0.0, (best - 1.0) / samples), hi = std::min(1.0, (best + 1.0) / samples);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 60; ++it) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if ((line_point(line, m1) - x).squaredNorm() < (line_point(line, m2) - x).squaredNorm())
      hi = m2;
    else
      lo = m1;
  }
  return 0.5 * (lo + hi);
}

double line_length(const Line& line) {
  const Vec3 d = line.c2 - line.c1;
  if (!line.path.curvilinear()) return d.norm();
  // 8 panels x 5-point Gauss-Legendre of |dx/ds| in the path coordinates.
  static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
  static const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                               0.4786286704993665, 0.2369268850561891};
  const int panels = 8;
  double length = 0.0;
  for (int p = 0; p < panels; ++p) {
    for (int g = 0; g < 5; ++g) {
      const double s = (p + 0.5 * (gx[g] + 1.0)) / panels;
      const Vec3 c = line.c1 + s * d;
      double speed2 = d(0) * d(0);
      if (line.path.kind == CsysKind::Cylindrical) {
        speed2 += std::pow(c(0) * d(1) * kDeg, 2) + d(2) * d(2);
      } else {
        speed2 += std::pow(c(0) * std::cos(c(2) * kDeg) * d(1) * kDeg, 2) +
                  std::pow(c(0) * d(2) * kDeg, 2);
      }
      length += 0.5 / panels * gw[g] * std::sqrt(speed2);
    }
  }
  return length;
}

double line_sweep_angle(const Line& line) {
  if (!line.path.curvilinear()) return 0.0;
  double angle = std::fabs(line.c2(1) - line.c1(1));
  if (line.path.kind == CsysKind::Spherical)
    angle = std::max(angle, std::fabs(line.c2(2) - line.c1(2)));
  return angle;
}

Vec3 line_centroid(const Line& line) {
  if (!line.path.curvilinear()) return 0.5 * (line_point(line, 0.0) + line_point(line, 1.0));
  Vec3 sum = Vec3::Zero();
  const int n = 64;
  for (int k = 0; k < n; ++k) sum += line_point(line, (k + 0.5) / n);
  return sum / n;
}

Vec3 area_centroid(const SolidModel& solid, const Area& area) {
  const int n = 8;
  std::vector<std::vector<Vec3>> sides;
  for (int sl : area.lines) {
    const Line& line = solid.lines.at(std::abs(sl));
    std::vector<Vec3> pts;
    for (int k = 0; k <= n; ++k)
      pts.push_back(line_point(line, sl > 0 ? double(k) / n : 1.0 - double(k) / n));
    sides.push_back(std::move(pts));
  }
  auto weighted = [](const Vec3& a, const Vec3& b, const Vec3& c, Vec3& sum, double& total) {
    const double w = 0.5 * (b - a).cross(c - a).norm();
    sum += w * (a + b + c) / 3.0;
    total += w;
  };
  Vec3 sum = Vec3::Zero();
  double total = 0.0;
  if (sides.size() == 4) {
    std::vector<Vec3> top(sides[2].rbegin(), sides[2].rend()),
        left(sides[3].rbegin(), sides[3].rend());
    const auto g = coons_quad(sides[0], sides[1], top, left);
    auto at = [&](int i, int j) { return g[static_cast<std::size_t>(i + j * (n + 1))]; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        weighted(at(i, j), at(i + 1, j), at(i + 1, j + 1), sum, total);
        weighted(at(i, j), at(i + 1, j + 1), at(i, j + 1), sum, total);
      }
  } else if (sides.size() == 3) {
    const auto g = triangle_lattice(sides[0], sides[1], sides[2]);
    auto at = [&](int i, int j) {
      return g[static_cast<std::size_t>(j * (n + 1) - j * (j - 1) / 2 + i)];
    };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n - j; ++i) {
        weighted(at(i, j), at(i + 1, j), at(i, j + 1), sum, total);
        if (i < n - j - 1) weighted(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), sum, total);
      }
  }
  if (total > 0.0) return sum / total;
  Vec3 mean = Vec3::Zero();
  int count = 0;
  for (const auto& side : sides)
    for (std::size_t k = 0; k + 1 < side.size(); ++k, ++count) mean += side[k];
  return count > 0 ? Vec3(mean / count) : Vec3::Zero();
}

Vec3 volume_centroid(const SolidModel& solid, const Volume& volume) {
  Vec3 sum = Vec3::Zero();
  for (int a : volume.areas) sum += area_centroid(solid, solid.areas.at(a));
  return volume.areas.empty() ? sum : Vec3(sum / static_cast<double>(volume.areas.size()));
}

Vec3 interpolate_in_system(const CoordinateSystem& system, const Vec3& a, const Vec3& b, double s) {
  Line line;
  set_line_path(line, a, b, system);
  return line_point(line, s);
}

}  // namespace impactfe::geometry
