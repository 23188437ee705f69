#include "elements/plane_solid.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"

namespace impactfe {

namespace {

constexpr double kTwoPi = 6.283185307179586;

bool is_triangle(PlaneShape s) {
  return s == PlaneShape::Tri3 || s == PlaneShape::Tri6;
}

bool is_quadratic(PlaneShape s) {
  return s == PlaneShape::Quad8 || s == PlaneShape::Tri6;
}

/// Shape functions and their natural derivatives (Zienkiewicz & Taylor vol. 1, §6.3-§6.5).
void plane_shape(PlaneShape shape, const Eigen::Vector2d& xi, Eigen::VectorXd& n,
                 Eigen::Matrix2Xd& dn) {
  const double s = xi(0), t = xi(1);
  const int nn = plane_shape_nodes(shape);
  n.resize(nn);
  dn.resize(2, nn);
  static const double cs[4] = {-1, 1, 1, -1}, ct[4] = {-1, -1, 1, 1};
  switch (shape) {
    case PlaneShape::Quad4:
      for (int a = 0; a < 4; ++a) {
        n(a) = 0.25 * (1 + s * cs[a]) * (1 + t * ct[a]);
        dn(0, a) = 0.25 * cs[a] * (1 + t * ct[a]);
        dn(1, a) = 0.25 * ct[a] * (1 + s * cs[a]);
      }
      break;
    case PlaneShape::Quad8: {
      for (int a = 0; a < 4; ++a) {
        const double ps = 1 + s * cs[a], pt = 1 + t * ct[a], q = s * cs[a] + t * ct[a] - 1;
        n(a) = 0.25 * ps * pt * q;
        dn(0, a) = 0.25 * cs[a] * pt * (q + ps);
        dn(1, a) = 0.25 * ct[a] * ps * (q + pt);
      }
      // Midsides of I-J (η = −1), J-K (ξ = 1), K-L (η = 1), L-I (ξ = −1).
      static const double ms[4] = {0, 1, 0, -1}, mt[4] = {-1, 0, 1, 0};
      for (int k = 0; k < 4; ++k) {
        const int a = 4 + k;
        if (ms[k] == 0) {
          n(a) = 0.5 * (1 - s * s) * (1 + t * mt[k]);
          dn(0, a) = -s * (1 + t * mt[k]);
          dn(1, a) = 0.5 * (1 - s * s) * mt[k];
        } else {
          n(a) = 0.5 * (1 + s * ms[k]) * (1 - t * t);
          dn(0, a) = 0.5 * ms[k] * (1 - t * t);
          dn(1, a) = -t * (1 + s * ms[k]);
        }
      }
      break;
    }
    case PlaneShape::Tri3:
      n << 1 - s - t, s, t;
      dn << -1, 1, 0, -1, 0, 1;
      break;
    case PlaneShape::Tri6: {
      const double l1 = 1 - s - t, l2 = s, l3 = t;
      n << l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1), 4 * l1 * l2, 4 * l2 * l3,
          4 * l3 * l1;
      // ∂L1 = (−1, −1), ∂L2 = (1, 0), ∂L3 = (0, 1).
      dn << -(4 * l1 - 1), 4 * l2 - 1, 0, 4 * (l1 - l2), 4 * l3, -4 * l3,  //
          -(4 * l1 - 1), 0, 4 * l3 - 1, -4 * l2, 4 * l2, 4 * (l1 - l3);
      break;
    }
  }
}

Eigen::Vector2d centre(PlaneShape shape) {
  return is_triangle(shape) ? Eigen::Vector2d(1.0 / 3.0, 1.0 / 3.0) : Eigen::Vector2d::Zero();
}

/// The stiffness points: 2x2 Gauss on the quadrilaterals (MAPDL's rule for PLANE182 and
/// PLANE183), the centroid of the constant-strain triangle in plane stress and plane strain
/// (B is constant there), the 3-point rule (degree 2) on the 6-node triangle and on the
/// axisymmetric 3-node triangle. At the centroid alone the axisymmetric triangle would have
/// 4 strain rows for 6 DOFs, so besides the axial translation a second zero-energy mode: the
/// in-plane rotation about the centroid, u_r = c (z − z̄), u_z = −c r, whose hoop strain
/// u_r / r vanishes only at z = z̄.
/// Reduced integration of the 4-node quadrilateral (PLANE182 KEYOPT(1) = 1): the centre alone
/// (MAPDL theory reference, PLANE182: 1 point if KEYOPT(1) = 1), stabilised by form_hourglass().
std::vector<QuadraturePoint> stiffness_rule(PlaneShape shape, PlaneBehaviour behaviour,
                                            PlaneTechnology technology) {
  switch (shape) {
    case PlaneShape::Quad4:
      if (technology == PlaneTechnology::Reduced) return {{Eigen::Vector3d(0.0, 0.0, 0.0), 4.0}};
      [[fallthrough]];
    case PlaneShape::Quad8:
      return gauss_square(2);
    case PlaneShape::Tri3:
      if (behaviour != PlaneBehaviour::Axisymmetric)
        return {{Eigen::Vector3d(1.0 / 3.0, 1.0 / 3.0, 0.0), 0.5}};
      [[fallthrough]];
    case PlaneShape::Tri6:
      return {{Eigen::Vector3d(1.0 / 6.0, 1.0 / 6.0, 0.0), 1.0 / 6.0},
              {Eigen::Vector3d(2.0 / 3.0, 1.0 / 6.0, 0.0), 1.0 / 6.0},
              {Eigen::Vector3d(1.0 / 6.0, 2.0 / 3.0, 0.0), 1.0 / 6.0}};
  }
  return {};
}

/// Rules exact for the consistent mass of an undistorted element, also with the radius of
/// axisymmetry in the integrand (degree 3 per direction on the 4-node, 5 on the 8-node
/// quadrilateral; 3 and 5 on the triangles).
std::vector<QuadraturePoint> mass_rule(PlaneShape shape) {
  switch (shape) {
    case PlaneShape::Quad4:
      return gauss_square(2);
    case PlaneShape::Quad8:
      return gauss_square(3);
    default:
      return collapsed_triangle(4);
  }
}

/// D of (xx, yy, zz, xy): plane stress with a zero zz row (σzz = 0), otherwise the 3-D
/// isotropic law restricted to εyz = εxz = 0 (Cook et al. 3.1-5).
Eigen::Matrix4d plane_elasticity(double e, double nu, PlaneBehaviour behaviour) {
  Eigen::Matrix4d d = Eigen::Matrix4d::Zero();
  if (behaviour == PlaneBehaviour::PlaneStress) {
    const double c = e / (1 - nu * nu);
    d(0, 0) = d(1, 1) = c;
    d(0, 1) = d(1, 0) = c * nu;
    d(3, 3) = c * 0.5 * (1 - nu);
    return d;
  }
  const Matrix6d d3 = isotropic_elasticity_matrix(e, nu);
  const int rows[4] = {0, 1, 2, 3};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d(i, j) = d3(rows[i], rows[j]);
  return d;
}

}  // namespace

