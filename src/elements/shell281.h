#pragma once
/// SHELL281: the 8-node quadratic shell (I J K L corners, M N O P midsides of I-J J-K K-L L-I)
/// and the 6-node triangle it becomes when K = L = O. Six DOFs per node in global axes.
/// See docs/elements/shell281.md.
///
/// Degenerated-continuum (Ahmad) Mindlin–Reissner shell (Ahmad, Irons & Zienkiewicz 1970;
/// Zienkiewicz & Taylor vol. 2, §15.3): X(ξ, η, ζ) = Σ N_a (x_a + ζ t_a/2 V_a) with the nodal
/// director V_a the surface normal of the element at node a, and the displacement
/// U = Σ N_a (u_a + ζ t_a/2 θ_a × V_a). Strains in the lamina frame (e1, e2 tangent, e3 normal;
/// e1 along ∂X/∂ξ, or the ESYS x axis projected on the surface) with σ33 = 0; transverse shear
/// k G with k = 5/6.
/// - Quadrilateral: 3 x 3 Gauss, the transverse shear tied (assumed covariant strains, in the
///   manner of the MITC elements, Bathe & Dvorkin 1986): γ_ξζ = c0 + c1 ξ + c2 η + c3 ξη + c4 η²
///   from the sides' points (±1/√3, ±1) and the centre, γ_ηζ likewise. Free of shear locking
///   and of spurious modes; 2 x 2 Gauss shear (MAPDL's reduced integration) locked the clamped
///   thin plate (0.66 of w at a/t = 1000 on 8 x 8 elements). Converges from the flexible side.
/// - Triangle: the 3-point midside rule (degree 2) for membrane, bending and shear.
/// - Drilling: Hughes–Brezzi penalty γ ∫ (θ·e3 − ½(∂v/∂x − ∂u/∂y))² dA, γ = G t, integrated
///   with the full rule, zero for a rigid rotation (Hughes & Brezzi 1989).
/// - Plasticity and implicit creep (a TB table of a homogeneous isotropic section): the
///   plane-stress J2 return (j2_plasticity.h) at the in-plane points of the membrane and bending
///   rule and 5 Gauss–Lobatto points through the thickness (the surfaces among them), as
///   SHELL181's; the transverse shear and drilling stay elastic.
/// Small deflection only: NLGEOM,ON is refused when the element is built. KEYOPT(1) = 1
/// (membrane only) has the translations alone.
#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "elements/element.h"
#include "elements/shell_laminate.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// Everything make_shell281 reads from the model, resolved; lets tests build elements directly.
struct Shell281Data {
  std::vector<int> node_ids;      // 8 (quadrilateral) or 6 (triangle I J K M N P)
  std::vector<Vec3> positions;    // same order
  std::vector<double> thickness;  // at each node
  double E = 0.0;
  double nu = 0.3;
  double rho = 0.0;
  double shear_factor = 5.0 / 6.0;
  double drill_factor = 1.0;   // γ / (G t)
  bool membrane_only = false;  // KEYOPT(1) = 1
  /// A layered section (SECDATA per layer, shell_laminate.h); empty plies: one homogeneous
  /// isotropic layer of E, nu, rho. The layers span the thickness in proportion to theirs.
  shell::Laminate laminate;
  /// SECOFFSET: the nodes on the mid-surface (0), the bottom (+1: the material lies on the side
  /// of the normal) or the top (−1), in units of the half thickness.
  double offset = 0.0;
  /// ESYS: the axes of the element's local coordinate system (columns, global directions); the
  /// lamina frame's e1 is then their x axis projected on the surface (shell_esys_x_axis), not
  /// ∂X/∂ξ. It orients the layer angles and the element results.
  std::optional<Eigen::Matrix3d> esys_axes;
  /// TB plasticity or implicit creep of the (homogeneous, isotropic) section (plasticity_of).
  std::optional<J2Plasticity> plasticity;
};

