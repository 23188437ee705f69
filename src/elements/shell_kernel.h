#pragma once
/// The flat-facet kernel of the SHELL63 / SHELL181 element: a small-strain, linear elastic
/// shell of 3 or 4 nodes in its own plane (local x, y; z normal). It knows nothing about
/// global axes, warping or large rotations (shell4.cpp does that).
///
/// Local DOFs per node, in this order: u, v, w, θx, θy, θz (θx = ∂w/∂y, θy = −∂w/∂x for a
/// Kirchhoff plate; θz is the drilling rotation).
///
/// - Membrane: quad = bilinear plane stress with the modified (Taylor–Beresford–Wilson)
///   incompatible modes 1−ξ², 1−η², condensed, 2×2 Gauss (Cook et al. §6.7); triangle = CST.
/// - Drilling: Hughes–Brezzi penalty γ ∫ (θz − ½(∂v/∂x − ∂u/∂y))² dA with γ = drill_factor·G·t,
///   which vanishes for a rigid in-plane rotation (Hughes & Brezzi 1989).
/// - Bending, thin (SHELL63): discrete Kirchhoff DKT triangle (Batoz, Bathe & Ho 1980) / DKQ
///   quad (Batoz & Ben Tahar 1982), D_b = E t³ RMI / (12(1−ν²)).
/// - Bending, Mindlin–Reissner (SHELL181, KernelData::mindlin): independent rotations with the
///   (bi)linear shape functions, βx = θy, βy = −θx; transverse shear with assumed covariant
///   strains, MITC4 on the quad (Bathe & Dvorkin 1985) and MITC3 on the triangle (Lee & Bathe
///   2004), D_s = k G t with k = 5/6 (shell_kernel_mindlin.cpp).
#include <Eigen/Core>

#include <array>
#include <vector>

#include <memory>

#include "elements/shell_laminate.h"
#include "materials/j2_plasticity.h"

namespace impactfe::shell {

/// Material, section and option data of one facet.
struct KernelData {
  double E = 0.0;
  double nu = 0.3;
  double rho = 0.0;                     // mass density
  double added_mass = 0.0;              // ADMSUA, mass per unit area added to ρt
  double rmi = 1.0;                     // bending-inertia ratio (bending stiffness only)
  double efs = 0.0;                     // elastic foundation stiffness (force / length³)
  std::array<double, 4> t{0, 0, 0, 0};  // thickness at the corners
  bool membrane = true;                 // KEYOPT(1) != 2
  bool bending = true;                  // KEYOPT(1) != 1
  bool extra_shapes = true;             // KEYOPT(3) != 2 (quad membrane only)
  bool rotary_inertia = true;           // KEYOPT(7) != 1
  double drill_factor = 1.0e-3;         // γ / (G t) of the drilling penalty
  bool mindlin = false;                 // Mindlin–Reissner bending + MITC shear (SHELL181)
  double shear_factor = 5.0 / 6.0;      // k of the transverse shear stiffness k G t
  /// A symmetric layered section (SHELL181): membrane A, bending D and transverse shear of the
  /// laminate instead of those of E, ν, t (B = 0: the kernel has no membrane-bending coupling).
  std::shared_ptr<const Laminate> laminate;
};

/// Stress resultants at the centroid, element axes: N = (TX, TY, TXY) force/length,
/// M = (MX, MY, MXY) moment/length with MX = −D(∂²w/∂x² + ν ∂²w/∂y²) (Timoshenko's sign),
/// and the centroidal thickness.
struct Resultants {
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  Eigen::Vector3d M = Eigen::Vector3d::Zero();
  /// Transverse shear forces (QX, QY) = k G t (γxz, γyz), force/length (Mindlin kernel only).
  Eigen::Vector2d Q = Eigen::Vector2d::Zero();
  double t = 0.0;
};

class FlatShellKernel {
 public:
  /// xy: corner coordinates in the facet plane, counter-clockwise (3 or 4 of them).
  /// Throws std::invalid_argument for a non-positive Jacobian (zero area / re-entrant quad).
  FlatShellKernel(const std::vector<Eigen::Vector2d>& xy, const KernelData& data);

