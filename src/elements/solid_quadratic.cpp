#include "elements/solid_quadratic.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/brick8.h"

namespace impactfe {

namespace {

Eigen::Matrix3d voigt_to_tensor(const Vector6d& s) {
  Eigen::Matrix3d t;
  t << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
  return t;
}

/// Small-strain B (Bathe 5.3, engineering shear; Voigt xx yy zz xy yz xz) of ∂N/∂x.
Eigen::MatrixXd strain_matrix(const Eigen::Matrix3Xd& grad) {
  const int nn = static_cast<int>(grad.cols());
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(6, 3 * nn);
  for (int a = 0; a < nn; ++a) {
    const double g0 = grad(0, a), g1 = grad(1, a), g2 = grad(2, a);
    b(0, 3 * a) = g0;
    b(1, 3 * a + 1) = g1;
    b(2, 3 * a + 2) = g2;
    b(3, 3 * a) = g1;
    b(3, 3 * a + 1) = g0;
    b(4, 3 * a + 1) = g2;
    b(4, 3 * a + 2) = g1;
    b(5, 3 * a) = g2;
    b(5, 3 * a + 2) = g0;
  }
  return b;
}

/// The points of the consistent mass: NᵀN is of degree 4 per coordinate on the brick (3x3x3 is
/// exact for a parallelepiped) and of degree 4 on the tetrahedron (conical product, degree 5).
std::vector<QuadraturePoint> mass_rule(QuadraticShape shape) {
  return shape == QuadraticShape::Hex20 ? gauss_cube(3) : collapsed_tetrahedron(4);
}

}  // namespace

QuadraticSolid::QuadraticSolid(int id, QuadraticShape shape, const std::vector<int>& nodes,
                               const std::vector<Vec3>& x, const IsotropicElasticity& material,
                               std::vector<QuadraturePoint> stiffness_rule,
                               std::vector<std::vector<int>> faces, const SourceLocation& where,
                               std::optional<J2Plasticity> plasticity, bool large_deflection)
    : Element(id),
      shape_(shape),
      nodes_(nodes),
      x_(x),
      rule_(std::move(stiffness_rule)),
      faces_(std::move(faces)),
      plasticity_(std::move(plasticity)) {
  const int nn = quadratic_shape_nodes(shape);
  IMPACTFE_CHECK(static_cast<int>(nodes.size()) == nn && static_cast<int>(x.size()) == nn,
                 "quadratic solid built with a wrong node count");
  for (int a = 0; a < nn; ++a)
    for (int b = a + 1; b < nn; ++b)
      if (nodes[a] == nodes[b])
        throw InputError(where, fmt::format("element {}: node {} appears twice (positions {} and "
                                            "{}); a quadratic solid needs distinct nodes",
                                            id, nodes[a], a + 1, b + 1));
  for (int node : nodes)
    for (Dof dof : {Dof::UX, Dof::UY, Dof::UZ}) dofs_.push_back(DofKey{node, dof});
  d_ = isotropic_elasticity_matrix(material.young, material.poisson);
  density_ = material.density;

  // A determinant below 1e-10 of (size/2)³ (size: largest node distance; ×6 for the unit
  // tetrahedron's volume 1/6) is "zero". Checked at every integration point and every corner:
  // a misplaced midside node makes the Jacobian change sign at a corner first.
  double size = 0.0;
  for (int a = 0; a < nn; ++a)
    for (int b = a + 1; b < nn; ++b) size = std::max(size, (x[a] - x[b]).norm());
  const double det_floor = 1e-10 * std::pow(0.5 * size, 3);
  auto check = [&](const Eigen::Vector3d& xi, const std::string& what) {
    const double det = point_at(xi).det;
    if (!(det > det_floor))
      throw InputError(where, fmt::format("element {}: zero or negative Jacobian determinant "
                                          "{:.6g} at {} (check the node order and the midside "
                                          "node positions)",
                                          id, det, what));
  };
  const auto nodes_xi = quadratic_shape_nodes_xi(shape);
  const int corners = shape == QuadraticShape::Hex20 ? 8 : 4;
  for (int c = 0; c < corners; ++c) check(nodes_xi[c], fmt::format("corner node {}", c + 1));
  for (std::size_t p = 0; p < rule_.size(); ++p)
    check(rule_[p].xi, fmt::format("integration point {}", p + 1));
  volume_ = 0.0;
  for (const QuadraturePoint& q : mass_rule(shape)) volume_ += q.weight * point_at(q.xi).det;
  if (plasticity_) committed_.resize(rule_.size());
  if (large_deflection) {
    IMPACTFE_CHECK(!plasticity_ || !plasticity_->has_creep(),
                   "quadratic solid: creep under large deflection");
    for (const QuadraturePoint& q : rule_) {
      const Point p = point_at(q.xi);
      finite_points_.push_back(FiniteStrainPoint{p.grad, q.weight * p.det});
    }
    finite_.resize(rule_.size());
    committed_u_.setZero(3, nn);
  }
}

QuadraticSolid::Point QuadraticSolid::point_at(const Eigen::Vector3d& xi) const {
  Point p;
  Eigen::Matrix3Xd dn;
  quadratic_shape(shape_, xi, p.n, dn);
  // J(i, j) = ∂x_j/∂ξ_i (Bathe's convention: ∂/∂x = J⁻¹ ∂/∂ξ).
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int a = 0; a < static_cast<int>(dn.cols()); ++a)
    j += dn.col(a) * x_[static_cast<std::size_t>(a)].transpose();
  p.det = j.determinant();
  p.grad = j.inverse() * dn;
  return p;
}

