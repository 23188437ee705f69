#pragma once
/// PLANE182 / PLANE183: the 2-D structural solids in the global X-Y plane (UX, UY per node).
/// The bilinear quadrilateral (and its constant-strain triangle K = L), the 8-node serendipity
/// quadrilateral and the 6-node triangle; plane stress (with a thickness), plane strain and
/// axisymmetry about the global Y axis (X radial, loads and matrices per full 360°). Small-strain
/// isotropic linear elasticity; the 4-node quadrilateral with full 2x2 integration, with the
/// B-bar (mean dilatation) of Hughes (1980), with the incompatible bending modes of Taylor,
/// Beresford & Wilson (1976), or at one point with hourglass stabilisation (KEYOPT(1) = 1).
/// Consistent or lumped mass, edge pressures, centroid stresses.
/// With a TB plasticity (or implicit creep) law: small-strain J2 at the stiffness points with
/// committed states per point (plane_solid_plastic.cpp): the 3-D return of the strain
/// (εxx, εyy, εzz, γxy) with εzz = u/r in axisymmetry and 0 in plane strain, the plane-stress
/// return (σzz = 0) otherwise; the incompatible modes, when active, are solved per element for
/// each u and condensed. Under large deflection (NLGEOM,ON; PlaneSolidOptions::large_deflection)
/// the element is finite-strain, updated-Lagrangian and hypoelastic as MAPDL's 18x elements
/// (plane_solid_finite.cpp): the strain increment from the midpoint configuration, the stress
/// rotated by the incremental rotation of Hughes & Winget (1980), Cauchy stress and the
/// accumulated logarithmic strain as results. Stress stiffening alone (SSTIF without NLGEOM) is
/// refused (docs/elements/plane182.md).
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "elements/element.h"
#include "elements/quadratic_shapes.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

enum class PlaneShape { Quad4, Tri3, Quad8, Tri6 };

/// KEYOPT(3) of PLANE182/183: 0 and 3 plane stress (3: with a thickness), 1 axisymmetric,
/// 2 plane strain.
enum class PlaneBehaviour { PlaneStress, Axisymmetric, PlaneStrain };

/// How the 4-node quadrilateral is integrated (PLANE182 KEYOPT(1)): Standard full 2x2 (the
/// triangles and the quadratic shapes always), BBar (KEYOPT(1) = 0 in plane strain and
/// axisymmetry: the volumetric strain replaced by its element mean), IncompatibleModes
/// (KEYOPT(1) = 3, and 2 in plane stress: four internal bending modes, condensed), Reduced
/// (KEYOPT(1) = 1: the material at the centre alone plus an elastic hourglass stiffness,
/// plane_solid_reduced.cpp).
enum class PlaneTechnology { Standard, BBar, IncompatibleModes, Reduced };

struct PlaneSolidOptions {
  PlaneShape shape = PlaneShape::Quad4;
  PlaneBehaviour behaviour = PlaneBehaviour::PlaneStress;
  PlaneTechnology technology = PlaneTechnology::Standard;
  double thickness = 1.0;  // plane stress and plane strain; unused in axisymmetry
  /// NLGEOM,ON when the element is built: finite-strain kinematics with a committed
  /// configuration and stress per point (Standard or BBar technology only).
  bool large_deflection = false;
  /// ERESX: the element nodal stresses extrapolated from the stiffness points or copied from
  /// the nearest one (element_nodal_stresses()).
  NodalStressRule nodal_stresses = NodalStressRule::Default;
};

/// SX SY SZ SXY S1 S2 S3 SINT SEQV, then EPPLX EPPLY EPPLZ EPPLXY EPEQ SEPL SRAT PLWK, then
/// EPCRX EPCRY EPCRZ EPCRXY EPCREQV CREQ (creep strain, equivalent, accumulated equivalent),
/// then EPELX EPELY EPELZ EPELXY (elastic strain, engineering shear; logarithmic under NLGEOM),
/// then the element nodal values of each node position k = 1..8 of the element (ESOL with a
/// NODE): SX@k SY@k SZ@k SXY@k EPELX@k EPELY@k EPELZ@k EPELXY@k (0 past the element's nodes).
const std::vector<std::string>& plane_solid_result_names();