int plane_shape_nodes(PlaneShape shape) {
  switch (shape) {
    case PlaneShape::Quad4:
      return 4;
    case PlaneShape::Tri3:
      return 3;
    case PlaneShape::Quad8:
      return 8;
    case PlaneShape::Tri6:
      return 6;
  }
  return 0;
}

std::vector<Eigen::Vector2d> plane_shape_nodes_xi(PlaneShape shape) {
  using V = Eigen::Vector2d;
  switch (shape) {
    case PlaneShape::Quad4:
      return {V(-1, -1), V(1, -1), V(1, 1), V(-1, 1)};
    case PlaneShape::Quad8:
      return {V(-1, -1), V(1, -1), V(1, 1), V(-1, 1), V(0, -1), V(1, 0), V(0, 1), V(-1, 0)};
    case PlaneShape::Tri3:
      return {V(0, 0), V(1, 0), V(0, 1)};
    case PlaneShape::Tri6:
      return {V(0, 0), V(1, 0), V(0, 1), V(0.5, 0), V(0.5, 0.5), V(0, 0.5)};
  }
  return {};
}

PlaneSolid::PlaneSolid(int id, const std::vector<int>& nodes, const std::vector<Vec3>& x,
                       const IsotropicElasticity& material, const PlaneSolidOptions& options,
                       std::vector<std::vector<int>> faces, const SourceLocation& where,
                       std::optional<J2Plasticity> plasticity)
    : Element(id),
      nodes_(nodes),
      x_(x),
      options_(options),
      faces_(std::move(faces)),
      plasticity_(std::move(plasticity)) {
  const PlaneShape shape = options.shape;
  const int nn = plane_shape_nodes(shape);
  IMPACTFE_CHECK(static_cast<int>(nodes.size()) == nn && static_cast<int>(x.size()) == nn,
                 "plane solid built with a wrong node count");
  IMPACTFE_CHECK(options.technology == PlaneTechnology::Standard || shape == PlaneShape::Quad4,
                 "B-bar and incompatible modes are formulations of the 4-node quadrilateral");
  IMPACTFE_CHECK(!options.large_deflection || options.technology == PlaneTechnology::Standard ||
                     options.technology == PlaneTechnology::BBar,
                 "large deflection is formulated for full integration and B-bar only");
  for (int a = 0; a < nn; ++a)
    for (int b = a + 1; b < nn; ++b)
      if (nodes[a] == nodes[b])
        throw InputError(where, fmt::format("element {}: node {} appears twice (positions {} and "
                                            "{}) in a shape that needs distinct nodes",
                                            id, nodes[a], a + 1, b + 1));
  for (int a = 0; a < nn; ++a) {
    if (std::abs(x[a](2) - x[0](2)) > 1e-9 * std::max(1.0, (x[a] - x[0]).norm()))
      throw InputError(where, fmt::format("element {}: node {} is not in the X-Y plane of node "
                                          "{} (a 2-D element lies in a plane Z = constant)",
                                          id, nodes[a], nodes[0]));
    if (options.behaviour == PlaneBehaviour::Axisymmetric && x[a](0) < 0.0)
      throw InputError(where, fmt::format("element {}: node {} at X = {:.6g} < 0: an "
                                          "axisymmetric element lies at X >= 0 (X is the radius)",
                                          id, nodes[a], x[a](0)));
  }
  for (int node : nodes)
    for (Dof dof : {Dof::UX, Dof::UY}) dofs_.push_back(DofKey{node, dof});
  d_ = plane_elasticity(material.young, material.poisson, options.behaviour);
  young_ = material.young;
  poisson_ = material.poisson;
  density_ = material.density;
  rule_ = stiffness_rule(shape, options.behaviour, options.technology);

  // The Jacobian keeps one sign over the element: checked at the corners and the stiffness
  // points (a misplaced midside node makes it change sign at a corner first).
  double size = 0.0;
  for (int a = 0; a < nn; ++a)
    for (int b = a + 1; b < nn; ++b) size = std::max(size, (x[a] - x[b]).norm());
  const double floor = 1e-10 * size * size;
  const Point c = point_at(centre(shape));
  orientation_ = c.det < 0.0 ? -1.0 : 1.0;
  det0_ = std::abs(c.det);
  j0_inverse_ = c.j_inverse;
  auto check = [&](const Eigen::Vector2d& xi, const std::string& what) {
    const double det = orientation_ * point_at(xi).det;
    if (!(det > floor))
      throw InputError(where, fmt::format("element {}: zero or inverted Jacobian ({:.6g}) at {} "
                                          "(check the node order and the midside node "
                                          "positions)",
                                          id, orientation_ * det, what));
  };
  const auto corners = plane_shape_nodes_xi(shape);
  for (int k = 0; k < (is_triangle(shape) ? 3 : 4); ++k)
    check(corners[k], fmt::format("corner node {}", nodes[k]));
  for (std::size_t p = 0; p < rule_.size(); ++p)
    check(rule_[p].xi.head<2>(), fmt::format("integration point {}", p + 1));
  volume_ = 0.0;
  for (const QuadraturePoint& q : mass_rule(shape)) {
    const Eigen::Vector2d xi = q.xi.head<2>();
    volume_ += measure(point_at(xi), q.weight);
  }
  form_stiffness();
  if (plasticity_) {
    committed_.resize(rule_.size());
    for (const QuadraturePoint& q : rule_)
      point_dv_.push_back(options.technology == PlaneTechnology::Reduced
                              ? volume_
                              : measure(point_at(q.xi.head<2>()), q.weight));
  }
  if (options.large_deflection) {
    finite_.resize(rule_.size());
    committed_u_ = Eigen::VectorXd::Zero(2 * nn);
  }
}

