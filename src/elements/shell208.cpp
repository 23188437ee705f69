// SHELL208: the 2-node axisymmetric shell (a conical frustum between nodes I and J in the X-Y
// plane, X radial, Y the axis of revolution), UX, UY, ROTZ at each node; matrices and loads per
// full 360° (forces on its nodes are totals around the circumference, as for the axisymmetric
// PLANE182/183). Small deflection, homogeneous isotropic section (SECTYPE,,SHELL / SECDATA).
//
// Degenerated-continuum (Ahmad) Mindlin–Reissner shell of revolution (Ahmad, Irons & Zienkiewicz
// 1970; Zienkiewicz & Taylor vol. 2, §15.4 "axisymmetric shells"; Cook et al., §15.5): with the
// unit tangent t = (J − I)/L, the normal n = (−t_y, t_x) and η ∈ [−h/2, h/2] along n,
//     X(ξ, η) = Σ N_a(ξ) x_a + η n,      U(ξ, η) = Σ N_a(ξ) (u_a + η θ_a e_z × n) = Σ N_a (u_a − η
//     θ_a t),
// linear N_a (plus, for KEYOPT(3) = 2, the extra internal node below). The strains of the shell
// in its (s, θ) surface, σ_nn = 0:
//     ε_ss = ∂U·t/∂s,   ε_θθ = U_x / r (r = X_x at the point, not at the mid-surface),
//     γ_sn = ∂U·n/∂s + ∂U·t/∂η,
// with σ = E/(1 − ν²) [[1, ν], [ν, 1]] (ε_ss, ε_θθ) and τ_sn = k G γ_sn, k = 5/6. The volume
// element is 2π r dA, integrated exactly enough through the thickness by 5 Gauss points (r varies
// across it). Along the length (MAPDL's SHELL208 integration): KEYOPT(3) = 0 one point for all
// terms (uniformly reduced: no spurious mode, the only zero-energy motion is the axial
// translation); KEYOPT(3) = 2 an extra internal node at mid-length, the bubble N_3 = 1 − ξ² on
// u_x, u_y and θ (the 3-node quadratic Mindlin shell of revolution), integrated at two points
// (reduced for the quadratic element: free of shear locking and of spurious modes) and condensed
// statically, K = K_ee − K_ei K_ii⁻¹ K_ie. As incompatible modes are (Wilson, Taylor et al.;
// Cook et al. §6.7), the internal node carries no load and no mass; its displacements are
// recovered from the nodes' for the stresses, q_i = −K_ii⁻¹ K_ie u.
//
// Results (result_names): S at TOP (η = +h/2, the side of n), MID and BOT as the components
// SX, SY, SZ (hoop), SXY, SEQV in global axes (X radial, Y axial, Z hoop, as the axisymmetric
// solids report them); the transverse shear stress kGγ is constant through the thickness.
// Element values at the centre; nodal values extrapolated from the two points (KEYOPT(3) = 2) or
// the centre's (KEYOPT(3) = 0).
#include <fmt/format.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "elements/element.h"
#include "elements/element_registry.h"
#include "elements/shell_laminate.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kShearFactor = 5.0 / 6.0;

struct Shell208Data {
  std::array<int, 2> node_ids{};
  std::array<Eigen::Vector2d, 2> x;  // (r, y) of I and J
  double h = 0.0;                    // thickness
  double E = 0.0, nu = 0.3, rho = 0.0;
  bool internal_node = false;  // KEYOPT(3) = 2: the extra internal node
};

const std::vector<std::string>& shell208_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const char* at : {"TOP", "MID", "BOT"})
      for (const char* c : {"SX", "SY", "SZ", "SXY", "SEQV"})
        out.push_back(fmt::format("{}_{}", c, at));
    return out;
  }();
  return names;
}