Eigen::MatrixXd QuadraticSolid::small_strain_stiffness() const {
  const int n = n_dofs();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (const QuadraturePoint& q : rule_) {
    const Point p = point_at(q.xi);
    const Eigen::MatrixXd b = strain_matrix(p.grad);
    k.noalias() += (q.weight * p.det) * (b.transpose() * d_ * b);
  }
  return 0.5 * (k + k.transpose());
}

void QuadraticSolid::tangent(const ElementContext& ctx, const Eigen::VectorXd& u,
                             Eigen::MatrixXd& K, Eigen::VectorXd& f_int) const {
  if (ctx.large_deflection != finite_strain())
    throw ElementSolutionError(
        id(), fmt::format("element {}: SOLID186/SOLID187 built {} cannot be solved {}: large "
                          "deflection (NLGEOM) may not change within an analysis of the "
                          "quadratic solids",
                          id(), finite_strain() ? "with NLGEOM,ON" : "small-strain",
                          ctx.large_deflection ? "with NLGEOM,ON" : "small-strain"));
  if (ctx.large_deflection) {
    // Updated Lagrangian: the symmetric tangent includes the initial-stress stiffness.
    finite_tangent(u, K, f_int, true);
    return;
  }
  if (plasticity_) {
    if (ctx.stress_stiffening)
      throw ElementSolutionError(
          id(), fmt::format("element {}: stress stiffening with a TB plasticity material is not "
                            "implemented for SOLID186/SOLID187",
                            id()));
    plastic_sum(u, K, f_int, nullptr);
    return;
  }
  K = small_strain_stiffness();
  if (ctx.stress_stiffening) {
    // K_σ = ∫ Gᵀ σ G dV per direction with σ the small-strain stress of u at the stiffness
    // points (Bathe 6.3.2, the linearised updated-Lagrangian term), so that the converged
    // state solves (K + K_σ(u)) u = F as ANSYS SSTIF does.
    const int nn = static_cast<int>(nodes_.size());
    Eigen::MatrixXd ks = Eigen::MatrixXd::Zero(nn, nn);
    for (const QuadraturePoint& q : rule_) {
      const Point p = point_at(q.xi);
      const Vector6d sigma = d_ * (strain_matrix(p.grad) * u);
      ks.noalias() += (q.weight * p.det) * (p.grad.transpose() * voigt_to_tensor(sigma) * p.grad);
    }
    for (int a = 0; a < nn; ++a)
      for (int c = 0; c < nn; ++c)
        for (int i = 0; i < 3; ++i) K(3 * a + i, 3 * c + i) += ks(a, c);
  }
  f_int = K * u;
}

Eigen::MatrixXd QuadraticSolid::scalar_mass() const {
  const int nn = static_cast<int>(nodes_.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nn, nn);
  for (const QuadraturePoint& q : mass_rule(shape_)) {
    const Point p = point_at(q.xi);
    m.noalias() += (density_ * q.weight * p.det) * (p.n * p.n.transpose());
  }
  return m;
}

