#pragma once
/// Rate-independent J2 (von Mises) plasticity, small strain: bilinear and multilinear isotropic
/// hardening (TB,BISO / TB,MISO / TB,PLAS,,,,BISO|MISO) and bilinear kinematic hardening
/// (TB,BKIN / TB,PLAS,,,,BKIN), APDL_MODELING §6.3. Backward-Euler radial return with the
/// algorithmic (consistent) tangent, Simo & Hughes, *Computational Inelasticity* (1998), Box 3.1
/// (1-D), Box 3.2 / eq. (3.3.14) (3-D), and plane stress by a local Newton iteration on the
/// thickness strain (σ33 = 0) around the 3-D return (its tangent is the exact static condensation
/// of the 3-D consistent tangent).
///
/// Every return is a pure function of (committed state, total strain): an element keeps the
/// committed state per integration point, evaluates trial states in its const tangent() and
/// stores the updated state only when the step has converged (Element::commit).
///
/// Beam fibres (and spars) call the uniaxial variant:
///   UniaxialPlasticState committed;            // per fibre, starts virgin
///   UniaxialPlasticState trial;
///   const UniaxialResponse r = law.uniaxial(committed, strain, &trial);
///   // r.stress, r.tangent (dσ/dε, consistent); on convergence: committed = trial.
/// `strain` is the total axial strain of the fibre (mechanical: without thermal / initial
/// strain). The law is the same object for all three variants.
#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/model.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe {

/// Committed history of one uniaxial material point (spar, beam fibre).
struct UniaxialPlasticState {
  double plastic_strain = 0.0;  ///< ε_p
  double back_stress = 0.0;     ///< β (kinematic hardening)
  double alpha = 0.0;           ///< equivalent plastic strain ∫|dε_p|
  double plastic_work = 0.0;    ///< ∫σ dε_p per unit volume (trapezoidal over the steps)
  double stress = 0.0;          ///< σ at the committed state
};

/// Committed history of one 3-D or plane-stress material point. Voigt order (xx, yy, zz, xy, yz,
/// xz); the plastic strain has engineering shear components (γ_p = 2ε_p), the back stress tensor
/// components.
struct PlasticState {
  Vector6d plastic_strain = Vector6d::Zero();
  Vector6d back_stress = Vector6d::Zero();
  double alpha = 0.0;                  ///< equivalent plastic strain ∫√(2/3)|dε_p|
  double plastic_work = 0.0;           ///< ∫σ:dε_p per unit volume
  double thickness_strain = 0.0;       ///< εzz of the last plane-stress return
  Vector6d stress = Vector6d::Zero();  ///< σ at the committed state
};

/// Flat forms of the committed states (restart files, Element::history_state): append to
/// `out`, or read from `in` at `pos` (advanced past what was read; throws when too short).
void append_state(std::vector<double>& out, const UniaxialPlasticState& s);
void append_state(std::vector<double>& out, const PlasticState& s);
void read_state(const std::vector<double>& in, std::size_t& pos, UniaxialPlasticState& s);
void read_state(const std::vector<double>& in, std::size_t& pos, PlasticState& s);

struct UniaxialResponse {
  double stress = 0.0;
  double tangent = 0.0;  ///< dσ/dε (consistent)
  bool yielding = false;
};

struct PlasticResponse {
  Vector6d stress = Vector6d::Zero();
  Matrix6d tangent = Matrix6d::Zero();  ///< dσ/dε, engineering shear strains
  bool yielding = false;
};

/// Plane-stress variant: strains and stresses (xx, yy, xy, yz, xz) with σzz = 0.
using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;
struct PlaneStressResponse {
  Vector5d stress = Vector5d::Zero();
  Matrix5d tangent = Matrix5d::Zero();
  bool yielding = false;
};

enum class HardeningKind { BilinearIsotropic, MultilinearIsotropic, BilinearKinematic, Creep };