class Shell208 : public Element {
 public:
  Shell208(int id, const Shell208Data& d, const SourceLocation& where)
      : Element(id), d_(d), where_(where) {
    const Eigen::Vector2d dx = d.x[1] - d.x[0];
    L_ = dx.norm();
    if (!(L_ > 0.0)) throw InputError(where, fmt::format("element {}: zero length", id));
    t_ = dx / L_;
    n_ = Eigen::Vector2d(-t_(1), t_(0));
    for (int a = 0; a < 2; ++a)
      for (Dof dof : {Dof::UX, Dof::UY, Dof::ROTZ})
        dofs_.push_back({d.node_ids[static_cast<std::size_t>(a)], dof});
    // Every point where the strains divide by r off the axis (r > 0): the outermost Gauss
    // points along the length (ξ = ±√0.6, of the mass and pressure rules) on both surfaces;
    // r is linear in ξ and η, so these corners bound every integration and result point. A node
    // on the axis is fine (the apex of a dome), its surfaces need not be.
    for (double xi : {-std::sqrt(0.6), std::sqrt(0.6)})
      for (double eta : {-0.5 * d.h, 0.5 * d.h})
        if (!(radius(xi, eta) > 0.0))
          throw InputError(where, fmt::format("element {}: its thickness reaches across the axis "
                                              "(X <= 0 at a surface integration point; X is the "
                                              "radius): use shorter elements or thinner section",
                                              id));
    for (double xi : {-1.0, 1.0})
      if (radius(xi, 0.0) < 0.0)
        throw InputError(where,
                         fmt::format("element {}: a node lies at X < 0 (X is the radius)", id));
    condense();
  }

  const char* family() const override { return "Shell208"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override { return ctx.stress_stiffening; }

  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    if (ctx.stress_stiffening || ctx.large_deflection)
      throw NotImplementedError(
          where_, fmt::format("element {} (SHELL208): stress stiffening and large deflection are "
                              "not implemented (small deflection only)",
                              id()));
    K = K_;
    f_int = K * u;
  }

