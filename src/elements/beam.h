#pragma once
/// Two-node 3-D beam (BEAM188, BEAM4, and BEAM3 as its X-Y restriction; APDL_MODELING §8.1-8.2).
///
/// Kinematics: Timoshenko beam with linear interpolation of the displacements and rotations,
/// evaluated at one point (mid-length): axial strain ε0 = Δu/L, curvatures κy = Δθy/L,
/// κz = Δθz/L, twist Δθx/L, shear strains γy = Δv/L − (θz1 + θz2)/2, γz = Δw/L + (θy1 + θy2)/2.
/// One-point integration removes shear locking; the shear stiffness is reduced by the residual
/// bending flexibility, 1/S = 1/(kGA) + L²/(12EI) (MacNeal 1978, Computers & Structures 8,
/// "A simple quadrilateral shell element", §3), which makes the 2-node element's stiffness the
/// exact Timoshenko stiffness of a prismatic beam (Przemieniecki, Theory of Matrix Structural
/// Analysis, §5.6, with Φ = 12EI/(kGAL²)); kA = 0 gives the Euler–Bernoulli beam (S = 12EI/L²).
/// Axial force and bending moments come from the section's fibres (elements/beam_section.h).
///
/// Plasticity (BEAM188 with a TB BISO / BKIN / MISO table): every fibre of the section at the
/// integration point is a uniaxial J2 material point (J2Plasticity::uniaxial, Simo & Hughes
/// Box 3.1) driven by its axial strain ε = ε0 + z κy − y κz; the section tangent is the fibre sum
/// of the consistent fibre tangents, so K_T is exact. Torsion (GJ) and transverse shear (S) stay
/// elastic, and so does the residual bending flexibility in S (the linear part of the curvature
/// of the one-point element): as in MAPDL's linear BEAM188, plastic flow is evaluated at the one
/// integration point at mid-length, so a plastic hinge at a node is felt by the elements beside
/// it half an element away (docs/plasticity.md: mesh finely where hinges form). Fibre states are
/// committed on converged steps (commit_history); tangent() returns from the committed ones.
///
/// Mass: consistent = linear interpolation for the axial and torsional inertia and the cubic
/// (Hermite) interpolation for the bending translations and rotary inertia (Przemieniecki
/// §11.3); lumped = ρAL/2 per translation and ρIL/2 per rotation.
///
/// Stress stiffening (small deflection): the axial strain takes the moderate-rotation term
/// (Δv² + Δw²)/(2L²), which adds (N/L)[1 −1; −1 1] on the transverse translations (Cook et al.,
/// Concepts and Applications of FEA, 4th ed., §18.3) and is the exact derivative of f_int.
///
/// Large deflection: co-rotational, the local element above in a frame that follows the chord
/// and the mean of the nodal triads (Battini & Pacoste 2002, CMAME 191, §3: r1 along the chord,
/// r3 ∝ r1 × q, q = (R1 + R2) R0 e2 / 2); local deformational rotations θ̄ = log(Rrᵀ R R0) as in
/// the co-rotational shell. f_int = Bᵀ f_l; K = Bᵀ K_l B + ∂(Bᵀ f_l)/∂u|f_l, the second (geometric)
/// term analytic (Battini & Pacoste 2002, §3.3: variations of the chord, of the frame through
/// its spin δω = W δp, of T(θ̄)⁻ᵀ and T(ψ)ᵀ through the so3 derivatives); it equals a central
/// difference of f_int to 3e-11 relative (test_beam), and the tangent is then symmetrised.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "elements/beam_section.h"
#include "elements/element.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// What a beam element is built from (the factories of BEAM188 / BEAM4 / BEAM3 fill it).
struct BeamData {
  int node_i = 0, node_j = 0;
  Vec3 xi = Vec3::Zero(), xj = Vec3::Zero();
  /// Element axes in global components: columns x (I → J), y, z.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  /// Element DOF positions kept out of the 12 (node I: UX..ROTZ, node J: UX..ROTZ); BEAM3
  /// keeps UX, UY, ROTZ.
  std::vector<int> active;
  BeamSectionProperties section;
  double youngs_modulus = 0.0;
  double shear_modulus = 0.0;
  double density = 0.0;
  double added_mass = 0.0;      // mass per length (BEAM3/BEAM4 ADDMAS)
  double initial_strain = 0.0;  // ISTRN (BEAM3/BEAM4)
  bool lumped_mass = false;     // BEAM4 KEYOPT(2) = 1
  /// BEAM188 with a TB plasticity table: the law of every fibre (geometric sections only).
  std::optional<J2Plasticity> plasticity;
};