/// An implicit creep equation of TB,CREEP (MAPDL Material Reference, implicit creep equations),
/// σ the von Mises stress, ε the equivalent creep strain, t the load-step time, T the absolute
/// temperature (temperature + TOFF):
///   1  strain hardening           ε̇ = C1 σ^C2 ε^C3 e^(−C4/T)
///   2  time hardening             ε̇ = C1 σ^C2 t^C3 e^(−C4/T)
///   3  generalized exponential    ε̇ = C1 σ^C2 r e^(−rt),  r = C5 σ^C3 e^(−C4/T)
///   6  modified time hardening    ε = C1 σ^C2 t^(C3+1) e^(−C4/T) / (C3+1)
///   7  modified strain hardening  ε̇ = [C1 σ^C2 ((C3+1) ε)^C3]^(1/(C3+1)) e^(−C4/T)
///   10 Norton                     ε̇ = C1 σ^C2 e^(−C3/T)
///   11 combined time hardening    ε = C1 σ^C2 t^(C3+1) e^(−C4/T) / (C3+1) + C5 σ^C6 t e^(−C7/T)
/// A temperature constant of 0 means no temperature term. Backward Euler, as MAPDL's implicit
/// creep: the laws given as rates (1, 2, 3, 7, 10) take the rate at the end of the substep
/// (stress, creep strain and time t_n+1) times Δt; the laws given as strains (6, 11) take the
/// difference of their strain over (t_n, t_n+1) at the end-of-substep stress (so a constant
/// stress reproduces their closed form at any step size, while time hardening 2 carries the
/// first-order error of the rectangle rule in t).
struct CreepLaw {
  int option = 0;         ///< TBOPT
  std::vector<double> c;  ///< C1, C2, ... (missing ones 0)
  double constant(std::size_t i) const { return i - 1 < c.size() ? c[i - 1] : 0.0; }
  /// The equivalent creep strain increment over the substep (t_n, t_n + dt) at the von Mises
  /// stress q (held over the substep) and the end-of-substep equivalent creep strain e.
  double increment(double q, double e, double t_end, double dt, double temperature) const;
};
/// The plasticity law of one material: elastic constants plus the hardening of its TB table.
class J2Plasticity {
 public:
  /// Bilinear: yield stress σy > 0, tangent modulus 0 ≤ Et < E (slope of σ–ε after yield).
  static J2Plasticity bilinear(double young, double poisson, double yield_stress,
                               double tangent_modulus, bool kinematic);
  /// Implicit creep without plasticity (TB,CREEP alone): the inelastic strain of the state is
  /// the creep strain, its `alpha` the equivalent creep strain. The law reads the substep's time
  /// from `clock` (shared with the solution driver).
  static J2Plasticity creep(double young, double poisson, CreepLaw law,
                            std::shared_ptr<const CreepClock> clock);
  bool has_creep() const { return kind_ == HardeningKind::Creep; }
  /// Multilinear isotropic: points (ε_p, σ) of plastic strain and true stress, ε_p ascending,
  /// the first at ε_p = 0 (σ = σy); perfectly plastic beyond the last point.
  static J2Plasticity multilinear(double young, double poisson,
                                  std::vector<std::pair<double, double>> curve);

  HardeningKind kind() const { return kind_; }
  double young() const { return young_; }
  double poisson() const { return poisson_; }
  double yield_stress() const { return isotropic_.front().second; }
  /// Isotropic flow stress k(α) and its slope k'(α).
  double flow_stress(double alpha) const;
  double flow_slope(double alpha) const;
  /// Kinematic plastic modulus H (0 unless BKIN): β̇ = (2/3) H ε̇_p (Prager), uniaxial β̇ = H ε̇_p.
  double kinematic_modulus() const { return kinematic_; }

  /// 1-D return (Simo & Hughes Box 3.1 with combined hardening).
  UniaxialResponse uniaxial(const UniaxialPlasticState& committed, double strain,
                            UniaxialPlasticState* updated) const;
  /// 3-D return (Box 3.2) and the consistent tangent (3.3.14). Engineering shear strains.
  PlasticResponse solid(const PlasticState& committed, const Vector6d& strain,
                        PlasticState* updated) const;
  /// Plane stress (σzz = 0): local Newton on εzz around the 3-D return; the tangent is the 3-D
  /// consistent tangent condensed on σzz = 0. Strain (εxx, εyy, γxy, γyz, γxz).
  PlaneStressResponse plane_stress(const PlasticState& committed, const Vector5d& strain,
                                   PlasticState* updated) const;

 private:
  /// Solves s − (c + H) Δα − k(α_n + Δα) = 0 for Δα ≥ 0 (k piecewise linear: exact per segment).
  double solve_increment(double s, double c, double alpha_n) const;
  /// Backward Euler on the equivalent creep strain: Δ = F(q_tr − cΔ, α_n + Δ) for Δ in
  /// [0, q_tr/c] (safeguarded Newton); `slope` gets dΔ/dq_tr for the consistent tangent.
  double creep_increment(double q_trial, double c, double alpha_n, double& slope) const;
  /// True when the clock asks for a creep increment now.
  bool creeping() const;

  HardeningKind kind_ = HardeningKind::BilinearIsotropic;
  double young_ = 0.0, poisson_ = 0.0;
  /// k(α): piecewise linear through these (α, k) points, extended with the last slope (bilinear:
  /// two points) or flat (multilinear) beyond the last one.
  std::vector<std::pair<double, double>> isotropic_;
  bool extend_last_slope_ = true;
  double kinematic_ = 0.0;
  CreepLaw creep_;
  std::shared_ptr<const CreepClock> clock_;
};

/// von Mises equivalent of a Voigt stress (tensor shear components).
double von_mises(const Vector6d& stress);

/// The plasticity law of material `record.mat` when it has a TB plasticity table (BISO, BKIN,
/// MISO, TB,PLAS with those options), nullopt otherwise. Throws InputError (at the TB command)
/// for data it cannot use: missing σy, Et ≥ E, a MISO curve that does not start at ε_p = 0 or
/// whose stress falls, more than one temperature, or a law not implemented (KINH, MKIN).
/// TB,CREEP (implicit TBOPT) gives the creep law of J2Plasticity::creep; a material with both a
/// creep and a plasticity table is refused, and so is creep where `implicit` is false (explicit
/// dynamics elements).
std::optional<J2Plasticity> plasticity_of(const Model& model, const ElementRecord& record,
                                          double young, double poisson, bool implicit = true);

}  // namespace impactfe
