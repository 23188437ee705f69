#include "geometry/mesh_quality.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "elements/element_registry.h"
#include "elements/quadratic_shapes.h"

namespace impactfe::geometry {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec3 unit(const Vec3& v) {
  const double n = v.norm();
  return n > 0.0 ? Vec3(v / n) : Vec3::Zero();
}

/// det[â, b̂, ĉ] of the unit edges from corner o to a, b, c: the corner's scaled Jacobian before
/// the regular cell's normalisation.
double corner_jacobian(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  return unit(a - o).dot(unit(b - o).cross(unit(c - o)));
}

/// The smallest corner sine of a polygon (a triangle or a quadrilateral) about its normal n.
double polygon_jacobian(const std::vector<Vec3>& p, const Vec3& n) {
  const int m = static_cast<int>(p.size());
  double worst = kInf;
  for (int i = 0; i < m; ++i) {
    const Vec3& o = p[static_cast<std::size_t>(i)];
    const Vec3 next = unit(p[static_cast<std::size_t>((i + 1) % m)] - o);
    const Vec3 prev = unit(p[static_cast<std::size_t>((i + m - 1) % m)] - o);
    worst = std::min(worst, next.cross(prev).dot(n));
  }
  return worst;
}

// Normalisations: the corner value of the regular cell.
const double kTetIdeal = 1.0 / std::sqrt(2.0);
const double kTriangleIdeal = std::sqrt(3.0) / 2.0;
const double kPyramidIdeal = 1.0 / std::sqrt(2.0);

double hexahedron_jacobian(const std::vector<Vec3>& x) {
  // The three edges leaving each corner, right-handed for MAPDL's positive brick (I J K L
  // counter-clockwise seen from M N O P).
  static constexpr int kAdjacent[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                          {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  double worst = kInf;
  for (int i = 0; i < 8; ++i)
    worst = std::min(
        worst, corner_jacobian(x[i], x[kAdjacent[i][0]], x[kAdjacent[i][1]], x[kAdjacent[i][2]]));
  return worst;
}

double tetrahedron_jacobian(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double worst = std::min({corner_jacobian(a, b, c, d), corner_jacobian(b, c, a, d),
                                 corner_jacobian(c, a, b, d), corner_jacobian(d, c, b, a)});
  return worst / kTetIdeal;
}

/// Bottom triangle a, top triangle b (b[i] above a[i]).
double wedge_jacobian(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  double worst = kInf;
  for (int i = 0; i < 3; ++i) {
    const int next = (i + 1) % 3, prev = (i + 2) % 3;
    worst = std::min(worst, corner_jacobian(a[i], a[next], a[prev], b[i]));
    worst = std::min(worst, corner_jacobian(b[i], b[prev], b[next], a[i]));
  }
  return worst / kTriangleIdeal;
}

/// Base corners c (counter-clockwise seen from the apex t); the apex itself is not measured.
double pyramid_jacobian(const std::array<Vec3, 4>& c, const Vec3& t) {
  double worst = kInf;
  for (int i = 0; i < 4; ++i)
    worst = std::min(worst, corner_jacobian(c[i], c[(i + 1) % 4], c[(i + 3) % 4], t));
  return worst / kPyramidIdeal;
}

/// max / min of det J of the isoparametric map over the nodes and the centre (+inf when one
/// is not positive). Volume: det of the 3 x 3 map; area: the area stretch signed against the
/// centre's normal.
double jacobian_ratio(QuadraticShape shape, const std::vector<Vec3>& x) {
  const int n = quadratic_shape_nodes(shape);
  Eigen::Matrix3Xd xm(3, n);
  for (int a = 0; a < n; ++a) xm.col(a) = x[static_cast<std::size_t>(a)];
  std::vector<Eigen::Vector3d> points = quadratic_shape_nodes_xi(shape);
  points.push_back(quadratic_shape_centre(shape));
  double lo = kInf, hi = 0.0;
  Eigen::VectorXd nf;
  Eigen::Matrix3Xd dn;
  for (const Eigen::Vector3d& xi : points) {
    quadratic_shape(shape, xi, nf, dn);
    const double det = (xm * dn.transpose()).determinant();
    lo = std::min(lo, det);
    hi = std::max(hi, det);
  }
  return lo > 0.0 ? hi / lo : kInf;
}

double area_jacobian_ratio(int face_nodes, const std::vector<Vec3>& x) {
  Eigen::Matrix3Xd xm(3, face_nodes);
  for (int a = 0; a < face_nodes; ++a) xm.col(a) = x[static_cast<std::size_t>(a)];
  std::vector<Eigen::Vector3d> points;
  if (face_nodes == 8)
    points = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0},  {-1, 1, 0}, {0, -1, 0},
              {1, 0, 0},   {0, 1, 0},  {-1, 0, 0}, {0, 0, 0}};
  else
    points = {{0, 0, 0},
              {1, 0, 0},
              {0, 1, 0},
              {0.5, 0, 0},
              {0.5, 0.5, 0},
              {0, 0.5, 0},
              {1.0 / 3.0, 1.0 / 3.0, 0}};
  Eigen::VectorXd nf, corner;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dn;
  const auto stretch = [&](const Eigen::Vector3d& xi) {
    quadratic_face_shape(face_nodes, xi, nf, dn, corner);
    const Vec3 a = xm * dn.row(0).transpose(), b = xm * dn.row(1).transpose();
    return Vec3(a.cross(b));
  };
  const Vec3 normal = unit(stretch(points.back()));
  double lo = kInf, hi = 0.0;
  for (const Eigen::Vector3d& xi : points) {
    const double det = stretch(xi).dot(normal);
    lo = std::min(lo, det);
    hi = std::max(hi, det);
  }
  return lo > 0.0 ? hi / lo : kInf;
}

}  // namespace