  int n_nodes() const { return n_; }
  int n_dofs() const { return 6 * n_; }
  double area() const { return area_; }
  /// ∫t dA (the facet's volume).
  double volume() const { return volume_; }
  /// ∫ (ρt + ADMSUA) dA: the translational mass of the facet.
  double total_mass() const { return total_mass_; }

  /// Linear stiffness, 6n × 6n, local DOF order. Formed at each call (the kernel keeps no
  /// 6n × 6n matrices: a linear model asks once per element and keeps the global products; a
  /// co-rotational element keeps the one it reads at every iteration, shell4.h).
  Eigen::MatrixXd stiffness() const;
  /// Consistent mass: (ρt + ADMSUA) ∫NᵀN on u, v, w with the bilinear/linear N, plus rotary
  /// inertia ρt³/12 ∫NᵀN on θx, θy, θz unless rotary inertia is off. Formed at each call.
  Eigen::MatrixXd consistent_mass() const;
  /// Lumped mass: total_mass()/n on each translation; Mindlin kernel with rotary inertia:
  /// ρt³/12·A/n on θx, θy; nothing on θz.
  Eigen::MatrixXd lumped_mass() const;

  /// Geometric (stress) stiffness of the membrane resultants of the local displacement d:
  /// ∫ ∇Nᵀ [[TX, TXY], [TXY, TY]] ∇N dA on each of u, v, w (centroidal resultants).
  Eigen::MatrixXd geometric_stiffness(const Eigen::VectorXd& d) const;

  /// Centroidal resultants of the local displacement d.
  Resultants resultants(const Eigen::VectorXd& d) const;

  // ---- elastic-plastic response (SHELL181 with a TB plasticity table) ------------------------
  /// Layers through the thickness at each in-plane Gauss point: 5-point Gauss–Lobatto
  /// (z = ±t/2, ±√(3/7) t/2, 0; layer 0 at the bottom, 4 at the top).
  static constexpr int kLayers = 5;
  /// Number of material points: in-plane points × layers (state vector size).
  int n_material_points() const;
  /// Local stiffness and internal force of the local displacement d with J2 plasticity at every
  /// layer point (plane stress σzz = 0, strain e + z κ; transverse shear is not part of the
  /// Kirchhoff DK kernel): N = ∫σ dz, M = ∫zσ dz, tangent [A B; B D] from the consistent
  /// plane-stress tangent. The quad's incompatible membrane modes are solved for equilibrium per
  /// call (local Newton) and condensed. Drilling penalty and foundation stay elastic. `updated`
  /// receives the states at d; `mean`, the resultants averaged over the area, and `layers`, the
  /// area-averaged layer stresses (σx, σy, σxy) bottom → top.
  void plastic_response(const J2Plasticity& law, const std::vector<PlasticState>& committed,
                        const Eigen::VectorXd& d, Eigen::MatrixXd& K, Eigen::VectorXd& f,
                        std::vector<PlasticState>* updated, Resultants* mean = nullptr,
                        std::array<Eigen::Vector3d, kLayers>* layers = nullptr) const;
  /// ∫ (plastic work per volume) dV of the given states.
  double plastic_work(const std::vector<PlasticState>& states) const;
  /// The inelastic (plastic or creep) strain of layer `layer` (0 bottom .. kLayers − 1 top)
  /// averaged over the area (Voigt xx, yy, zz, xy, yz, xz in the kernel's axes, engineering
  /// shears).
  Vector6d layer_inelastic_strain(const std::vector<PlasticState>& states, int layer) const;

  /// DK rotation fields βx = Hx·U, βy = Hy·U (β = −∇w at the Kirchhoff points) at natural
  /// point (ξ, η) for the bending DOFs U = (w, θx, θy) per node; exposed for tests.
  void dk_rotations(double xi, double eta, Eigen::VectorXd& Hx, Eigen::VectorXd& Hy) const;

