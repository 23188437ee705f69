#pragma once
/// Three-node quadratic 3-D beam (BEAM189): nodes I, J (ends), K (midside), optional
/// orientation node L. Small deflection (with stress stiffening), linear elastic.
///
/// Kinematics: isoparametric Timoshenko beam, positions, displacements u and rotations θ
/// interpolated by the quadratic Lagrange functions of ξ ∈ [−1, 1] (I at −1, K at 0, J at +1),
/// so a midside node off the chord makes the element curved. At a point of the axis with unit
/// tangent t = x_ξ/|x_ξ| and section axes (e2, e3) the generalised strains are the linearised
/// ones of the geometrically exact (Reissner–Simo) rod, Γ = Λ0ᵀ(u' + t × θ), K = Λ0ᵀ θ' (Simo &
/// Vu-Quoc 1986, CMAME 58, eqs. 2.11, linearised; ' = d/ds):
///   ε0 = t·u',  κy = e2·θ',  κz = e3·θ',  twist = t·θ',
///   γy = e2·u' − e3·θ,  γz = e3·u' + e2·θ
/// (on a straight element along x: u', v' − θz, w' + θy as BEAM188). A rigid motion
/// u = c + ω × x, θ = ω gives zero strain exactly, curved or not, since x_ξ is interpolated
/// with the same functions as u.
///
/// Integration: two Gauss points along the axis for every term (reduced for the shear, which
/// removes shear locking; Zienkiewicz & Taylor, The Finite Element Method, vol. 2, §13.3). The
/// 2-point rule keeps the element's rank (no spurious zero-energy mode: 2 points × 6 strains =
/// 12 = 18 DOFs − 6 rigid motions). With the shear strain sampled at the Gauss points the
/// element is the mixed element with linear shear strain: for an end load on a cantilever it
/// gives the exact Timoshenko rotations and nodal deflections (the projection error of the
/// quadratic rotation, a multiple of the Legendre P2, integrates to zero over each half of the
/// element), and a constant moment exactly. The section stiffness D = (fibre sum of E for N, My,
/// Mz; GJ; G kA_y, G kA_z) is the one of BEAM188 (elements/beam_section.h). A section without shear
/// areas (ASEC) is shear-rigid: its shear stiffness is a penalty, 10⁵ times the bending
/// stiffness 12 EI/ℓ² of the element length ℓ, which leaves 10⁻⁵ of shear flexibility (reduced
/// integration does not lock under it).
///
/// Mass: consistent ∫ Nᵀ m N ds with m = diag(ρA I₃, R diag(ρ(Iyy + Izz), ρIyy, ρIzz) Rᵀ)
/// (translational and rotary inertia, R the section axes), 3-point Gauss; lumped (LUMPM): the
/// row sums of each node's blocks (1/6, 2/3, 1/6 of a straight element's mass).
///
/// Stress stiffening (SSTIF, PSTRES, buckling): the axial strain takes the moderate-rotation
/// term ½ u'ᵀ(I − t tᵀ)u', which adds N Gᵀ(I − t tᵀ)G (G: u' = G u) at each Gauss point, the
/// exact derivative of f_int (BEAM188's (Δv² + Δw²)/(2L²); Cook et al. §18.3).
///
/// Results: the generalised stresses D (B u − ε_th) of the two Gauss points, extrapolated
/// linearly to I and J and interpolated to K (section axes; the signs of BEAM188's −f at I, +f at
/// J); nominal extreme-fibre stresses at I and J.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "elements/beam_section.h"
#include "elements/element.h"

namespace impactfe {

/// What a BEAM189 is built from (its factory fills it).
struct QuadraticBeamData {
  std::array<int, 3> nodes{};  // I, J, K
  std::array<Vec3, 3> x{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  /// Element z of the I-J chord's axes (orientation node L or the default rule, beam_frame);
  /// the section axes at a point are e3 = this projected normal to the tangent, e2 = e3 × t.
  Vec3 z_reference = Vec3::UnitZ();
  BeamSectionProperties section;
  double youngs_modulus = 0.0;
  double shear_modulus = 0.0;
  double density = 0.0;
};

/// Result names of BEAM189: those of the 2-node beams at I and J (FX MY MZ TQ SFZ SFY, SDIR
/// SBYT SBYB SBZT SBZB, SMAX SMIN), then the section forces at K.
const std::vector<std::string>& quadratic_beam_result_names();

class QuadraticBeam final : public Element {
 public:
  using Vec18 = Eigen::Matrix<double, 18, 1>;
  using Mat18 = Eigen::Matrix<double, 18, 18>;
  using StrainMatrix = Eigen::Matrix<double, 6, 18>;

  /// Throws std::invalid_argument with a user message for a bad geometry (the factory adds
  /// the record's location).
  QuadraticBeam(int id, QuadraticBeamData data);

  const char* family() const override { return "QuadraticBeam"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  std::optional<double> volume() const override { return data_.section.area * length_; }
  /// Equivalent nodal forces of the axial thermal strain ε_th = ALPX ΔT(ξ), ΔT interpolated from
  /// the temperature changes at I, J, K: ∫ Bᵀ D (ε_th, 0, ...) ds (2-point Gauss, as K).
  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;

  /// Work-equivalent nodal loads of a force per length on face `face` (SFBEAM, SFE; the faces
  /// of BEAM188). Small deflection: the load acts on the initial axis.
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;

  /// Arc length of the axis (3-point Gauss of |x_ξ|, exact for a straight element).
  double length() const { return length_; }
  /// Section axes at ξ (columns: tangent x, y, z in global components).
  Eigen::Matrix3d axes_at(double xi) const;
  /// Generalised strains (ε0, κy, κz, twist, γy, γz) = B u at ξ, and |x_ξ|.
  StrainMatrix strain_matrix(double xi, double* jacobian = nullptr) const;
  /// Section stiffness on the generalised strains.
  const Eigen::Matrix<double, 6, 6>& section_stiffness() const { return D_; }
  const Mat18& stiffness() const { return K_; }

 private:
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  /// Internal force f, tangent K and Gauss-point generalised stresses sg[2] at u (each when
  /// asked); `stiffening` adds the moderate-rotation axial strain, `thermal` takes ε_th off.
  void evaluate(const Vec18& u, bool stiffening, bool thermal, Vec18* f, Mat18* K, Vec6* sg) const;
  /// ε_th at ξ from the temperature change set last (0 without one).
  double thermal_strain(double xi) const;
  Vec18 thermal_forces() const;

  QuadraticBeamData data_;
  std::vector<DofKey> dofs_;
  double length_ = 0.0;
  Eigen::Matrix<double, 6, 6> D_ = Eigen::Matrix<double, 6, 6>::Zero();
  Mat18 K_ = Mat18::Zero();
};

}  // namespace impactfe