  /// −M ā (Element's) for fields symmetric about Y (the axis) only.
  void acceleration_field_load(const ElementContext& ctx,
                               const std::vector<LinearAccelerationField>& fields,
                               const std::function<Vec3(int)>& position,
                               Eigen::MatrixXd& f) const override {
    require_axisymmetric_fields(*this, fields);
    Element::acceleration_field_load(ctx, fields, position, f);
  }

  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override {
    // ∫ρ Hᵀ H dV of the displacement U = Σ N_a (u_a − η θ_a t): 3 points along, 5 across.
    M.setZero(6, 6);
    for (const auto& [xi, w] : along_points(3))
      for (const auto& [eta, v] : thickness_points()) {
        Eigen::Matrix<double, 2, 6> H = Eigen::Matrix<double, 2, 6>::Zero();
        const std::array<double, 2> N = shapes(xi);
        for (int a = 0; a < 2; ++a) {
          H(0, 3 * a) = N[static_cast<std::size_t>(a)];
          H(1, 3 * a + 1) = N[static_cast<std::size_t>(a)];
          H.col(3 * a + 2) = -eta * N[static_cast<std::size_t>(a)] * t_;
        }
        M += d_.rho * H.transpose() * H * (w * v * volume_factor(xi, eta));
      }
    if (ctx.lumped_mass) {
      // Each row summed over the columns of its own kind (the translations of its direction,
      // the rotations): ∫ρ N_a dV on the translations, ∫ρ η² N_a dV on the rotations, so that
      // a rigid axial translation carries the element's whole mass.
      Eigen::MatrixXd lumped = Eigen::MatrixXd::Zero(6, 6);
      for (int i = 0; i < 6; ++i) lumped(i, i) = M(i, i % 3) + M(i, 3 + i % 3);
      M = lumped;
    }
  }

  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd&, Eigen::VectorXd& f) const override {
    if (face != 1 && face != 2)
      throw ModelError(
          fmt::format("element {} (SHELL208): face {} takes no pressure here (faces "
                      "1 and 2, the top and bottom; the edge faces 3 and 4 are not "
                      "implemented)",
                      id(), face));
    if (ctx.large_deflection)
      throw NotImplementedError(where_, fmt::format("element {} (SHELL208): large deflection is "
                                                    "not implemented",
                                                    id()));
    // Face 1 (top, η = +h/2) presses against the normal n, face 2 (bottom, η = −h/2) along
    // it; linear between the values at I and J, per 360°, over the area of the loaded surface
    // itself (2π r(η) ds): a pressure inside a cylinder of mean radius R pushes with p (R − h/2)
    // per unit area of the mid-surface, the equilibrium of the thick-walled tube. Along ±n the
    // rotations do no work (n·t = 0), so no moment arises from the surface's eccentricity.
    const Eigen::Vector2d direction = face == 1 ? Eigen::Vector2d(-n_) : n_;
    const double eta = face == 1 ? 0.5 * d_.h : -0.5 * d_.h;
    f.setZero(6);
    for (const auto& [xi, w] : along_points(3)) {
      const std::array<double, 2> N = shapes(xi);
      const double pressure = N[0] * p[0] + N[1] * p[1];
      const double dA = kTwoPi * radius(xi, eta) * 0.5 * L_ * w;
      for (int a = 0; a < 2; ++a)
        f.segment<2>(3 * a) += N[static_cast<std::size_t>(a)] * pressure * dA * direction;
    }
  }

  const std::vector<std::string>& result_names() const override { return shell208_names(); }

  void results(const ElementContext&, const Eigen::VectorXd& u, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out = values_at(0.0, u);
  }

  bool nodal_results(const ElementContext&, const Eigen::VectorXd& u,
                     std::map<int, ElementResultValues>& at_node) const override {
    if (!d_.internal_node) {
      const ElementResultValues centre = values_at(0.0, u);
      for (int a = 0; a < 2; ++a) at_node[d_.node_ids[static_cast<std::size_t>(a)]] = centre;
      return true;
    }
    // Linear through the two Gauss points' values, at ξ = ∓1 (a factor √3 beyond them).
    const double g = 1.0 / std::sqrt(3.0);
    const ElementResultValues p1 = values_at(-g, u), p2 = values_at(g, u);
    for (int a = 0; a < 2; ++a) {
      const double xi = a == 0 ? -1.0 : 1.0;
      const double w2 = 0.5 * (1.0 + xi / g), w1 = 1.0 - w2;
      ElementResultValues v(p1.size());
      for (std::size_t i = 0; i < v.size(); ++i) v[i] = w1 * p1[i] + w2 * p2[i];
      for (std::size_t s = 0; s < 3; ++s) {  // SEQV of the extrapolated components
        const std::size_t k = 5 * s;
        v[k + 4] = von_mises_xyz(v[k], v[k + 1], v[k + 2], v[k + 3]);
      }
      at_node[d_.node_ids[static_cast<std::size_t>(a)]] = std::move(v);
    }
    return true;
  }

  std::optional<double> volume() const override {
    double v = 0.0;
    for (const auto& [xi, w] : along_points(2))
      for (const auto& [eta, q] : thickness_points()) v += w * q * volume_factor(xi, eta);
    return v;
  }

 private:
  using Points = std::vector<std::pair<double, double>>;  // (coordinate, weight)

  static Points along_points(int n) {
    if (n == 1) return {{0.0, 2.0}};
    if (n == 2) {
      const double g = 1.0 / std::sqrt(3.0);
      return {{-g, 1.0}, {g, 1.0}};
    }
    const double g = std::sqrt(0.6);
    return {{-g, 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {g, 5.0 / 9.0}};
  }

  /// 5-point Gauss through the thickness: η and its weight (over dη, summing to h).
  Points thickness_points() const {
    static const double g[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
    static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};
    Points out;
    for (int k = 0; k < 5; ++k) out.push_back({0.5 * d_.h * g[k], 0.5 * d_.h * w[k]});
    return out;
  }

  static std::array<double, 2> shapes(double xi) { return {0.5 * (1.0 - xi), 0.5 * (1.0 + xi)}; }

  double radius(double xi, double eta) const {
    const std::array<double, 2> N = shapes(xi);
    return N[0] * d_.x[0](0) + N[1] * d_.x[1](0) + eta * n_(0);
  }

  /// 2π r · ds/dξ: the weights of along_points and thickness_points times it give dV.
  double volume_factor(double xi, double eta) const { return kTwoPi * radius(xi, eta) * 0.5 * L_; }

  /// N and dN/ds of I, J and the internal node's bubble 1 − ξ² (columns 6..8, (u_x, u_y, θ)).
  struct Shapes {
    std::array<double, 3> N, dN;
  };
  Shapes shapes3(double xi) const {
    const std::array<double, 2> N = shapes(xi);
    return {{N[0], N[1], 1.0 - xi * xi}, {-1.0 / L_, 1.0 / L_, -4.0 * xi / L_}};
  }

  /// Rows ε_ss, ε_θθ at (ξ, η) over (UX, UY, ROTZ) of I, J and the internal node.
  Eigen::Matrix<double, 2, 9> membrane_bending_b(double xi, double eta) const {
    const Shapes sh = shapes3(xi);
    const double r = radius(xi, eta);
    Eigen::Matrix<double, 2, 9> B = Eigen::Matrix<double, 2, 9>::Zero();
    for (std::size_t a = 0; a < 3; ++a) {
      const int c = 3 * static_cast<int>(a);
      B(0, c) = sh.dN[a] * t_(0);
      B(0, c + 1) = sh.dN[a] * t_(1);
      B(0, c + 2) = -sh.dN[a] * eta;
      B(1, c) = sh.N[a] / r;
      B(1, c + 2) = -sh.N[a] * eta * t_(0) / r;
    }
    return B;
  }

  /// γ_sn at ξ (independent of η), over the same 9 columns.
  Eigen::Matrix<double, 1, 9> shear_b(double xi) const {
    const Shapes sh = shapes3(xi);
    Eigen::Matrix<double, 1, 9> B;
    for (std::size_t a = 0; a < 3; ++a) {
      const int c = 3 * static_cast<int>(a);
      B(0, c) = sh.dN[a] * n_(0);
      B(0, c + 1) = sh.dN[a] * n_(1);
      B(0, c + 2) = -sh.N[a];
    }
    return B;
  }

  /// The stiffness on the nodes (condensed over the internal node for KEYOPT(3) = 2) and the
  /// recovery of the internal node's displacements from the nodes', formed once (linear).
  void condense() {
    const double c = d_.E / (1.0 - d_.nu * d_.nu);
    Eigen::Matrix2d D;
    D << c, c * d_.nu, c * d_.nu, c;
    const double kG = kShearFactor * d_.E / (2.0 * (1.0 + d_.nu));
    const int n_along = d_.internal_node ? 2 : 1;
    Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
    for (const auto& [xi, w] : along_points(n_along))
      for (const auto& [eta, v] : thickness_points()) {
        const Eigen::Matrix<double, 2, 9> B = membrane_bending_b(xi, eta);
        const Eigen::Matrix<double, 1, 9> S = shear_b(xi);
        const double dV = w * v * volume_factor(xi, eta);
        K += (B.transpose() * D * B + S.transpose() * kG * S) * dV;
      }
    if (!d_.internal_node) {
      K_ = K.topLeftCorner<6, 6>();
      recover_.setZero();
      return;
    }
    // K_ii is positive definite: the bubbles vanish at the nodes, so the only motion it could
    // miss would be a zero-energy mode of the quadratic element, which two points do not have.
    const Eigen::LDLT<Eigen::Matrix3d> Kii(K.bottomRightCorner<3, 3>());
    recover_ = -Kii.solve(K.bottomLeftCorner<3, 6>());
    K_ = K.topLeftCorner<6, 6>() + K.topRightCorner<6, 3>() * recover_;
  }

  /// The 9 displacements (I, J, internal node) of the nodes' 6.
  Eigen::Matrix<double, 9, 1> with_internal(const Eigen::VectorXd& u) const {
    Eigen::Matrix<double, 9, 1> q;
    q.head<6>() = u.head<6>();
    q.tail<3>() = recover_ * u.head<6>();
    return q;
  }

  static double von_mises_xyz(double sx, double sy, double sz, double sxy) {
    return std::sqrt(0.5 * ((sx - sy) * (sx - sy) + (sy - sz) * (sy - sz) + (sz - sx) * (sz - sx)) +
                     3.0 * sxy * sxy);
  }

  /// The stresses at ξ at the three surfaces, in global axes (result_names order).
  ElementResultValues values_at(double xi, const Eigen::VectorXd& u) const {
    const double c = d_.E / (1.0 - d_.nu * d_.nu);
    const Eigen::Matrix<double, 9, 1> q = with_internal(u);
    const double tau = kShearFactor * d_.E / (2.0 * (1.0 + d_.nu)) * (shear_b(xi) * q)(0);
    ElementResultValues out;
    for (double eta : {0.5 * d_.h, 0.0, -0.5 * d_.h}) {
      const Eigen::Vector2d e = membrane_bending_b(xi, eta) * q;
      const double s_ss = c * (e(0) + d_.nu * e(1)), s_hoop = c * (d_.nu * e(0) + e(1));
      // σ = σ_ss t⊗t + τ (t⊗n + n⊗t) in the X-Y plane, σ_ZZ the hoop stress.
      const double sx = s_ss * t_(0) * t_(0) + 2.0 * tau * t_(0) * n_(0);
      const double sy = s_ss * t_(1) * t_(1) + 2.0 * tau * t_(1) * n_(1);
      const double sxy = s_ss * t_(0) * t_(1) + tau * (t_(0) * n_(1) + t_(1) * n_(0));
      out.insert(out.end(), {sx, sy, s_hoop, sxy, von_mises_xyz(sx, sy, s_hoop, sxy)});
    }
    return out;
  }

  Shell208Data d_;
  SourceLocation where_;
  double L_ = 0.0;
  Eigen::Vector2d t_, n_;
  std::vector<DofKey> dofs_;
  Eigen::Matrix<double, 6, 6> K_;        // on the nodes (condensed)
  Eigen::Matrix<double, 3, 6> recover_;  // internal node from the nodes (zero without it)
};