/// The element nodal items stored per node position (plane_solid_result_names()).
inline constexpr int kPlaneNodalItems = 8;
inline constexpr int kPlaneMaxNodes = 8;

/// The result items (plane_solid_result_names()) of a stress (xx, yy, zz, xy), the inelastic
/// items 0.
ElementResultValues plane_stress_items(const Eigen::Vector4d& stress);

/// Number of nodes of a plane shape and their natural coordinates (quadrilaterals on [-1, 1]²,
/// corners I J K L then the midsides of I-J J-K K-L L-I; triangles on the unit triangle, corners
/// I J K then the midsides of I-J J-K K-I).
int plane_shape_nodes(PlaneShape shape);
std::vector<Eigen::Vector2d> plane_shape_nodes_xi(PlaneShape shape);

class PlaneSolid final : public Element {
 public:
  /// `nodes`: node ids in the shape's order, all distinct; `x`: their coordinates (Z ignored:
  /// must be the same for all); `faces`: face k + 1 as positions in `nodes` (the two corners in
  /// MAPDL's order J-I, K-J, L-K, I-L, then the midside node; empty for a collapsed face).
  /// Throws InputError at `where` for a zero Jacobian or mixed orientation, and in axisymmetry
  /// for a node at negative X. `plasticity`: the material's J2 law (plasticity_of), if any.
  PlaneSolid(int id, const std::vector<int>& nodes, const std::vector<Vec3>& x,
             const IsotropicElasticity& material, const PlaneSolidOptions& options,
             std::vector<std::vector<int>> faces, const SourceLocation& where = {},
             std::optional<J2Plasticity> plasticity = std::nullopt);