/// Result names of every beam type: section forces at I and J (FX MY MZ TQ SFZ SFY), extreme-fibre
/// stresses at I and J (SDIR SBYT SBYB SBZT SBZB), SMAX/SMIN at I and J, and the plastic items of
/// the section point (EPEQ: largest fibre equivalent plastic strain, SRAT: largest fibre
/// |σ − β| / k(α), 1 on the yield surface, PLWK: plastic work per volume; 0 when elastic).
const std::vector<std::string>& beam_result_names();

class Beam final : public Element {
 public:
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  Beam(int id, BeamData data);

  const char* family() const override { return "Beam"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;
  /// Equivalent nodal forces of the axial thermal strain ε_th = ALPX ΔT (ΔT the mean of the end
  /// temperatures): the section resultants D (ε_th, 0, 0) applied at the ends, −at I, +at J.
  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;
  /// Work-equivalent nodal loads of a force per length on face `face` (SFBEAM, SFE): MAPDL's
  /// beam faces, normal loads with the Hermite moments; follows the element under large
  /// deflection. The section forces stay those of the nodal displacements (K u), as the
  /// one-point element reports them: mesh finely where a distributed load acts.
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  std::optional<double> volume() const override { return data_.section.area * length_; }

  bool has_history() const override { return data_.plasticity.has_value(); }
  double plastic_work() const override;
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  /// Committed fibre states (one per section fibre; empty for an elastic beam).
  const std::vector<UniaxialPlasticState>& fibre_states() const { return committed_; }
  const BeamSectionProperties& section() const { return data_.section; }

  double length() const { return length_; }
  /// Shear stiffnesses S_y, S_z after the residual-bending-flexibility correction.
  double shear_stiffness_y() const { return shear_y_; }
  double shear_stiffness_z() const { return shear_z_; }
  /// Local element force vector (element axes, 12 components: node I then J, forces then
  /// moments) at u; the section forces are −f at I and +f at J.
  /// With `states`, the fibre states at u (returned from the committed ones) are stored there.
  Vec12 local_forces(const ElementContext& ctx, const Eigen::VectorXd& u,
                     std::vector<UniaxialPlasticState>* states = nullptr) const;

 private:
  struct Corotated {
    Eigen::Matrix3d Rr;
    Vec12 d;  // local deformational displacements (ū at 6, θ̄1 at 3..5, θ̄2 at 9..11)
    // With B: what the analytic geometric stiffness needs (δp = [δx1, δw1, δx2, δw2]).
    Mat12 Bp;                        // δd = Bp δp (before the T(ψ) factors)
    Eigen::Matrix<double, 3, 12> W;  // frame spin, local components: δω = W δp
    Vec3 q1l, q2l;                   // R_a R0 e2 in the frame
    double ln = 0.0;                 // current chord length
  };
  Vec12 expand(const Eigen::VectorXd& u) const;
  /// Section resultants (N, My, Mz) of the thermal strain at the temperature change set last.
  Eigen::Vector3d thermal_resultants() const;
  void restrict(const Vec12& f, const Mat12& K, Eigen::VectorXd& f_out,
                Eigen::MatrixXd& K_out) const;
  /// Section resultants (N, My, Mz) and tangent at (ε0, κy, κz) through the fibres; plastic
  /// fibres return from their committed states (`updated` receives the new ones).
  void section_response(const Eigen::Vector3d& e, Eigen::Vector3d& s, Eigen::Matrix3d& D,
                        std::vector<UniaxialPlasticState>* updated = nullptr) const;
  /// Local response at local displacement d (element axes): f_l and K_l; `stiffening` adds the
  /// moderate-rotation axial strain.
  void local_response(const Vec12& d, bool stiffening, Vec12& f, Mat12* K,
                      std::vector<UniaxialPlasticState>* updated = nullptr) const;
  /// Local deformational displacements at global U (co-rotated under large deflection).
  Vec12 local_displacement(const ElementContext& ctx, const Vec12& U) const;
  Corotated corotate(const Vec12& u, Mat12* B) const;
  /// ∂(Bᵀ f_l)/∂u at fixed f_l (the geometric part of the co-rotational tangent), analytic.
  Mat12 corotational_geometric(const Vec12& u, const Corotated& c, const Vec12& fl) const;
  Mat12 rotation() const;  // T: local = T global

  BeamData data_;
  std::vector<DofKey> dofs_;
  double length_ = 0.0;
  double torsion_stiffness_ = 0.0;  // GJ
  double shear_y_ = 0.0, shear_z_ = 0.0;
  Mat12 K_linear_;             // local linear stiffness
  Eigen::Matrix3d D_elastic_;  // elastic section stiffness (nominal stresses of the results)
  std::vector<UniaxialPlasticState> committed_;  // per fibre (plastic beams)
};

}  // namespace impactfe