std::optional<ElementShape> element_shape(const CellTopology& cell, const std::vector<int>& nodes,
                                          const std::vector<Vec3>& x) {
  if (cell.dimension < 2 || static_cast<int>(nodes.size()) < cell.n_nodes() ||
      x.size() < nodes.size())
    return std::nullopt;
  const auto same = [&](int a, int b) { return nodes[a] == nodes[b]; };
  ElementShape s;
  // Edge ratio over the edges between distinct corners.
  double longest = 0.0, shortest = kInf;
  for (const auto& [a, b] : cell.edges) {
    if (same(a, b)) continue;
    const double l = (x[a] - x[b]).norm();
    longest = std::max(longest, l);
    shortest = std::min(shortest, l);
  }
  if (!(longest > 0.0)) return std::nullopt;
  s.edge_ratio = shortest > 0.0 ? longest / shortest : kInf;
  bool collapsed = false;
  if (cell.dimension == 3) {
    if (cell.corner_nodes == 4) {
      s.scaled_jacobian = tetrahedron_jacobian(x[0], x[1], x[2], x[3]);
    } else {
      int distinct = 0;
      for (int a = 0; a < 8; ++a) {
        bool repeated = false;
        for (int b = 0; b < a; ++b) repeated = repeated || same(a, b);
        distinct += repeated ? 0 : 1;
      }
      collapsed = distinct < 8;
      // MAPDL's degenerate bricks: wedge K = L, O = P; pyramid M = N = O = P; tetrahedron
      // K = L and M = N = O = P.
      const bool top_point = same(4, 5) && same(5, 6) && same(6, 7);
      if (distinct == 8)
        s.scaled_jacobian = hexahedron_jacobian(x);
      else if (distinct == 6 && same(2, 3) && same(6, 7))
        s.scaled_jacobian = wedge_jacobian({x[0], x[1], x[2]}, {x[4], x[5], x[6]});
      else if (distinct == 5 && top_point)
        s.scaled_jacobian = pyramid_jacobian({x[0], x[1], x[2], x[3]}, x[4]);
      else if (distinct == 4 && same(2, 3) && top_point)
        s.scaled_jacobian = tetrahedron_jacobian(x[0], x[1], x[2], x[4]);
      else
        return std::nullopt;
    }
  } else {
    const bool triangle = cell.corner_nodes == 3 || same(2, 3);
    collapsed = cell.corner_nodes == 4 && triangle;
    std::vector<Vec3> p(x.begin(), x.begin() + (triangle ? 3 : 4));
    const Vec3 normal =
        triangle ? unit((p[1] - p[0]).cross(p[2] - p[0])) : unit((p[2] - p[0]).cross(p[3] - p[1]));
    s.scaled_jacobian = polygon_jacobian(p, normal) / (triangle ? kTriangleIdeal : 1.0);
  }
  if (cell.midside_nodes > 0 && !collapsed) {
    if (cell.cell == VtkCell::QuadraticHexahedron)
      s.jacobian_ratio = jacobian_ratio(QuadraticShape::Hex20, x);
    else if (cell.cell == VtkCell::QuadraticTetra)
      s.jacobian_ratio = jacobian_ratio(QuadraticShape::Tet10, x);
    else if (cell.cell == VtkCell::QuadraticQuad)
      s.jacobian_ratio = area_jacobian_ratio(8, x);
    else if (cell.cell == VtkCell::QuadraticTriangle)
      s.jacobian_ratio = area_jacobian_ratio(6, x);
  }
  return s;
}