  const char* family() const override { return "PlaneSolid"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override {
    return plasticity_.has_value() || options_.large_deflection;
  }
  /// Plastic elements, and every element under large deflection (its committed configuration
  /// and stress are the start of the next increment).
  bool has_history() const override { return plasticity_.has_value() || options_.large_deflection; }
  double plastic_work() const override;
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  /// Committed state of stiffness point p (plastic elements only).
  const PlasticState& point_state(int p) const {
    return committed_.at(static_cast<std::size_t>(p));
  }
  int n_points() const { return static_cast<int>(rule_.size()); }
  /// Natural coordinates of stiffness point p.
  Eigen::Vector2d point_xi(int p) const {
    return rule_.at(static_cast<std::size_t>(p)).xi.head<2>();
  }
  /// K = ∫ BᵀDB dV (dV = t dA, or 2πr dA), condensed over the incompatible modes; f_int = K u.
  /// With plasticity K = ∫ BᵀC_alg B dV and f_int = ∫ Bᵀσ dV from the committed states.
  /// Large deflection and stress stiffening are refused (ElementSolutionError).
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent ρ∫NᵀN dV; lumped: row sums (4-node shapes) or HRZ (8- and 6-node shapes,
  /// whose row sums are negative at the corners).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  /// −M ā (Element's), in axisymmetry for fields symmetric about Y only: the radial
  /// centrifugal load ρω²r then acts on the ring of radius r through the 2πr of the mass.
  void acceleration_field_load(const ElementContext& ctx,
                               const std::vector<LinearAccelerationField>& fields,
                               const std::function<Vec3(int)>& position,
                               Eigen::MatrixXd& f) const override;
  /// Pressure on edge `face` (1..4), linear between the values at its two corners (p[0] at the
  /// face's first node), positive into the element: f_a = −∫ N_a p n dS (dS = t ds or 2πr ds).
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  /// Equivalent nodal forces of the thermal strain (docs/thermal_loads.md): f = ∫ Bᵀ D ε_th dV
  /// with ε_th = α (T − T_ref) at the stiffness points, T interpolated from the nodes: (αx, αy,
  /// 0) ΔT in plane stress (σzz = 0), (αx, αy, αz) ΔT with εzz = 0 in plane strain (so σzz =
  /// ν(σx + σy) − E αz ΔT), the hoop strain αz ΔT in axisymmetry; B-bar, the reduced mean strain
  /// and the incompatible modes as in the stiffness (the modes' share condensed:
  /// f = f_u − Rᵀ f_a). Elastic small strain; with plasticity or NLGEOM: NotImplementedError.
  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;
  const std::vector<std::string>& result_names() const override;
  /// Finite strain (large deflection, plane_solid_finite.cpp) at total displacement u from the
  /// committed state: f_int = ∫ Bᵀσ dv over the current configuration and its exact derivative
  /// K (material part of the rate form with the incremental rotation, initial-stress part and
  /// the change of volume). `symmetric`: K replaced by ½(K + Kᵀ), as the symmetric solvers
  /// need (tangent()).
  void finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f_int,
                      bool symmetric) const;
  /// Cauchy stress (xx, yy, zz, xy) of stiffness point p at u (large deflection only).
  Eigen::Vector4d finite_point_stress(const Eigen::VectorXd& u, int p) const;
  /// SX SY S1 S2 S3 SINT SEQV at the centroid (natural centre), global axes; SZ is the
  /// hoop stress in axisymmetry, ν(SX + SY) in plane strain, 0 in plane stress. With
  /// plasticity the volume averages of the points' stresses, plastic strains EPPLX..EPPLXY
  /// (engineering shear), EPEQ, PLWK, SEPL (flow stress at EPEQ) and SRAT (largest point ratio
  /// of equivalent stress to flow stress); these are 0 without plasticity. A creep law (no
  /// yield surface) reports its inelastic strain as EPCR X..XY, EPCR EQV (von Mises equivalent
  /// of the averaged creep strain) and NL CREQ (accumulated equivalent creep strain), with the
  /// plastic items 0, as MAPDL separates them.
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  /// The stresses of the integration points extrapolated to the nodes (bilinear through the
  /// 2x2 points, linear through 3 points, constant from 1), with their derived items. Not for
  /// a plastic element (false: its history is not in a freshly built element).
  bool nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                     std::map<int, ElementResultValues>& at_node) const override;
  /// The stresses (xx, yy, zz, xy) at the element's nodes (element order) as MAPDL's ERESX
  /// default gives them: extrapolated from the stiffness points (as nodal_results()) while no
  /// point has yielded, copied from the nearest stiffness point (midside nodes: the mean of the
  /// nearest points) once any point carries plastic or creep strain. Evaluated from the
  /// committed states, so valid in the solution (results()), not in a rebuilt element.
  std::vector<Eigen::Vector4d> element_nodal_stresses(const ElementContext& ctx,
                                                      const Eigen::VectorXd& u) const;
  /// ∫ t dA, or the volume of the full ring ∫ 2πr dA.
  std::optional<double> volume() const override { return volume_; }

  /// Stress (xx, yy, zz, xy) at the natural centre for displacement u.
  Eigen::Vector4d centroid_stress(const Eigen::VectorXd& u) const;
  /// The (condensed) stiffness matrix.
  const Eigen::MatrixXd& stiffness() const { return k_; }
  PlaneShape shape() const { return options_.shape; }