void QuadraticSolid::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  Eigen::MatrixXd ms = scalar_mass();
  if (ctx.lumped_mass) {
    // HRZ: the consistent diagonal scaled to the element mass ρV. Row sums would give the
    // corners of the 20-node brick and the 10-node tetrahedron negative masses.
    const Eigen::VectorXd diag = ms.diagonal();
    const double sum = diag.sum();
    ms.setZero();
    if (sum > 0.0) ms.diagonal() = diag * (density_ * volume_ / sum);
  }
  const int nn = static_cast<int>(nodes_.size());
  M.setZero(3 * nn, 3 * nn);
  for (int a = 0; a < nn; ++a)
    for (int b = 0; b < nn; ++b)
      for (int i = 0; i < 3; ++i) M(3 * a + i, 3 * b + i) = ms(a, b);
}

void QuadraticSolid::pressure_load(const ElementContext& ctx, int face,
                                   const std::array<double, 4>& p, const Eigen::VectorXd& u,
                                   Eigen::VectorXd& f) const {
  if (face < 1 || face > static_cast<int>(faces_.size()))
    throw ModelError(
        fmt::format("element {}: face {} does not exist (1..{})", id(), face, faces_.size()));
  if (ctx.large_deflection)
    throw ElementSolutionError(
        id(), fmt::format("element {}: pressure on a quadratic solid under large deflection "
                          "(follower load) is not implemented",
                          id()));
  f.setZero(n_dofs());
  const std::vector<int>& nodes = faces_[static_cast<std::size_t>(face - 1)];
  if (nodes.empty()) return;  // a face collapsed to an edge (degenerate SOLID186) carries none
  const int fn = static_cast<int>(nodes.size());
  // 3x3 Gauss on the quadrilateral, the degree-4 collapsed rule on the triangle: exact for a
  // flat face with (bi)linear pressure (the integrand N p (∂x/∂ξ × ∂x/∂η) is then of degree 4).
  const std::vector<QuadraturePoint> rule = fn == 8 ? gauss_square(3) : collapsed_triangle(3);
  Eigen::VectorXd n, corner;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dn;
  for (const QuadraturePoint& q : rule) {
    quadratic_face_shape(fn, q.xi, n, dn, corner);
    Vec3 dxi = Vec3::Zero(), deta = Vec3::Zero();
    for (int a = 0; a < fn; ++a) {
      const Vec3& xa = x_[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a)])];
      dxi += dn(0, a) * xa;
      deta += dn(1, a) * xa;
    }
    double pressure = 0.0;
    for (int c = 0; c < static_cast<int>(corner.size()); ++c)
      pressure += corner(c) * p[static_cast<std::size_t>(c)];
    // The corner order makes ∂x/∂ξ × ∂x/∂η point outward; positive pressure pushes inward.
    const Vec3 load = -q.weight * pressure * dxi.cross(deta);
    for (int a = 0; a < fn; ++a)
      f.segment<3>(3 * nodes[static_cast<std::size_t>(a)]) += n(a) * load;
  }
}

Vector6d QuadraticSolid::stress_at(const Eigen::Vector3d& xi, const Eigen::VectorXd& u) const {
  return d_ * (strain_matrix(point_at(xi).grad) * u);
}

const std::vector<std::string>& quadratic_solid_result_names() {
  return brick8_result_names();  // the same items as SOLID185
}

const std::vector<std::string>& QuadraticSolid::result_names() const {
  return quadratic_solid_result_names();
}

void QuadraticSolid::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& v, ElementResultValues& out) const {
  if (finite_strain() && ctx.large_deflection) {
    finite_results(u, out);
    return;
  }
  if (plasticity_ && !ctx.stress_stiffening && !ctx.large_deflection) {
    plastic_results(u, out);
    return;
  }
  out = solid_stress_row(stress_at(quadratic_shape_centre(shape_), u));  // plastic items 0
}

bool QuadraticSolid::nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                                   std::map<int, ElementResultValues>& at_node) const {
  if (plasticity_ || finite_strain() || ctx.large_deflection) return false;
  const bool brick = shape_ == QuadraticShape::Hex20;
  const int nb = brick ? 8 : 4;
  auto basis = [&](const Eigen::Vector3d& xi) {
    Eigen::VectorXd f(nb);
    if (brick)
      f << 1, xi(0), xi(1), xi(2), xi(0) * xi(1), xi(1) * xi(2), xi(0) * xi(2),
          xi(0) * xi(1) * xi(2);
    else
      f << 1, xi(0), xi(1), xi(2);
    return f;
  };
  const int np = static_cast<int>(rule_.size());
  Eigen::MatrixXd a(np, nb), values(np, 6);
  for (int q = 0; q < np; ++q) {
    const Eigen::Vector3d& xi = rule_[static_cast<std::size_t>(q)].xi;
    a.row(q) = basis(xi).transpose();
    values.row(q) = stress_at(xi, u).transpose();
  }
  // Exact through 8 (2x2x2) or 4 points; least squares through 27.
  const Eigen::MatrixXd coefficients = a.colPivHouseholderQr().solve(values);
  const std::vector<Eigen::Vector3d> xi_nodes = quadratic_shape_nodes_xi(shape_);
  at_node.clear();
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Vector6d s = (basis(xi_nodes[k]).transpose() * coefficients).transpose();
    at_node[nodes_[k]] = solid_stress_row(s);
  }
  return true;
}