PlaneSolid::Point PlaneSolid::point_at(const Eigen::Vector2d& xi) const {
  Point p;
  Eigen::Matrix2Xd dn;
  plane_shape(options_.shape, xi, p.n, dn);
  Eigen::Matrix2d j = Eigen::Matrix2d::Zero();  // J(i, k) = ∂x_k/∂ξ_i
  p.radius = 0.0;
  for (int a = 0; a < static_cast<int>(dn.cols()); ++a) {
    const Vec3& xa = x_[static_cast<std::size_t>(a)];
    j += dn.col(a) * xa.head<2>().transpose();
    p.radius += p.n(a) * xa(0);
  }
  p.det = j.determinant();
  p.j_inverse = j.inverse();
  p.grad = p.j_inverse * dn;
  return p;
}

double PlaneSolid::measure(const Point& p, double w) const {
  const double area = w * std::abs(p.det);
  return options_.behaviour == PlaneBehaviour::Axisymmetric ? area * kTwoPi * p.radius
                                                            : area * options_.thickness;
}

Eigen::MatrixXd PlaneSolid::strain_matrix(const Point& p) const {
  const int nn = static_cast<int>(p.n.size());
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(4, 2 * nn);
  const bool axisymmetric = options_.behaviour == PlaneBehaviour::Axisymmetric;
  for (int a = 0; a < nn; ++a) {
    b(0, 2 * a) = p.grad(0, a);
    b(1, 2 * a + 1) = p.grad(1, a);
    if (axisymmetric) b(2, 2 * a) = p.n(a) / p.radius;  // hoop strain u_r / r
    b(3, 2 * a) = p.grad(1, a);
    b(3, 2 * a + 1) = p.grad(0, a);
  }
  return b;
}