 private:
  struct Point {
    double xi, eta, w;
  };
  void shape(double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN_dx, double& detJ) const;
  void dk_fields(const double* N6, Eigen::VectorXd& Hx, Eigen::VectorXd& Hy) const;
  void dk_curvature(double xi, double eta, Eigen::MatrixXd& B, double& detJ) const;
  /// Curvature operator (κx, κy, κxy) of the bending DOFs (w, θx, θy per node) at (ξ, η): the
  /// DK one, or the Mindlin one of the (bi)linear rotations (κ = ∇β, β = (θy, −θx)).
  void bending_b(double xi, double eta, Eigen::MatrixXd& B) const;
  /// Assumed transverse shear strains (γxz, γyz) of the bending DOFs at (ξ, η), 2 × 3n: MITC4
  /// (quad) or MITC3 (triangle). Mindlin kernel only.
  void shear_b(double xi, double eta, Eigen::MatrixXd& B) const;
  /// The Jacobian [∂(x, y)/∂ξ; ∂(x, y)/∂η] of the (bi)linear map at (ξ, η).
  Eigen::Matrix2d jacobian(double xi, double eta) const;
  /// Covariant transverse shear strains (γξ, γη) = (∂w/∂ξ + β·∂x/∂ξ, ∂w/∂η + β·∂x/∂η) of the
  /// displacement-based field at (ξ, η), 2 × 3n: the values the MITC elements tie to.
  Eigen::Matrix<double, 2, Eigen::Dynamic> covariant_shear(double xi, double eta) const;
  void add_shear(Eigen::MatrixXd& K) const;
  double thickness_at(const Eigen::VectorXd& N) const;
  std::vector<Point> points() const;
  /// Centroidal strain operators and the incompatible modes' centre Jacobian.
  void set_centroid_data();
  /// The parts of the linear stiffness, added into K (6n × 6n, local DOF order).
  void add_membrane(Eigen::MatrixXd& K) const;
  void add_drilling(Eigen::MatrixXd& K) const;
  void add_bending(Eigen::MatrixXd& K) const;
  void add_foundation(Eigen::MatrixXd& K) const;
  /// Drilling penalty and foundation (6n × 6n): the parts that stay elastic under plasticity.
  Eigen::MatrixXd elastic_extra() const;
  /// Membrane B (3 × (2n + 4): compatible, then the 4 incompatible modes of a quad) at a point.
  Eigen::MatrixXd membrane_b(const Point& p) const;
  /// One pass over the points at membrane (2n + modes) and bending (3n) coordinates.
  void plastic_sum(const J2Plasticity& law, const std::vector<PlasticState>& committed,
                   const Eigen::VectorXd& qm, const Eigen::VectorXd& qb, Eigen::MatrixXd& K,
                   Eigen::VectorXd& f, std::vector<PlasticState>* updated, Resultants* mean,
                   std::array<Eigen::Vector3d, kLayers>* layers) const;

  int n_;
  KernelData data_;
  std::vector<Eigen::Vector2d> xy_;
  double area_ = 0.0;
  double volume_ = 0.0;
  double total_mass_ = 0.0;
  // DK side coefficients a, b, c, d, e per side k (corner k → corner k+1).
  std::vector<std::array<double, 5>> side_;
  int n_modes_ = 0;  // incompatible membrane modes (4 for a quad, else 0)
  double detJ0_ = 0.0;
  Eigen::Matrix2d J0i_ = Eigen::Matrix2d::Identity();
  Eigen::MatrixXd Bm0_;  // centroidal membrane strain of (u, v) of all nodes, 3 × 2n
  Eigen::MatrixXd Bb0_;  // centroidal curvature of (w, θx, θy), 3 × 3n
  Eigen::MatrixXd Bs0_;  // centroidal transverse shear strain of (w, θx, θy), 2 × 3n (Mindlin)
};

/// von Mises equivalent of a plane stress state (σx, σy, τxy; σz = 0).
double plane_stress_von_mises(double sx, double sy, double sxy);

/// Plane-stress (or plate) constitutive matrix [[1,ν,0],[ν,1,0],[0,0,(1−ν)/2]]·scale.
Eigen::Matrix3d plane_stress(double nu, double scale);

}  // namespace impactfe::shell