 private:
  struct Point {
    Eigen::Matrix2Xd grad;  // ∂N/∂x, ∂N/∂y of every node
    Eigen::VectorXd n;      // N of every node
    double det = 0.0;       // det J (signed)
    double radius = 0.0;    // X at the point
    Eigen::Matrix2d j_inverse;
  };
  Point point_at(const Eigen::Vector2d& xi) const;
  /// dV per unit natural area at a point of natural weight w: w |det J| × (t or 2πr).
  double measure(const Point& p, double w) const;
  /// Strain-displacement matrix (rows xx yy zz xy; zz = u/r in axisymmetry, else 0).
  Eigen::MatrixXd strain_matrix(const Point& p) const;
  /// The incompatible-mode strains of a point (4 x 4: modes (1−ξ²) ux, uy, (1−η²) ux, uy).
  Eigen::Matrix4d mode_matrix(const Point& p, const Eigen::Vector2d& xi) const;
  void form_stiffness();
  /// Reduced integration (plane_solid_reduced.cpp): the mean strain operator and the elastic
  /// stabilisation stiffness.
  void form_hourglass();
  /// The strain operator of the stiffness point p: B there, or the element mean with reduced
  /// integration.
  Eigen::MatrixXd point_strain(const Point& p) const;

  // ---- plasticity (plane_solid_plastic.cpp) ----
  using PointStates = std::vector<PlasticState>;
  /// The strain operator of stiffness point q (rows xx yy zz xy, B-bar applied) over the nodal
  /// DOFs, then the 4 incompatible-mode amplitudes when `modes`.
  Eigen::MatrixXd point_operator(std::size_t q, bool modes) const;
  /// σ (xx yy zz xy) and dσ/dε (4 x 4) of one point for the strain (εxx, εyy, εzz, γxy).
  void point_response(const PlasticState& committed, const Eigen::Vector4d& strain,
                      Eigen::Vector4d& stress, Eigen::Matrix4d& tangent,
                      PlasticState* updated) const;
  /// ∫BᵀC_alg B dV and ∫Bᵀσ dV at the generalised displacements q (nodal, then the modes).
  void plastic_sum(const Eigen::VectorXd& q, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                   PointStates* updated, std::vector<Eigen::Vector4d>* stresses) const;
  /// K_T and f_int on the nodal DOFs: the mode amplitudes (when active) solved for
  /// ∫Gᵀσ dV = 0 by Newton and condensed out. `updated` receives the states at u when given.
  void tangent_plastic(const Eigen::VectorXd& u, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                       PointStates* updated, std::vector<Eigen::Vector4d>* stresses) const;
  void plastic_results(const Eigen::VectorXd& u, ElementResultValues& out) const;