Eigen::MatrixXd PlaneSolid::point_strain(const Point& p) const {
  return options_.technology == PlaneTechnology::Reduced ? mean_strain_ : strain_matrix(p);
}

Eigen::Matrix4d PlaneSolid::mode_matrix(const Point& p, const Eigen::Vector2d& xi) const {
  // Taylor, Beresford & Wilson (1976): the modes' natural gradients (−2ξ, 0) and (0, −2η)
  // mapped with the centre Jacobian and scaled by det J0 / det J, so that their integral over
  // the element vanishes (the patch test); in axisymmetry the r-weighted mean is removed too.
  const double scale = det0_ / std::abs(p.det);
  const Eigen::Vector2d g1 = scale * (j0_inverse_ * Eigen::Vector2d(-2.0 * xi(0), 0.0));
  const Eigen::Vector2d g2 = scale * (j0_inverse_ * Eigen::Vector2d(0.0, -2.0 * xi(1)));
  Eigen::Matrix4d g = Eigen::Matrix4d::Zero();
  int col = 0;
  for (const Eigen::Vector2d& gk : {g1, g2}) {
    g(0, col) = gk(0);  // ux mode: εxx, γxy
    g(3, col) = gk(1);
    g(1, col + 1) = gk(1);  // uy mode: εyy, γxy
    g(3, col + 1) = gk(0);
    col += 2;
  }
  return g;
}

void PlaneSolid::form_stiffness() {
  const int n = 2 * static_cast<int>(nodes_.size());
  const bool reduced = options_.technology == PlaneTechnology::Reduced;
  if (reduced) form_hourglass();
  std::vector<Point> points;
  std::vector<double> dv;
  double total = 0.0;
  for (const QuadraturePoint& q : rule_) {
    points.push_back(point_at(q.xi.head<2>()));
    // Reduced: the one point carries the whole (2x2-exact) volume with the mean strain B̄.
    dv.push_back(reduced ? volume_ : measure(points.back(), q.weight));
    total += dv.back();
  }
  std::vector<Eigen::MatrixXd> b;
  for (const Point& p : points) b.push_back(point_strain(p));
  const bool bbar = options_.technology == PlaneTechnology::BBar;
  const bool modes = options_.technology == PlaneTechnology::IncompatibleModes;
  if (bbar) {
    // Mean dilatation (Hughes 1980): θ̄ = ∫ θ dV / V replaces θ = εxx + εyy + εzz at every
    // point, ε̄ = ε + (θ̄ − θ)/3 (1, 1, 1, 0).
    mean_dilatation_ = Eigen::RowVectorXd::Zero(n);
    for (std::size_t q = 0; q < b.size(); ++q)
      mean_dilatation_ += dv[q] * b[q].topRows(3).colwise().sum();
    mean_dilatation_ /= total;
    for (auto& bq : b) {
      const Eigen::RowVectorXd shift = (mean_dilatation_ - bq.topRows(3).colwise().sum()) / 3.0;
      for (int r = 0; r < 3; ++r) bq.row(r) += shift;
    }
  }
  k_ = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t q = 0; q < b.size(); ++q) k_.noalias() += dv[q] * b[q].transpose() * d_ * b[q];
  if (modes) {
    std::vector<Eigen::Matrix4d> g;
    mean_modes_.setZero();
    for (std::size_t q = 0; q < points.size(); ++q) {
      g.push_back(mode_matrix(points[q], rule_[q].xi.head<2>()));
      mean_modes_ += dv[q] * g.back();
    }
    mean_modes_ /= total;
    Eigen::Matrix4d kaa = Eigen::Matrix4d::Zero();
    Eigen::MatrixXd kau = Eigen::MatrixXd::Zero(4, n);
    for (std::size_t q = 0; q < points.size(); ++q) {
      const Eigen::Matrix4d gq = g[q] - mean_modes_;
      kaa.noalias() += dv[q] * gq.transpose() * d_ * gq;
      kau.noalias() += dv[q] * gq.transpose() * d_ * b[q];
    }
    // Static condensation of the internal modes: K = Kuu − Kau' Kaa⁻¹ Kau, α = −Kaa⁻¹ Kau u.
    mode_recovery_ = kaa.ldlt().solve(kau);
    kaa_inverse_ = kaa.inverse();
    k_ -= kau.transpose() * mode_recovery_;
  }
  if (reduced) k_ += hourglass_;
  k_ = 0.5 * (k_ + k_.transpose()).eval();
}