// ---- plasticity ----------------------------------------------------------------------------

void QuadraticSolid::plastic_sum(const Eigen::VectorXd& u, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                                 std::vector<PlasticState>* updated) const {
  // The 3-D return (J2Plasticity::solid) at every stiffness point from its committed state;
  // K = ∫BᵀC_alg B dV with the consistent tangent, so the global Newton converges quadratically.
  const int n = n_dofs();
  k.setZero(n, n);
  f.setZero(n);
  for (std::size_t q = 0; q < rule_.size(); ++q) {
    const Point p = point_at(rule_[q].xi);
    const Eigen::MatrixXd b = strain_matrix(p.grad);
    const double dv = rule_[q].weight * p.det;
    const PlasticResponse r =
        plasticity_->solid(committed_[q], b * u, updated ? &(*updated)[q] : nullptr);
    f.noalias() += dv * (b.transpose() * r.stress);
    k.noalias() += dv * (b.transpose() * r.tangent * b);
  }
  k = 0.5 * (k + k.transpose()).eval();
}

void QuadraticSolid::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (finite_strain() && ctx.large_deflection) {
    FiniteStrainUpdate at;
    Eigen::VectorXd f;
    finite_sum(u, nullptr, f, &at);
    finite_ = at.states;
    if (plasticity_)
      for (std::size_t p = 0; p < finite_.size(); ++p) committed_[p] = finite_[p].plastic;
    committed_u_ = Eigen::Map<const Eigen::Matrix3Xd>(u.data(), 3, u.size() / 3);
    return;
  }
  if (!plasticity_) return;
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  std::vector<PlasticState> next = committed_;
  plastic_sum(u, k, f, &next);
  committed_ = next;
}

std::vector<double> QuadraticSolid::history_state() const {
  std::vector<double> out;
  for (const PlasticState& s : committed_) append_state(out, s);  // per stiffness point
  // Large deflection: the accumulated strains, then the committed displacement.
  for (const FiniteStrainState& s : finite_)
    out.insert(out.end(), s.strain.data(), s.strain.data() + 6);
  out.insert(out.end(), committed_u_.data(), committed_u_.data() + committed_u_.size());
  return out;
}

void QuadraticSolid::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  for (PlasticState& s : committed_) read_state(state, pos, s);
  const std::size_t finite = 6 * finite_.size() + static_cast<std::size_t>(committed_u_.size());
  IMPACTFE_CHECK(pos + finite == state.size(), "SOLID186/187: saved state of the wrong length");
  for (std::size_t p = 0; p < finite_.size(); ++p) {
    for (int i = 0; i < 6; ++i) finite_[p].strain(i) = state[pos++];
    if (plasticity_) finite_[p].plastic = committed_[p];
  }
  for (Eigen::Index i = 0; i < committed_u_.size(); ++i) committed_u_.data()[i] = state[pos++];
}

double QuadraticSolid::plastic_work() const {
  double w = 0.0;
  for (std::size_t q = 0; q < committed_.size(); ++q)
    w += committed_[q].plastic_work * rule_[q].weight * point_at(rule_[q].xi).det;
  return w;
}

