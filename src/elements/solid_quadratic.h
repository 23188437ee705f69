#pragma once
/// SOLID186 / SOLID187: the quadratic isoparametric solids (UX UY UZ per node). The 20-node
/// serendipity hexahedron, integrated with 2x2x2 Gauss points (uniform reduced integration,
/// MAPDL's default KEYOPT(2) = 0) or 3x3x3 (KEYOPT(2) = 1), and the 10-node tetrahedron with the
/// 4-point rule (SOLID187, and SOLID186's degenerate tetrahedron). Small-strain isotropic linear
/// elasticity; consistent mass (exact rules: 3x3x3, or the conical product on the tetrahedron) or
/// HRZ-lumped mass; linear stress stiffening; consistent pressure loads on the 8-node and 6-node
/// faces. With a TB plasticity (or implicit creep) law: small-strain J2 at the stiffness points
/// with committed states per point. Large deflection (NLGEOM,ON, elastic or plastic) is
/// updated-Lagrangian and hypoelastic (elements/solid_finite_strain.h: midpoint increments,
/// Hughes-Winget rotation, Cauchy stress, logarithmic strain); stress stiffening with plasticity
/// is refused (docs/elements/solid186.md).
#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "elements/element.h"
#include "elements/quadratic_shapes.h"
#include "elements/solid_finite_strain.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// SX SY SZ SXY SYZ SXZ S1 S2 S3 SINT SEQV, EPPLX..EPPLXZ EPEQ SEPL SRAT PLWK.
const std::vector<std::string>& quadratic_solid_result_names();

class QuadraticSolid final : public Element {
 public:
  /// `nodes`: the node ids in the cell's order (corners, then midside nodes), all distinct;
  /// `x`: their coordinates; `stiffness_rule`: the points of ∫BᵀDB dV (gauss_cube(2 or 3), or
  /// tetrahedron_4_point()); `faces`: face k + 1 of the element type's numbering as positions
  /// in `nodes` (corners, then the midside nodes of its sides; empty for a face collapsed to an
  /// edge or a point). Throws InputError at `where` for a zero or negative Jacobian at an
  /// integration point or a corner.
  QuadraticSolid(int id, QuadraticShape shape, const std::vector<int>& nodes,
                 const std::vector<Vec3>& x, const IsotropicElasticity& material,
                 std::vector<QuadraturePoint> stiffness_rule, std::vector<std::vector<int>> faces,
                 const SourceLocation& where = {},
                 std::optional<J2Plasticity> plasticity = std::nullopt,
                 bool large_deflection = false);

