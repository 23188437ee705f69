#pragma once
/// SOLID45 / SOLID185: the 8-node isoparametric brick (UX UY UZ per node), 2x2x2 Gauss
/// integration (thesis eq. 2-5, Bathe §5.3), optional Wilson incompatible modes with Taylor's
/// modification (extra shapes), degenerate prism / pyramid / tetrahedron by repeated nodes,
/// consistent or HRZ-lumped mass, linear stress stiffening and a total-Lagrangian large-deflection
/// formulation (Green-Lagrange strain, 2nd Piola-Kirchhoff stress, St. Venant-Kirchhoff).
/// With a TB plasticity table: small-strain J2 plasticity at the 8 Gauss points (committed
/// states per point); the incompatible modes, when active, stay in the strain and their
/// amplitudes are solved per element for each u (local Newton, then static condensation of the
/// consistent tangent) — the enhanced-mode treatment of SOLID185 KEYOPT(2) = 3 and SOLID45.
/// Without extra shapes the plastic brick uses B-bar (mean dilatation, as MAPDL's SOLID185
/// KEYOPT(2) = 0), so isochoric plastic flow does not lock; the elastic brick without TB keeps
/// full integration (docs/elements/solid45.md). A plastic brick under large deflection (NLGEOM,ON)
/// is updated-Lagrangian and hypoelastic (elements/solid_finite_strain.h: midpoint increments,
/// Hughes-Winget rotation, Cauchy stress, logarithmic strain) with the mean dilatation applied to
/// the strain increment; the elastic brick keeps the total-Lagrangian St. Venant-Kirchhoff form.
#include <Eigen/Core>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "elements/element.h"
#include "elements/solid_finite_strain.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

struct ResultSequence;  // elements/element_registry.h

/// Small-strain technology of the brick (SOLID185 KEYOPT(2)). Standard: full 2x2x2 with the
/// incompatible modes when extra_shapes (KEYOPT(2) = 3, SOLID45), B-bar for a plastic brick
/// without them. BBar (KEYOPT(2) = 0): selective dilatational (Hughes 1980), the volumetric
/// strain of every Gauss point replaced by the element mean. Enhanced (KEYOPT(2) = 2): the 9
/// incompatible modes plus 4 enhanced volumetric strains (Simo & Rifai 1990), 13 internal
/// parameters condensed per element; a collapsed brick falls back to BBar.
enum class BrickStrain { Standard, BBar, Enhanced };

/// The brick's result names (SX..PLWK) and its faces 1..6 in MAPDL's numbering (corner
/// positions, outward normals by the right-hand rule): for the registration.
const std::vector<std::string>& brick8_result_names();
/// A row of brick8_result_names() with the stress columns of s (xx yy zz xy yz xz): S X..XZ,
/// the principal stresses S1 ≥ S2 ≥ S3, SINT and SEQV; the plastic and creep columns zero.
ElementResultValues solid_stress_row(const Vector6d& s);
/// The POST1 sequences (S, EPPL, NL, EPCR) of brick8_result_names(), shared by the 3-D solids
/// (brick8_types.cpp).
const std::vector<ResultSequence>& solid_result_sequences();
const std::vector<std::vector<int>>& brick8_faces();

/// The 8-node brick. All matrices are in global Cartesian axes; the DOF order is (node, UX/UY/UZ)
/// for the distinct nodes in order of first appearance in I..P.
class Brick8 final : public Element {
 public:
  /// `nodes`: node ids I..P (repeats allowed: degenerate shapes); `x`: their coordinates.
  /// `extra_shapes` requests the incompatible modes; they are dropped when nodes repeat.
  /// Throws InputError at `where` for a zero or negative Jacobian at a Gauss point.
  /// `large_deflection` (ElementBuildContext): keep the mode recovery that the total-Lagrangian
  /// tangent reads at every iteration; otherwise it is formed when asked.
  Brick8(int id, const std::array<int, 8>& nodes, const std::array<Vec3, 8>& x,
         const IsotropicElasticity& material, bool extra_shapes, const SourceLocation& where = {},
         std::optional<J2Plasticity> plasticity = std::nullopt, bool large_deflection = false,
         BrickStrain strain = BrickStrain::Standard);