void PlaneSolid::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                         Eigen::VectorXd& f_int) const {
  if (ctx.large_deflection != options_.large_deflection)
    throw ElementSolutionError(
        id(), fmt::format("element {}: PLANE182/PLANE183 built {} cannot be solved {}: large "
                          "deflection (NLGEOM) may not change within an analysis of the 2-D "
                          "solids",
                          id(), options_.large_deflection ? "with NLGEOM,ON" : "small-strain",
                          ctx.large_deflection ? "with NLGEOM,ON" : "small-strain"));
  if (ctx.large_deflection) {
    finite_tangent(u, K, f_int, true);
    return;
  }
  if (ctx.stress_stiffening)
    throw ElementSolutionError(
        id(), fmt::format("element {}: stress stiffening (SSTIF / PSTRES) without large "
                          "deflection is not implemented for the 2-D solids",
                          id()));
  if (plasticity_) {
    tangent_plastic(u, K, f_int, nullptr, nullptr);
    return;
  }
  K = k_;
  f_int = K * u;
}

void PlaneSolid::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const int nn = static_cast<int>(nodes_.size());
  Eigen::MatrixXd ms = Eigen::MatrixXd::Zero(nn, nn);
  for (const QuadraturePoint& q : mass_rule(options_.shape)) {
    const Point p = point_at(q.xi.head<2>());
    ms.noalias() += (density_ * measure(p, q.weight)) * (p.n * p.n.transpose());
  }
  if (ctx.lumped_mass) {
    // Row sums for the 4-node shapes (positive); HRZ (Hinton, Rock & Zienkiewicz 1976) for the
    // quadratic ones, whose row sums are zero or negative at the corners.
    Eigen::VectorXd lumped = ms.rowwise().sum();
    if (is_quadratic(options_.shape)) {
      const Eigen::VectorXd diag = ms.diagonal();
      lumped = diag.sum() > 0.0 ? Eigen::VectorXd(diag * (ms.sum() / diag.sum())) : diag;
    }
    ms = lumped.asDiagonal();
  }
  M.setZero(2 * nn, 2 * nn);
  for (int a = 0; a < nn; ++a)
    for (int b = 0; b < nn; ++b)
      for (int i = 0; i < 2; ++i) M(2 * a + i, 2 * b + i) = ms(a, b);
}

void PlaneSolid::acceleration_field_load(const ElementContext& ctx,
                                         const std::vector<LinearAccelerationField>& fields,
                                         const std::function<Vec3(int)>& position,
                                         Eigen::MatrixXd& f) const {
  if (options_.behaviour == PlaneBehaviour::Axisymmetric)
    require_axisymmetric_fields(*this, fields);
  Element::acceleration_field_load(ctx, fields, position, f);
}

void PlaneSolid::pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                               const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  if (face < 1 || face > static_cast<int>(faces_.size()))
    throw ModelError(
        fmt::format("element {}: face {} does not exist (1..{})", id(), face, faces_.size()));
  // Under large deflection the pressure follows the edge deformed by u (no load stiffness).
  const bool follow = ctx.large_deflection && u.size() == n_dofs();
  f.setZero(n_dofs());
  const std::vector<int>& edge = faces_[static_cast<std::size_t>(face - 1)];
  if (edge.empty()) return;  // a face collapsed to a node carries no load
  const bool quadratic = edge.size() == 3;
  // 3 Gauss points: exact for a straight edge with linear pressure, also with the radius.
  const double gauss_s[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gauss_w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (int q = 0; q < 3; ++q) {
    const double s = gauss_s[q];
    Eigen::VectorXd n(edge.size()), dn(edge.size());
    if (quadratic) {
      n << 0.5 * s * (s - 1), 0.5 * s * (s + 1), 1 - s * s;
      dn << s - 0.5, s + 0.5, -2 * s;
    } else {
      n << 0.5 * (1 - s), 0.5 * (1 + s);
      dn << -0.5, 0.5;
    }
    Eigen::Vector2d xs = Eigen::Vector2d::Zero(), dxs = Eigen::Vector2d::Zero();
    for (std::size_t a = 0; a < edge.size(); ++a) {
      Eigen::Vector2d xa = x_[static_cast<std::size_t>(edge[a])].head<2>();
      if (follow) xa += u.segment<2>(2 * edge[a]);
      xs += n(static_cast<int>(a)) * xa;
      dxs += dn(static_cast<int>(a)) * xa;
    }
    // The faces run clockwise around a counter-clockwise element (J-I, K-J, L-K, I-L): the
    // outward normal of the tangent (tx, ty) is (−ty, tx) there.
    const Eigen::Vector2d normal = orientation_ * Eigen::Vector2d(-dxs(1), dxs(0));
    const double pressure = 0.5 * (1 - s) * p[0] + 0.5 * (1 + s) * p[1];
    const double factor =
        options_.behaviour == PlaneBehaviour::Axisymmetric ? kTwoPi * xs(0) : options_.thickness;
    const Eigen::Vector2d load = -gauss_w[q] * pressure * factor * normal;
    for (std::size_t a = 0; a < edge.size(); ++a)
      f.segment<2>(2 * edge[a]) += n(static_cast<int>(a)) * load;
  }
}