  const char* family() const override { return "QuadraticSolid"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override {
    return ctx.large_deflection || ctx.stress_stiffening || plasticity_.has_value();
  }
  bool has_history() const override { return plasticity_.has_value() || finite_strain(); }
  /// True when built for large deflection (updated-Lagrangian finite strain).
  bool finite_strain() const { return !finite_points_.empty(); }
  double plastic_work() const override;
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  /// Committed state of stiffness point p (plastic elements only).
  const PlasticState& point_state(int p) const {
    return committed_.at(static_cast<std::size_t>(p));
  }
  /// K = ∫BᵀDB dV, f_int = K u; with stress stiffening K + K_σ(u) and f_int = (K + K_σ) u (the
  /// geometric stiffness of the small-strain stress of u at the stiffness points, as Brick8).
  /// With plasticity K = ∫BᵀC_alg B dV, f_int = ∫Bᵀσ dV from the committed states.
  /// Large deflection: f_int = ∫ Bᵀσ dv on the current configuration (Cauchy stress) and the
  /// symmetric tangent of solid_finite_strain.h (finite_tangent()).
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent ρ∫NᵀN dV, or HRZ-lumped when ctx.lumped_mass (Hinton, Rock & Zienkiewicz 1976:
  /// the diagonal of the consistent matrix scaled to the element mass; positive at every node,
  /// where row sums give negative corner masses for these elements).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  /// Pressure on face 1..6 (brick: J-I-L-K, I-J-N-M, J-K-O-N, K-L-P-O, L-I-M-P, M-N-O-P) or 1..4
  /// (tetrahedron: J-I-K, I-J-L, J-K-L, K-I-L), outward normals; the corner values interpolated
  /// (bi)linearly over the face; f_a = −∫ N_a p n dA with the quadratic face functions.
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  /// SX SY SZ SXY SYZ SXZ S1 S2 S3 SINT SEQV at the natural centre, global axes; with
  /// plasticity the volume averages of the points' stresses, plastic strains (engineering
  /// shear), EPEQ and PLWK, SEPL (flow stress at EPEQ), SRAT (largest point ratio of equivalent
  /// to flow stress); the plastic items are 0 without plasticity.
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  /// The stresses at the nodes (PRNSOL, PLNSOL, *GET NODE S) of an elastic small-strain element:
  /// the lowest polynomial through the stiffness points' stresses, trilinear on the brick (fitted
  /// by least squares to the 27 points of KEYOPT(2) = 1), linear on the tetrahedron, evaluated at
  /// the nodes, so a midside node takes the mean of its corners (Cook et al. §6.13; MAPDL's
  /// ERESX default for elastic elements). false (the centroid values stand for the nodes) for a
  /// plastic or finite-strain element, whose rebuilt copy has no history.
  bool nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                     std::map<int, ElementResultValues>& at_node) const override;
  std::optional<double> volume() const override { return volume_; }
  /// Finite strain: f_int at u and the exact tangent, non-symmetric, or with `symmetric` the
  /// symmetric form tangent() assembles (FiniteStrainTangent::Symmetric).
  void finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f_int,
                      bool symmetric) const;
  /// Finite strain: the Cauchy stress of stiffness point p at u, from the committed state.
  Vector6d finite_point_stress(const Eigen::VectorXd& u, int p) const;
  /// Stress (xx, yy, zz, xy, yz, xz) at natural coordinates xi for displacement u.
  Vector6d stress_at(const Eigen::Vector3d& xi, const Eigen::VectorXd& u) const;
  QuadraticShape shape() const { return shape_; }
  /// Number of stiffness integration points.
  int stiffness_points() const { return static_cast<int>(rule_.size()); }
  /// ∫BᵀDB dV over the stiffness points (formed when asked: not kept, 29 kB per brick).
  Eigen::MatrixXd small_strain_stiffness() const;

 private:
  struct Point {
    Eigen::Matrix3Xd grad;  // ∂N/∂x of every node
    Eigen::VectorXd n;      // N of every node
    double det = 0.0;       // det J
  };
  Point point_at(const Eigen::Vector3d& xi) const;
  /// ρ∫NᵀN dV (one direction) with a rule exact for undistorted elements.
  Eigen::MatrixXd scalar_mass() const;
  /// ∫BᵀC_alg B dV and ∫Bᵀσ dV at u from the committed states; the states at u into `updated`.
  void plastic_sum(const Eigen::VectorXd& u, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                   std::vector<PlasticState>* updated) const;
  void plastic_results(const Eigen::VectorXd& u, ElementResultValues& out) const;
  /// Finite strain at u from the committed states (solid_finite_strain.h).
  void finite_sum(const Eigen::VectorXd& u, Eigen::MatrixXd* k, Eigen::VectorXd& f,
                  FiniteStrainUpdate* update,
                  FiniteStrainTangent form = FiniteStrainTangent::Exact) const;
  /// The volume averages of the states at u (reference weights) as results().
  void finite_results(const Eigen::VectorXd& u, ElementResultValues& out) const;

  QuadraticShape shape_;
  std::vector<int> nodes_;
  std::vector<Vec3> x_;
  std::vector<DofKey> dofs_;
  Matrix6d d_;
  double density_ = 0.0;
  double volume_ = 0.0;
  std::vector<QuadraturePoint> rule_;  // stiffness points
  std::vector<std::vector<int>> faces_;
  std::optional<J2Plasticity> plasticity_;
  std::vector<PlasticState> committed_;  // per stiffness point (plastic elements)
  // Large deflection: the stiffness points' reference gradients and measures, their committed
  // finite-strain states and the committed displacement (3 x nodes); empty otherwise.
  std::vector<FiniteStrainPoint> finite_points_;
  std::vector<FiniteStrainState> finite_;
  Eigen::Matrix3Xd committed_u_;
};

}  // namespace impactfe