  const char* family() const override { return "Brick8"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override {
    return ctx.large_deflection || ctx.stress_stiffening || plasticity_.has_value();
  }
  bool has_history() const override { return plasticity_.has_value(); }
  double plastic_work() const override;
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  /// Committed state of Gauss point p (0..7, order of the corners' signs); plastic bricks only.
  const PlasticState& gauss_state(int p) const {
    return committed_.at(static_cast<std::size_t>(p));
  }
  /// Linear: K = condensed ∫BᵀDB dV, f_int = K u (+ K_σ u with stress stiffening, K_σ from the
  /// stress of u, so that the converged state solves (K + K_σ(u)) u = F as ANSYS SSTIF does).
  /// Large deflection: total-Lagrangian f_int = ∫ B_Lᵀ S dV0 and its exact derivative; with
  /// plasticity the updated-Lagrangian f_int = ∫ Bᵀσ dv on the current configuration and the
  /// symmetric tangent of solid_finite_strain.h (finite_tangent(), brick8_finite.cpp).
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent ρ∫NᵀN dV (trilinear functions, 2x2x2) or HRZ-lumped when ctx.lumped_mass.
  /// f_int of tangent() alone; under large deflection without extra shapes the
  /// total-Lagrangian sum skips the stiffness blocks.
  void internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                      Eigen::VectorXd& f_int) const override;
  bool separate_internal_force(const ElementContext& ctx) const override {
    return ctx.large_deflection && !plasticity_ && !extra_shapes_;
  }
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;

  /// Pressure on face 1..6 (J-I-L-K, I-J-N-M, J-K-O-N, K-L-P-O, L-I-M-P, M-N-O-P, outward
  /// normals): f_a = −∫ N_a p n dA over the bilinear face, 3x3 Gauss; on the face deformed by u
  /// under large deflection.
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;

  /// Equivalent nodal forces of the thermal strain, f = ∫ Bᵀ D ε_th dV (2x2x2 Gauss, the
  /// temperature interpolated by the trilinear functions; with extra shapes the bubbles' share
  /// condensed onto the corners as their stiffness is).
  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;