std::unique_ptr<Element> make_shell208(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& msg) {
    return InputError(record.where, fmt::format("element {} (SHELL208): {}", record.id, msg));
  };
  if (ctx.large_deflection)
    throw fail("large deflection (NLGEOM,ON) is not implemented for SHELL208");
  const ElementType& type = model.element_types.at(record.type);
  if (record.nodes.size() < 2) throw fail("needs nodes I and J");
  Shell208Data d;
  for (std::size_t a = 0; a < 2; ++a) {
    const int id = record.nodes[a];
    const auto it = model.nodes.find(id);
    if (it == model.nodes.end()) throw fail(fmt::format("node {} is not defined", id));
    if (std::abs(it->second.x(2)) > 0.0)
      throw fail(
          fmt::format("node {} lies off the X-Y plane (Z = {:g}): an axisymmetric element "
                      "lies in it",
                      id, it->second.x(2)));
    d.node_ids[a] = id;
    d.x[a] = it->second.x.head<2>();
  }
  if (d.node_ids[0] == d.node_ids[1]) throw fail("nodes I and J are the same node");
  const auto sec = model.sections.find(record.secnum);
  if (record.secnum <= 0 || sec == model.sections.end() || sec->second.type != "SHELL" ||
      sec->second.data.empty())
    throw fail(fmt::format("needs a shell section (SECTYPE,{},SHELL and SECDATA,thickness)",
                           std::max(record.secnum, 1)));
  std::vector<shell::LayerInput> layers;
  try {
    layers = shell::section_layers(model, sec->second, record.mat);
  } catch (const std::invalid_argument& e) {
    throw fail(e.what());
  }
  if (layers.size() != 1)
    throw fail(
        fmt::format("section {} has {} layers: layered SHELL208 sections are not "
                    "implemented (one homogeneous layer)",
                    sec->second.id, layers.size()));
  if (!sec->second.offset.empty() && sec->second.offset != "MID")
    throw fail(fmt::format("section {}: SECOFFSET,{} is not implemented for SHELL208 (MID)",
                           sec->second.id, sec->second.offset));
  const int mat_id = layers.front().material;
  const auto mat_it = model.materials.find(mat_id);
  if (mat_it == model.materials.end() || !mat_it->second.has("EX"))
    throw fail(fmt::format("material {} has no EX", mat_id));
  const Material& mat = mat_it->second;
  require_isotropic(mat, mat_id, record.id, record.where);
  d.h = layers.front().thickness;
  if (!(d.h > 0.0)) throw fail("zero or negative thickness");
  d.E = mat.get("EX", 0.0);
  if (!(d.E > 0.0)) throw fail(fmt::format("material {}: EX must be positive", mat_id));
  d.nu = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  d.rho = mat.get("DENS", 0.0);
  d.internal_node = type.key(3) == 2;
  return std::make_unique<Shell208>(record.id, d, record.where);
}

const ElementRegistration kShell208{
    {.name = "SHELL208",
     .number = 208,
     .family = "Shell208",
     .n_nodes = 2,
     .needs_material = true,
     .section_types = {"SHELL"},
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = shell208_names(),
     // S at the top surface (SHELL,MID / BOT choose the others), global axes (Z the hoop).
     .result_sequences = {{"S", "X", "SX_TOP"},
                          {"S", "Y", "SY_TOP"},
                          {"S", "Z", "SZ_TOP"},
                          {"S", "XY", "SXY_TOP"},
                          {"S", "EQV", "SEQV_TOP"}},
     // Face 1 the top (pressure against the normal), face 2 the bottom (along it).
     .faces = {{0, 1}, {0, 1}},
     .sf_faces = 1,
     .note = "SHELL208 is a degenerated-continuum Mindlin-Reissner shell of revolution: small "
             "deflection, one homogeneous isotropic layer, results in global axes (Z hoop)",
     .create = make_shell208}};

}  // namespace

}  // namespace impactfe