Eigen::Vector4d PlaneSolid::centroid_stress(const Eigen::VectorXd& u) const {
  const Point p = point_at(centre(options_.shape));
  Eigen::MatrixXd b = point_strain(p);
  if (options_.technology == PlaneTechnology::BBar) {
    const Eigen::RowVectorXd shift = (mean_dilatation_ - b.topRows(3).colwise().sum()) / 3.0;
    for (int r = 0; r < 3; ++r) b.row(r) += shift;
  }
  Eigen::Vector4d strain = b * u;
  if (options_.technology == PlaneTechnology::IncompatibleModes)
    strain += (mode_matrix(p, centre(options_.shape)) - mean_modes_) * mode_amplitudes(u);
  return d_ * (strain - thermal_strain(p));
}

Eigen::Vector4d PlaneSolid::thermal_strain(const Point& p) const {
  const std::vector<double>& dT = temperature_change();
  const ThermalExpansion& te = thermal_expansion();
  if (dT.empty() || !te.expands()) return Eigen::Vector4d::Zero();
  double t = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    for (std::size_t j = 0; j < te.nodes.size() && j < dT.size(); ++j)
      if (te.nodes[j] == nodes_[k]) {
        t += p.n(static_cast<Eigen::Index>(k)) * dT[j];
        break;
      }
  // Plane stress: D has no zz row or column, so αz ΔT drops out as σzz = 0 requires.
  return Eigen::Vector4d(te.alpha.x() * t, te.alpha.y() * t, te.alpha.z() * t, 0.0);
}

void PlaneSolid::thermal_sums(Eigen::VectorXd& f_u, Eigen::Vector4d& f_a) const {
  const bool reduced = options_.technology == PlaneTechnology::Reduced;
  const bool modes = options_.technology == PlaneTechnology::IncompatibleModes;
  f_u = Eigen::VectorXd::Zero(2 * static_cast<Eigen::Index>(nodes_.size()));
  f_a.setZero();
  for (const QuadraturePoint& q : rule_) {
    const Point p = point_at(q.xi.head<2>());
    const double dv = reduced ? volume_ : measure(p, q.weight);
    Eigen::MatrixXd b = point_strain(p);
    if (options_.technology == PlaneTechnology::BBar) {
      const Eigen::RowVectorXd shift = (mean_dilatation_ - b.topRows(3).colwise().sum()) / 3.0;
      for (int r = 0; r < 3; ++r) b.row(r) += shift;
    }
    const Eigen::Vector4d s = d_ * thermal_strain(p);
    f_u.noalias() += dv * (b.transpose() * s);
    if (modes)
      f_a.noalias() += dv * ((mode_matrix(p, q.xi.head<2>()) - mean_modes_).transpose() * s);
  }
}

Eigen::Vector4d PlaneSolid::mode_amplitudes(const Eigen::VectorXd& u) const {
  Eigen::Vector4d alpha = -(mode_recovery_ * u);
  if (!temperature_change().empty() && thermal_expansion().expands()) {
    Eigen::VectorXd f_u;
    Eigen::Vector4d f_a;
    thermal_sums(f_u, f_a);
    alpha += kaa_inverse_ * f_a;
  }
  return alpha;
}

void PlaneSolid::thermal_load(const ElementContext&, Eigen::VectorXd& f) const {
  if (plasticity_ || options_.large_deflection)
    throw NotImplementedError(fmt::format(
        "element {} ({}): thermal strain is implemented for the elastic small-strain 2-D solids; "
        "this one is {}",
        id(), family(), plasticity_ ? "plastic (TB)" : "under large deflection (NLGEOM,ON)"));
  Eigen::Vector4d f_a;
  thermal_sums(f, f_a);
  // Static condensation of the modes: (K_uu − K_ua K_aa⁻¹ K_au) u = f_u − Rᵀ f_a, R = K_aa⁻¹ K_au.
  if (options_.technology == PlaneTechnology::IncompatibleModes)
    f.noalias() -= mode_recovery_.transpose() * f_a;
}