class Shell281 : public Element {
 public:
  /// Throws InputError(where, ...) for a degenerate geometry (non-positive Jacobian).
  Shell281(int id, const Shell281Data& data, const SourceLocation& where);

  /// "Shell281", or "Shell281Layered" for a layered section (whose results add each layer's).
  const char* family() const override { return layered() ? "Shell281Layered" : "Shell281"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override {
    return ctx.stress_stiffening || data_.plasticity.has_value();
  }
  /// K (plus the stress stiffness of the stresses at u with SSTIF), f = K u; with plasticity
  /// the consistent tangent and f_int of the states returned from the committed ones at u.
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent ∫ρ Hᵀ H dV (rotary inertia of the directors included) plus ρt³/12 on the
  /// drilling rotation; lumped: HRZ diagonal scaling (Hinton, Rock & Zienkiewicz 1976).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  /// Face 1 (bottom: positive pushes along +N, N = ∂x/∂ξ × ∂x/∂η of I-J-K-L) or face 2 (top,
  /// along −N), pressure bilinear (linear) in the corner values; faces 3..6: in-plane edge
  /// pressures on J-I, K-J, L-K, I-L, a force per length positive into the element.
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  const std::vector<std::string>& result_names() const override;
  /// The lamina frame at the element centre (e1 along ∂x/∂ξ, e3 the normal): the axes of the
  /// centroid values. The nodal values come from the frames at the Gauss points, which on a
  /// curved element differ from it by the element's curvature; POST1 rotates them with this one.
  Eigen::Matrix3d result_axes(const ElementContext& ctx, const Eigen::VectorXd& u) const override;
  /// Values at the element centre (element axes: e1 along ∂x/∂ξ).
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  /// The same values extrapolated from the Gauss points to each node (MAPDL's ERESX default).
  bool nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                     std::map<int, ElementResultValues>& at_node) const override;
  std::optional<double> volume() const override { return volume_; }

  bool has_history() const override { return data_.plasticity.has_value(); }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  double plastic_work() const override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;