void QuadraticSolid::plastic_results(const Eigen::VectorXd& u, ElementResultValues& out) const {
  // The states at u (the committed ones after a converged step), averaged over the volume of
  // the stiffness rule.
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  std::vector<PlasticState> at = committed_;
  // A creep return at u would add the creep of the clock's substep once more: the committed
  // states are those at the converged u (results are taken after Element::commit_history).
  if (!plasticity_->has_creep()) plastic_sum(u, k, f, &at);
  Vector6d s = Vector6d::Zero(), eppl = Vector6d::Zero();
  double epeq = 0.0, plwk = 0.0, srat = 0.0, total = 0.0;
  const bool creep = plasticity_->has_creep();  // no yield surface: SEPL, SRAT 0
  for (std::size_t q = 0; q < rule_.size(); ++q) {
    const double dv = rule_[q].weight * point_at(rule_[q].xi).det;
    const PlasticState& st = at[q];
    total += dv;
    s += dv * st.stress;
    eppl += dv * st.plastic_strain;
    epeq += dv * st.alpha;
    plwk += dv * st.plastic_work;
    if (!creep)
      srat = std::max(srat,
                      von_mises(st.stress - st.back_stress) / plasticity_->flow_stress(st.alpha));
  }
  s /= total;
  eppl /= total;
  epeq /= total;
  plwk /= total;
  out = solid_stress_row(s);
  if (creep) {
    // A creep law (no yield surface): EPCR X..XZ, EQV = √(2/3 ε:ε) of the (deviatoric) creep
    // strain with the engineering shears halved, NL CREQ the accumulated equivalent creep
    // strain; the plastic items stay 0 as MAPDL separates them. PLWK: the creep work.
    const double eqv =
        std::sqrt(2.0 / 3.0 * (eppl.head<3>().squaredNorm() + 0.5 * eppl.tail<3>().squaredNorm()));
    for (int c = 0; c < 6; ++c) out[static_cast<std::size_t>(21 + c)] = eppl(c);
    out[27] = eqv;
    out[28] = epeq;
    out[20] = plwk;
    return;
  }
  const double plastic[10] = {eppl(0), eppl(1), eppl(2), eppl(3),
                              eppl(4), eppl(5), epeq,    plasticity_->flow_stress(epeq),
                              srat,    plwk};
  std::copy(plastic, plastic + 10, out.begin() + 11);
}

// ---- large deflection (solid_finite_strain.h) ------------------------------------------------

void QuadraticSolid::finite_sum(const Eigen::VectorXd& u, Eigen::MatrixXd* k, Eigen::VectorXd& f,
                                FiniteStrainUpdate* update, FiniteStrainTangent form) const {
  FiniteStrainElement e;
  e.id = id();
  e.points = &finite_points_;
  e.d = d_;
  e.plasticity = plasticity_ ? &*plasticity_ : nullptr;
  const Eigen::Map<const Eigen::Matrix3Xd> uc(u.data(), 3, u.size() / 3);
  finite_strain_sum(e, committed_u_, uc, finite_, k, f, update, form);
}

void QuadraticSolid::finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                                    Eigen::VectorXd& f_int, bool symmetric) const {
  IMPACTFE_CHECK(finite_strain(), "finite_tangent of a quadratic solid built small-strain");
  finite_sum(u, &K, f_int, nullptr,
             symmetric ? FiniteStrainTangent::Symmetric : FiniteStrainTangent::Exact);
  if (symmetric) K = 0.5 * (K + K.transpose()).eval();
}

Vector6d QuadraticSolid::finite_point_stress(const Eigen::VectorXd& u, int p) const {
  FiniteStrainUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  return at.stress.at(static_cast<std::size_t>(p));
}

void QuadraticSolid::finite_results(const Eigen::VectorXd& u, ElementResultValues& out) const {
  // Volume averages over the stiffness points (reference weights), as the small-strain plastic
  // results; the stresses are Cauchy, the states rotated into the current configuration.
  FiniteStrainUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  Vector6d s = Vector6d::Zero(), eppl = Vector6d::Zero();
  double epeq = 0.0, plwk = 0.0, srat = 0.0, total = 0.0;
  for (const FiniteStrainPoint& p : finite_points_) total += p.dv0;
  for (std::size_t q = 0; q < finite_points_.size(); ++q) {
    const double w = finite_points_[q].dv0 / total;
    s += w * at.stress[q];
    if (!plasticity_) continue;
    const PlasticState& st = at.states[q].plastic;
    eppl += w * st.plastic_strain;
    epeq += w * st.alpha;
    plwk += w * st.plastic_work;
    srat =
        std::max(srat, von_mises(st.stress - st.back_stress) / plasticity_->flow_stress(st.alpha));
  }
  out = solid_stress_row(s);
  if (!plasticity_) return;
  const double plastic[10] = {eppl(0), eppl(1), eppl(2), eppl(3),
                              eppl(4), eppl(5), epeq,    plasticity_->flow_stress(epeq),
                              srat,    plwk};
  std::copy(plastic, plastic + 10, out.begin() + 11);
}

}  // namespace impactfe