  /// SX SY SZ SXY SYZ SXZ S1 S2 S3 SINT SEQV at the centroid, global axes (Cauchy stress under
  /// large deflection); with plasticity the volume average of the Gauss-point stresses, and
  /// EPPLX..EPPLXZ (plastic strain, engineering shear), EPEQ (equivalent plastic strain), SEPL
  /// (yield stress at EPEQ), SRAT (equivalent stress / SEPL, largest point), PLWK (plastic work
  /// per volume), volume averages of the points; zeros without plasticity. With implicit creep
  /// (TB,CREEP) the inelastic strain is reported as EPCRX..EPCRXZ (creep strain, engineering
  /// shear), EPCREQV (its equivalent, equivalent_inelastic_strain) and CREQ (accumulated
  /// equivalent creep strain) instead, the plastic items zero.
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  /// The stresses at the corners (PRNSOL, PLNSOL, *GET NODE S) of an elastic small-strain
  /// brick with 8 distinct nodes: the trilinear field through the 8 Gauss points' stresses
  /// evaluated at the corners (Cook et al. §6.13; MAPDL's ERESX default for elastic elements).
  /// false (the centroid values stand for the nodes) for a plastic, large-deflection or
  /// degenerate brick, and for one whose material expands thermally (a rebuilt copy does not
  /// know the temperatures of the set).
  bool nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                     std::map<int, ElementResultValues>& at_node) const override;

  /// True when the incompatible modes are active (requested and all 8 nodes distinct).
  bool extra_shapes() const { return extra_shapes_; }
  /// The small-strain technology in effect (Enhanced on a collapsed brick becomes BBar).
  BrickStrain strain() const { return strain_; }
  /// Internal strain parameters condensed per element: 0, 9 (incompatible modes) or 13.
  int n_internal() const { return n_internal_; }
  /// True when some of the nodes I..P repeat (prism, pyramid, tetrahedron).
  bool degenerate() const { return n_unique_ < 8; }
  /// Element volume ∫dV (2x2x2 Gauss), in the deck's length unit cubed.
  std::optional<double> volume() const override { return volume_; }
  /// Cauchy stress (xx, yy, zz, xy, yz, xz) at the centroid for displacement u.
  Vector6d centroid_stress(const ElementContext& ctx, const Eigen::VectorXd& u) const;
  /// True for a plastic brick built for large deflection (updated-Lagrangian finite strain).
  bool finite_strain() const { return !finite_points_.empty(); }
  /// Finite strain: f_int at u (element DOF order) and the exact tangent, non-symmetric, or with
  /// `symmetric` the symmetric form tangent() assembles (FiniteStrainTangent::Symmetric).
  void finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f_int,
                      bool symmetric) const;
  /// Finite strain: the Cauchy stress of Gauss point p (0..7) at u, from the committed state.
  Vector6d finite_point_stress(const Eigen::VectorXd& u, int p) const;

 private:
  /// ε_th = (ALPX, ALPY, ALPZ) Σ N_a ΔT_a, no shear, at the point with trilinear values `n`.
  Vector6d thermal_strain(const Eigen::Matrix<double, 8, 1>& n) const;
  static constexpr int kGauss = 8;
  static constexpr int kModes = 3;  // incompatible bubble functions (1-ξ²), (1-η²), (1-ζ²)
  static constexpr int kFunctions = 11;  // 8 trilinear + 3 bubbles
  // The shape function values at the points are the same for every brick (gauss_shape()).
  struct GaussPoint {
    Eigen::Matrix<double, 3, kFunctions> grad;  // d/dX of the 8 (+3 modified) functions
    double dv = 0.0;                            // weight * det J
  };

  Eigen::Matrix<double, 24, 1> to_corners(const Eigen::VectorXd& u) const;
  /// The corner matrices summed onto the unique nodes of a brick with repeated nodes (a brick
  /// without forms them in place: tangent()).
  void from_corners(const Eigen::MatrixXd& kc, const Eigen::VectorXd& fc, Eigen::MatrixXd& k,
                    Eigen::VectorXd& f) const;
  /// ∫ B_Lᵀ S dV0 and ∫ (B_Lᵀ D B_L + G ᵀ S G) dV0 over the first NF functions at the
  /// generalised displacements q (3 NF: corners then bubble amplitudes). q = 0 gives the
  /// linear stiffness.
  /// NF = 8 (corners) or 11 (with the bubbles); fixed-size operands, and K summed over the
  /// Gauss points by two small products after the point loop (see the definition).
  /// `k` == nullptr: f alone (the same operations, so bitwise the same f).
  /// K0 > 0: only the block of K over the functions K0..NF-1 is formed (the rest of `k` is left
  /// as it was): the bubble block that the Newton iterations on their amplitudes need.
  template <int NF, int K0 = 0>
  void tl_sum(const Eigen::Matrix<double, 3 * NF, 1>& q, Eigen::Matrix<double, 3 * NF, 3 * NF>* k,
              Eigen::Matrix<double, 3 * NF, 1>& f) const;
  void tangent_linear(const ElementContext& ctx, const Eigen::Matrix<double, 24, 1>& uc,
                      Eigen::MatrixXd& kc, Eigen::VectorXd& fc) const;
  void tangent_large(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd& kc,
                     Eigen::VectorXd& fc) const;
  using PointStates = std::vector<PlasticState>;  // per Gauss point
  /// Small-strain elastic-plastic K_T and f_int on the corners: the Gauss points return from
  /// the committed states; with extra shapes the mode amplitudes are solved for equilibrium
  /// first (Newton) and condensed out. `updated` receives the states at u when given.
  void tangent_plastic(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd& kc,
                       Eigen::VectorXd& fc, PointStates* updated) const;
  /// ∫BᵀC_alg B dV, ∫Bᵀσ dV at generalised displacements q (24 corners, or 24 + n_internal()).
  void plastic_sum(const Eigen::VectorXd& q, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                   PointStates* updated) const;
  /// The condensed small-strain stiffness on the corners, formed when asked (not kept: a linear
  /// model's bricks are asked once, and the assembler keeps the global sums; 75 MB on 16 384
  /// bricks), and the mode recovery α = R u_c into `recovery` when given.
  Eigen::Matrix<double, 24, 24> small_strain_stiffness(Eigen::MatrixXd* recovery) const;
  /// α = R u_c, the small-strain internal amplitudes (n_internal() x 24; 9 x 24 of zeros
  /// without any): the kept R of a plastic or large-deflection brick, else formed now.
  Eigen::MatrixXd mode_recovery() const;
  /// Small-strain B (Voigt xx yy zz xy yz xz, engineering shear) at Gauss point p over the
  /// corners, then (`internal`) the n_internal() internal parameters: bubble k direction i at
  /// column 24 + 3k + i, enhanced volumetric mode m at 33 + m. Without internal parameters the
  /// corner columns carry the B-bar shift when B-bar is in effect (bbar_active()).
  Eigen::Matrix<double, 6, Eigen::Dynamic> strain_operator(int p, bool internal) const;
  /// B-bar in the small-strain forms: BrickStrain::BBar, or a plastic brick without modes.
  bool bbar_active() const {
    return n_internal_ == 0 && (strain_ == BrickStrain::BBar || plasticity_);
  }
  /// Scalar (one direction) mass matrix over the distinct nodes, consistent.
  Eigen::MatrixXd scalar_mass() const;
  /// Finite strain on the corners: f, the exact tangent when `kc` is given, the states at u.
  void finite_sum(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd* kc, Eigen::VectorXd& fc,
                  FiniteStrainUpdate* update,
                  FiniteStrainTangent form = FiniteStrainTangent::Exact) const;
  /// Finite strain: the states at the corner displacements uc become the committed ones.
  void finite_commit(const Eigen::Matrix<double, 24, 1>& uc);

  std::array<int, 8> nodes_;
  std::array<Vec3, 8> x_;
  std::array<int, 8> corner_to_unique_{};
  int n_unique_ = 0;
  std::vector<DofKey> dofs_;
  Matrix6d d_;
  double density_ = 0.0;
  bool extra_shapes_ = false;
  BrickStrain strain_ = BrickStrain::Standard;
  int n_internal_ = 0;
  double det0_ = 0.0;  // det J at the element centre (enhanced-strain scaling)
  double volume_ = 0.0;
  std::array<GaussPoint, kGauss> gauss_;
  Eigen::Matrix<double, 3, 8> grad_centre_;  // d/dX of the trilinear functions at ξ = 0
  // Only what every brick reads is kept inline (a linear brick is 3.3 kB, 16 384 of them 54 MB):
  // R = mode_recovery() for bricks whose tangent reads it at every iteration (9 x 24, or
  // empty), and the Gauss points' committed states for plastic ones (8, or empty).
  Eigen::MatrixXd mode_recovery_;
  Eigen::Matrix<double, 1, 24> mean_dilatation_;  // (1/V) ∫ ∂u_i/∂x_i row over the corners
  std::optional<J2Plasticity> plasticity_;
  PointStates committed_{};
  // Plastic brick under large deflection: the Gauss points' reference gradients and measures,
  // their committed finite-strain states and the committed corner displacements (all empty
  // otherwise).
  std::vector<FiniteStrainPoint> finite_points_;
  std::vector<FiniteStrainState> finite_;
  Eigen::Matrix3Xd committed_u_;  // 3 x 8 (corners)
};

}  // namespace impactfe