const std::vector<std::string>& plane_solid_result_names() {
  // A function-local static: the registrations read it during static initialisation.
  static const std::vector<std::string> names = {
      "SX",    "SY",    "SZ",     "SXY",     "S1",   "S2",    "S3",    "SINT",  "SEQV",
      "EPPLX", "EPPLY", "EPPLZ",  "EPPLXY",  "EPEQ", "SEPL",  "SRAT",  "PLWK",  "EPCRX",
      "EPCRY", "EPCRZ", "EPCRXY", "EPCREQV", "CREQ", "EPELX", "EPELY", "EPELZ", "EPELXY"};
  static const std::vector<std::string> with_nodes = [] {
    std::vector<std::string> all = names;
    for (int k = 1; k <= kPlaneMaxNodes; ++k)
      for (const char* item : {"SX", "SY", "SZ", "SXY", "EPELX", "EPELY", "EPELZ", "EPELXY"})
        all.push_back(fmt::format("{}@{}", item, k));
    return all;
  }();
  return with_nodes;
}

const std::vector<std::string>& PlaneSolid::result_names() const {
  return plane_solid_result_names();
}

/// SX SY SZ SXY S1 S2 S3 SINT SEQV of a stress (xx, yy, zz, xy), the inelastic items 0.
ElementResultValues plane_stress_items(const Eigen::Vector4d& s) {
  // In-plane principal stresses and SZ, ordered S1 >= S2 >= S3.
  const double mean = 0.5 * (s(0) + s(1));
  const double radius = std::hypot(0.5 * (s(0) - s(1)), s(3));
  std::array<double, 3> pr = {mean + radius, mean - radius, s(2)};
  std::sort(pr.begin(), pr.end(), std::greater<double>());
  const double s1 = pr[0], s2 = pr[1], s3 = pr[2];
  const double seqv =
      std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  ElementResultValues out = {s(0), s(1), s(2), s(3), s1, s2, s3, s1 - s3, seqv};
  out.resize(plane_solid_result_names().size(), 0.0);
  return out;
}

void PlaneSolid::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                         const Eigen::VectorXd& v, ElementResultValues& out) const {
  if (options_.large_deflection && ctx.large_deflection) {
    finite_results(u, out);
  } else {
    if (plasticity_ && !ctx.stress_stiffening) {
      plastic_results(u, out);
    } else {
      out = plane_stress_items(centroid_stress(u));
    }
    // EPEL: the elastic strain of the reported stress (isotropic law).
    const Eigen::Vector4d s(out[0], out[1], out[2], out[3]);
    const Eigen::Vector4d epel = elastic_strain(s);
    std::copy(epel.data(), epel.data() + 4, out.begin() + 23);
  }
  // The element nodal values (ESOL,,ELEM,NODE): stored here, in the solution, because those of
  // a plastic element come from its committed states, which a rebuilt element lacks.
  const std::size_t first = plane_solid_result_names().size() - kPlaneNodalItems * kPlaneMaxNodes;
  out.resize(plane_solid_result_names().size(), 0.0);
  const std::vector<Eigen::Vector4d> at_nodes = element_nodal_stresses(ctx, u);
  // Slot k + 1 is the node's position in the element's node list as E gives it: the 6-node
  // triangle is I J K K L M K N there (the quadrilateral form), its nodes I J K L M N here.
  static constexpr std::array<std::size_t, 6> kTri6Slot = {0, 1, 2, 4, 5, 7};
  for (std::size_t k = 0; k < at_nodes.size(); ++k) {
    const Eigen::Vector4d epel = elastic_strain(at_nodes[k]);
    const std::size_t slot = options_.shape == PlaneShape::Tri6 ? kTri6Slot[k] : k;
    const auto at = out.begin() + static_cast<std::ptrdiff_t>(first + kPlaneNodalItems * slot);
    std::copy(at_nodes[k].data(), at_nodes[k].data() + 4, at);
    std::copy(epel.data(), epel.data() + 4, at + 4);
  }
}

void PlaneSolid::point_stresses(const ElementContext& ctx, const Eigen::VectorXd& u,
                                std::vector<Eigen::Vector4d>& sigma, bool& inelastic) const {
  sigma.clear();
  inelastic = false;
  if (options_.large_deflection && ctx.large_deflection) {
    finite_point_stresses(u, sigma, inelastic);
    return;
  }
  if (plasticity_ && !ctx.stress_stiffening) {
    if (plasticity_->has_creep()) {
      // As plastic_results(): the committed states are those at the converged u.
      for (const PlasticState& st : committed_) {
        sigma.emplace_back(st.stress.head<4>());
        inelastic = inelastic || st.alpha > 0.0;
      }
      return;
    }
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    PointStates at = committed_;
    tangent_plastic(u, k, f, &at, &sigma);
    for (const PlasticState& st : at) inelastic = inelastic || st.alpha > 0.0;
    return;
  }
  Eigen::Vector4d alpha = Eigen::Vector4d::Zero();
  if (options_.technology == PlaneTechnology::IncompatibleModes) alpha = mode_amplitudes(u);
  for (const QuadraturePoint& q : rule_) {
    const Eigen::Vector2d xi = q.xi.head<2>();
    const Point p = point_at(xi);
    Eigen::MatrixXd b = point_strain(p);
    if (options_.technology == PlaneTechnology::BBar) {
      const Eigen::RowVectorXd shift = (mean_dilatation_ - b.topRows(3).colwise().sum()) / 3.0;
      for (int r = 0; r < 3; ++r) b.row(r) += shift;
    }
    Eigen::Vector4d strain = b * u;
    if (options_.technology == PlaneTechnology::IncompatibleModes)
      strain += (mode_matrix(p, xi) - mean_modes_) * alpha;
    sigma.push_back(d_ * (strain - thermal_strain(p)));
  }
}