MeshQuality mesh_quality(const Model& model, const std::vector<int>& elements) {
  MeshQuality q;
  q.worst_scaled_jacobian = kInf;
  for (int id : elements) {
    const auto e = model.elements.find(id);
    if (e == model.elements.end()) continue;
    const auto t = model.element_types.find(e->second.type);
    if (t == model.element_types.end()) continue;
    const CellTopology& cell = element_type_descriptor(t->second).topology();
    std::vector<int> nodes(
        e->second.nodes.begin(),
        e->second.nodes.begin() + std::min<std::ptrdiff_t>(cell.n_nodes(), e->second.nodes.size()));
    std::vector<Vec3> x;
    for (int n : nodes) {
      const auto node = model.nodes.find(n);
      if (node == model.nodes.end()) break;
      x.push_back(node->second.x);
    }
    if (x.size() != nodes.size()) continue;
    const std::optional<ElementShape> s = element_shape(cell, nodes, x);
    if (!s) continue;
    ++q.measured;
    if (s->edge_ratio > q.worst_edge_ratio || q.worst_edge_ratio_element == 0) {
      q.worst_edge_ratio = s->edge_ratio;
      q.worst_edge_ratio_element = id;
    }
    if (s->scaled_jacobian < q.worst_scaled_jacobian) {
      q.worst_scaled_jacobian = s->scaled_jacobian;
      q.worst_scaled_jacobian_element = id;
    }
    const double ratio = s->jacobian_ratio.value_or(1.0);
    if (s->jacobian_ratio &&
        (ratio > q.worst_jacobian_ratio || q.worst_jacobian_ratio_element == 0)) {
      q.worst_jacobian_ratio = ratio;
      q.worst_jacobian_ratio_element = id;
    }
    const bool inverted = !(s->scaled_jacobian > 0.0) || ratio == kInf;
    if (inverted) {
      ++q.inverted;
      if (q.first_inverted == 0 || id < q.first_inverted) q.first_inverted = id;
    }
    if (inverted || s->edge_ratio > kEdgeRatioWarning ||
        s->scaled_jacobian < kScaledJacobianWarning || ratio > kJacobianRatioWarning) {
      ++q.past_limits;
      if (q.first_past_limits == 0 || id < q.first_past_limits) q.first_past_limits = id;
    }
  }
  if (q.measured == 0) q.worst_scaled_jacobian = 1.0;
  return q;
}

std::string describe(const MeshQuality& q) {
  if (q.measured == 0) return {};
  const auto number = [](double v) {
    return v == kInf ? std::string("inf") : fmt::format("{:.3g}", v);
  };
  std::string out = fmt::format(
      "{} element(s): edge ratio <= {} (element {}), scaled Jacobian >= "
      "{} (element {})",
      q.measured, number(q.worst_edge_ratio), q.worst_edge_ratio_element,
      number(q.worst_scaled_jacobian), q.worst_scaled_jacobian_element);
  if (q.worst_jacobian_ratio_element != 0)
    out += fmt::format(", Jacobian ratio <= {} (element {})", number(q.worst_jacobian_ratio),
                       q.worst_jacobian_ratio_element);
  return out;
}

}  // namespace impactfe::geometry