  // ---- finite strain (plane_solid_finite.cpp) ----
  /// Committed state of one stiffness point under large deflection: the accumulated
  /// (logarithmic) strain (xx, yy, zz, xy; engineering shear) in global axes, and the elastic
  /// Cauchy stress of an element without plasticity.
  struct FiniteState {
    Eigen::Vector4d strain = Eigen::Vector4d::Zero();
  };
  struct FiniteUpdate;      // the states at u, for commit and results
  struct FiniteKinematics;  // the midpoint kinematics of one point (plane_solid_finite.cpp)
  struct FiniteResponse;    // the rotated law's response at one point (plane_solid_finite.cpp)
  void finite_sum(const Eigen::VectorXd& u, Eigen::MatrixXd* K, Eigen::VectorXd& f,
                  FiniteUpdate* update) const;
  /// Pass 1 of finite_sum at stiffness point p: F_½, L, ∇_x N, the increment q and ∂q/∂u.
  void finite_kinematics(std::size_t p, const Eigen::Map<const Eigen::Matrix2Xd>& un,
                         const Eigen::Matrix2Xd& du, FiniteKinematics& k) const;
  /// The law at stiffness point p from the committed state at ε_n + ΔRᵀ Δε ΔR, rotated by ΔR.
  void finite_response(std::size_t p, const FiniteKinematics& k, FiniteResponse& r) const;
  /// The point's contribution to K (the exact derivative of f_int, finite_sum's header).
  void add_finite_tangent(const FiniteKinematics& k, const FiniteResponse& r,
                          const Eigen::VectorXd& a, const Eigen::VectorXd& lzz,
                          Eigen::MatrixXd& K) const;
  void finite_commit(const Eigen::VectorXd& u);
  void finite_results(const Eigen::VectorXd& u, ElementResultValues& out) const;
  /// Cauchy stresses of the stiffness points at u; `inelastic`: a point carries plastic strain.
  void finite_point_stresses(const Eigen::VectorXd& u, std::vector<Eigen::Vector4d>& sigma,
                             bool& inelastic) const;
  /// Stresses of the stiffness points at u as results() evaluates them (small strain, plastic or
  /// elastic; finite strain); `inelastic`: some point carries plastic or creep strain.
  void point_stresses(const ElementContext& ctx, const Eigen::VectorXd& u,
                      std::vector<Eigen::Vector4d>& sigma, bool& inelastic) const;
  /// The elastic extrapolation of point stresses to the nodes (nodal_results()).
  std::vector<Eigen::Vector4d> extrapolate_to_nodes(
      const std::vector<Eigen::Vector4d>& sigma) const;
  /// Each node's nearest stiffness point's stresses (a node equally near several: their mean).
  std::vector<Eigen::Vector4d> copy_to_nodes(const std::vector<Eigen::Vector4d>& sigma) const;
  /// ε_th = α (T − T_ref) (xx, yy, zz, xy) at a point, T interpolated from the nodes'
  /// temperature changes (temperature_change()); zero when none is set.
  Eigen::Vector4d thermal_strain(const Point& p) const;
  /// The thermal load on the nodal DOFs (f_u) and on the incompatible modes (f_a).
  void thermal_sums(Eigen::VectorXd& f_u, Eigen::Vector4d& f_a) const;
  /// The incompatible-mode amplitudes at u: −R u, plus K_aa⁻¹ f_a under a thermal strain.
  Eigen::Vector4d mode_amplitudes(const Eigen::VectorXd& u) const;
  /// The elastic strain (xx, yy, zz, xy; engineering shear) of a stress (isotropic law).
  Eigen::Vector4d elastic_strain(const Eigen::Vector4d& stress) const;

  std::vector<int> nodes_;
  std::vector<Vec3> x_;
  std::vector<DofKey> dofs_;
  PlaneSolidOptions options_;
  std::vector<std::vector<int>> faces_;
  Eigen::Matrix4d d_;
  double density_ = 0.0;
  double volume_ = 0.0;
  double orientation_ = 1.0;  // +1 counter-clockwise corners, −1 clockwise
  std::vector<QuadraturePoint> rule_;
  Eigen::MatrixXd k_;
  Eigen::RowVectorXd mean_dilatation_;  // B-bar: element mean of the volumetric row
  Eigen::Matrix4d mean_modes_;          // incompatible modes: their element mean (subtracted)
  Eigen::MatrixXd mode_recovery_;       // α = −mode_recovery_ u (+ K_aa⁻¹ f_a, thermal)
  Eigen::Matrix4d kaa_inverse_ = Eigen::Matrix4d::Zero();  // incompatible modes: K_aa⁻¹
  Eigen::MatrixXd hourglass_;    // reduced integration: the stabilisation stiffness
  Eigen::MatrixXd mean_strain_;  // reduced integration: B̄ = ∫ B dV / V
  Eigen::Matrix2d j0_inverse_;
  double det0_ = 1.0;
  std::optional<J2Plasticity> plasticity_;
  PointStates committed_;         // per stiffness point (plastic elements)
  std::vector<double> point_dv_;  // dV of the stiffness points (plastic elements)
  double young_ = 0.0, poisson_ = 0.0;
  // Large deflection: committed displacement (element DOF order) and point states.
  Eigen::VectorXd committed_u_;
  std::vector<FiniteState> finite_;
};

}  // namespace impactfe