std::vector<Eigen::Vector4d> PlaneSolid::extrapolate_to_nodes(
    const std::vector<Eigen::Vector4d>& sigma) const {
  // The lowest polynomial through the point values (bilinear through the 2x2 points of the
  // quadrilaterals, linear through the 3 points of the triangles, constant at the one point of
  // the plane triangle) evaluated at the nodes: the extrapolation of integration-point stresses
  // to the nodes (Cook et al. §6.13). Midside nodes get the polynomial's value there, the mean
  // of their corners' values.
  const int np = static_cast<int>(rule_.size());
  auto basis = [&](const Eigen::Vector2d& xi) {
    Eigen::VectorXd f(np);
    if (np == 4) f << 1, xi(0), xi(1), xi(0) * xi(1);
    if (np == 3) f << 1, xi(0), xi(1);
    if (np == 1) f << 1;
    return f;
  };
  Eigen::MatrixXd a(np, np), values(np, 4);
  for (int q = 0; q < np; ++q) {
    a.row(q) = basis(rule_[static_cast<std::size_t>(q)].xi.head<2>()).transpose();
    values.row(q) = sigma[static_cast<std::size_t>(q)].transpose();
  }
  const Eigen::MatrixXd coefficients = a.partialPivLu().solve(values);
  const auto xi_nodes = plane_shape_nodes_xi(options_.shape);
  std::vector<Eigen::Vector4d> out;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    out.emplace_back((basis(xi_nodes[k]).transpose() * coefficients).transpose());
  return out;
}

std::vector<Eigen::Vector4d> PlaneSolid::element_nodal_stresses(const ElementContext& ctx,
                                                                const Eigen::VectorXd& u) const {
  std::vector<Eigen::Vector4d> sigma;
  bool inelastic = false;
  point_stresses(ctx, u, sigma, inelastic);
  // ERESX default (MAPDL command reference, ERESX): "If any portion of the element is plastic
  // (or other active material nonlinearity), copy the integration point results to the nodes";
  // ERESX,YES copies always, ERESX,NO extrapolates always.
  const NodalStressRule rule = options_.nodal_stresses;
  const bool copy =
      rule == NodalStressRule::Copy || (rule == NodalStressRule::Default && inelastic);
  return copy ? copy_to_nodes(sigma) : extrapolate_to_nodes(sigma);
}

std::vector<Eigen::Vector4d> PlaneSolid::copy_to_nodes(
    const std::vector<Eigen::Vector4d>& sigma) const {
  // Each node takes the value of its nearest stiffness point in natural coordinates; a node
  // equally near several (midside nodes) takes their mean.
  const auto xi_nodes = plane_shape_nodes_xi(options_.shape);
  std::vector<Eigen::Vector4d> out;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const QuadraturePoint& q : rule_)
      nearest = std::min(nearest, (q.xi.head<2>() - xi_nodes[k]).squaredNorm());
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    int count = 0;
    for (std::size_t q = 0; q < rule_.size(); ++q)
      if ((rule_[q].xi.head<2>() - xi_nodes[k]).squaredNorm() <= nearest + 1e-9) {
        sum += sigma[q];
        ++count;
      }
    out.emplace_back(sum / count);
  }
  return out;
}

bool PlaneSolid::nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                               std::map<int, ElementResultValues>& at_node) const {
  // The elastic element only: a rebuilt plastic element has no history (its element values
  // stand for its nodes in PRNSOL; ESOL with a NODE reads the values stored in the solution).
  if (plasticity_ || options_.large_deflection) return false;
  std::vector<Eigen::Vector4d> sigma;
  bool inelastic = false;
  point_stresses(ctx, u, sigma, inelastic);
  const std::vector<Eigen::Vector4d> s = options_.nodal_stresses == NodalStressRule::Copy
                                             ? copy_to_nodes(sigma)
                                             : extrapolate_to_nodes(sigma);
  at_node.clear();
  for (std::size_t k = 0; k < nodes_.size(); ++k) at_node[nodes_[k]] = plane_stress_items(s[k]);
  return true;
}

}  // namespace impactfe