  int n_nodes() const { return n_; }
  /// The element's displacement vector on all 6n DOFs (membrane only: rotations zero).
  Eigen::VectorXd expand(const Eigen::VectorXd& u) const;
  /// The translation block of a 6n × 6n matrix (membrane only), else the matrix.
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& A) const;
  /// Linear stiffness (global axes, 6n × 6n). Exposed for tests.
  Eigen::MatrixXd stiffness() const;
  /// Geometric stiffness of the stresses of the displacement u. Exposed for tests.
  Eigen::MatrixXd geometric_stiffness(const Eigen::VectorXd& u) const;

  static const std::vector<std::string>& names();
  /// The result names of a layered element: names() and then, for each layer L = 1, 2, ..:
  /// SX SY SXY SEQV at its TOP, MID and BOT ("SX_L1_TOP"), up to kMaxResultLayers layers.
  static const std::vector<std::string>& layered_names();
  static constexpr int kMaxResultLayers = 12;
  bool layered() const { return layers_.size() > 1; }
  /// Points through the thickness of the plasticity rule (Gauss–Lobatto, shell281_plastic.cpp).
  static constexpr int kPlasticPoints = 5;

 private:
  struct Rule {
    double xi, eta, w;
  };
  /// Shape functions and natural derivatives at (ξ, η).
  void shape(double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN) const;
  /// Lamina frame R = [e1 e2 e3] and the area element |∂x/∂ξ × ∂x/∂η| of the mid-surface.
  Eigen::Matrix3d frame(const Eigen::VectorXd& N, const Eigen::MatrixXd& dN, double* dA) const;
  /// The local displacement gradient operator at (ξ, η, ζ): rows 3p + q give L_pq = ∂u_p/∂x_q
  /// in the frame R (9 × 6n), and det J.
  Eigen::MatrixXd gradient(double xi, double eta, double zeta, const Eigen::Matrix3d& R,
                           double* detJ) const;
  /// Strains (ε11, ε22, γ12, γ13, γ23) of the local gradient operator (5 × 6n).
  static Eigen::MatrixXd strains(const Eigen::MatrixXd& G);
  /// The global gradient ∂U_i/∂X_j operator (rows 3i + j) at (ξ, η, ζ), with det J.
  Eigen::MatrixXd global_gradient(double xi, double eta, double zeta, double* detJ) const;
  /// Covariant transverse shear strains (γ_ξζ, γ_ηζ) of the displacement field (2 × 6n).
  Eigen::MatrixXd covariant_shear(double xi, double eta, double zeta) const;
  /// Assumed (tied) transverse shear (γ13, γ23) in the frame R (2 × 6n), quadrilateral.
  Eigen::MatrixXd assumed_shear(double xi, double eta, double zeta, const Eigen::Matrix3d& R) const;
  /// The transverse shear operator of the stiffness: assumed (quadrilateral) or displacement-based.
  Eigen::MatrixXd shear_b(double xi, double eta, double zeta, const Eigen::Matrix3d& R) const;
  void full_pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                          const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  std::vector<Rule> bending_rule() const;
  std::vector<Rule> shear_rule() const;
  std::vector<Rule> full_rule() const;
  double thickness_at(const Eigen::VectorXd& N) const;
  /// A layer in the thickness coordinate ζ ∈ [−1, 1] with its stiffness in the lamina frame.
  struct Layer {
    double zeta_bot, zeta_top;
    Eigen::Matrix3d Q;   // (σ11, σ22, τ12) of (ε11, ε22, γ12)
    Eigen::Matrix2d Gs;  // (τ13, τ23) of (γ13, γ23), shear correction included
    double rho;
  };
  /// A point of the thickness rule: ζ, its weight (Σ = 2 over the thickness) and its layer.
  struct ThicknessPoint {
    double zeta, w;
    std::size_t layer;
  };
  /// Two-point Gauss in each layer (exact for strains linear in ζ); the mid-surface with
  /// weight 2 and the thickness-averaged stiffness for the membrane-only element.
  std::vector<ThicknessPoint> thickness_rule() const;
  /// Two-point Gauss in each layer, whatever the KEYOPT(1) (the mass).
  std::vector<ThicknessPoint> layer_points() const;
  /// The in-plane stiffness averaged over the thickness (membrane only).
  Eigen::Matrix3d mean_q() const;

  /// Result values at (ξ, η) (result_names() order).
  ElementResultValues values_at(double xi, double eta, const Eigen::VectorXd& u) const;

  /// The membrane and bending stiffness (layer by layer) and the transverse shear and
  /// drilling stiffness, whose sum is stiffness().
  Eigen::MatrixXd membrane_bending_stiffness() const;
  Eigen::MatrixXd shear_drilling_stiffness() const;
  /// With plasticity: K and f_int at ue (6n) from the committed states; `updated` receives the
  /// states at ue (point-major: bending_rule() point × 5 Lobatto points, bottom first).
  void plastic_sum(const Eigen::VectorXd& ue, Eigen::MatrixXd& K, Eigen::VectorXd& f,
                   std::vector<PlasticState>* updated) const;
  /// With plasticity: the result values at each bending_rule() point from its states at ue,
  /// and the weights that interpolate them at (ξ, η) (Lagrange through the points).
  std::vector<ElementResultValues> plastic_point_values(const Eigen::VectorXd& ue) const;
  std::vector<double> point_weights(double xi, double eta) const;

  int n_ = 0;
  std::vector<DofKey> dofs_;
  std::vector<Vec3> X_;
  std::vector<Vec3> V_;  // nodal directors
  std::vector<double> t_;
  std::vector<int> node_ids_;
  Shell281Data data_;
  double volume_ = 0.0;
  std::vector<Layer> layers_;            // bottom first
  double drill_g_ = 0.0;                 // the thickness-averaged in-plane shear modulus
  double zeta0_ = 0.0;                   // Shell281Data::offset
  std::vector<PlasticState> committed_;  // plasticity: the converged states (plastic_sum order)
};

}  // namespace impactfe
