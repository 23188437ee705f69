#pragma once
/// The point contact law shared by CONTA178 (node to node) and CONTA175 (node to a rigid
/// target surface), APDL_MODELING §8.4. Two points I (for CONTA175: the target's pilot node) and
/// J (the contact node), each with UX, UY, UZ (in 2-D, TARGE169, UX, UY only and the vectors
/// below with z = 0: elements/target_line.h); a contact normal n pointing from the I side to the
/// J side and the gap g = g0 + n·(u_J − u_I), closed when g ≤ 0 (penetration −g). CONTA178 has
/// a fixed n and g0; CONTA175 re-finds them by the contact search before each status update
/// (the locate() hook), so its DOF list - and the assembly pattern - does not change within a
/// step (large sliding on a deformable target changes it between steps, connectivity.h).
///
/// Normal contact (Wriggers, Computational Contact Mechanics, 2nd ed., §5.2 penalty, §5.3 and
/// §10.3.4 augmented Lagrange): compressive force p = λ − k_n g while closed. KEYOPT(2) = 1 is
/// the pure penalty method (λ = 0); KEYOPT(2) = 0 (default) is augmented Lagrange: after an
/// iteration that leaves the status unchanged with a penetration above the tolerance, the
/// multiplier is updated λ ← λ − k_n g (Uzawa step) and the iteration is declared unconverged,
/// at most kMaxAugmentations times per substep; λ is committed with the step and carried into
/// the next one, so a lasting contact converges to the exact constraint over the substeps.
/// A contact is closed only while it penetrates (g ≤ 0, as MAPDL: no force across an open gap;
/// with a multiplier λ > 0, g ≤ 1e-8 λ/k_n, the round-off around the g = 0 that the multiplier
/// converges to) and opening releases λ: a multiplier kept across a positive gap would push the
/// bodies apart beyond the surface and give back more energy than the impact put in.
///
/// Tangential contact: Coulomb friction with elastic slip (Wriggers §5.2.3; the return map of
/// the COMBIN40 slider in 3-D): trial force ξ = k_t (u_t − s) with the relative tangential
/// displacement u_t = (I − n nᵀ)(u_J − u_I) and the committed slip s; sticking when |ξ| ≤ μ p,
/// sliding with force μ p ξ/|ξ| otherwise. The sliding tangent keeps the symmetric part
/// μ p k_t/|ξ| (I − d dᵀ) and drops the non-symmetric coupling μ k_n d nᵀ (the linear solvers
/// are symmetric): Newton converges linearly while sliding, the residual is exact.
///
/// Kinematics (ContactKinematics): the law sees the gap g(u), its gradient G = ∂g/∂u, its Hessian
/// H = ∂²g/∂u² and the tangential relative displacement u_t(u) with T = ∂u_t/∂u over the element's
/// DOFs. A point pair (CONTA178, a rigid target) has G = [−n; n], T = [−P, P] and H = 0; a node
/// against a deformable facet (elements/target_surface.h DeformableTargetPoint) has the facet
/// nodes in its DOFs and H ≠ 0 (the variation of the normal and of the projection point). With
/// the compressive force p the element force is f = −p G + Tᵀ f_t and the tangent
/// K = k_n G Gᵀ − p H + Tᵀ K_t T + Σ_k f_t,k ∂²u_t,k/∂u² (Wriggers §4.2, eq. 4.36 and §9.3 for
/// the node-to-segment case): consistent, and symmetric for normal contact and sticking; K_t is
/// ∂f_t/∂u_t in full (k_t I sticking, μ p k_t/|ξ| (I − d dᵀ) sliding), since on a deformable or
/// rotating target T also has components along n. Sliding still drops μ k_n Tᵀ d Gᵀ (above).
///
/// Behaviour (KEYOPT(12)): 0 standard, 1 rough (no sliding, separation allowed), 2 no separation
/// once closed (frictionless), 3 bonded once closed, 4 no separation always, 5 bonded always,
/// 6 bonded when initially closed (never in contact when initially open).
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "elements/element.h"
#include "elements/penetration_check.h"

namespace impactfe {

struct ResultSequence;  // elements/element_registry.h

enum class ContactBehaviour {
  Standard = 0,
  Rough = 1,
  NoSeparation = 2,
  Bonded = 3,
  NoSeparationAlways = 4,
  BondedAlways = 5,
  BondedInitial = 6
};

struct ContactLawData {
  Vec3 normal = Vec3::UnitX();  // unit, from the I side towards J
  double gap0 = 0.0;            // gap at u = 0 along the normal (negative: interference)
  double kn = 0.0;              // normal penalty stiffness, force/length
  double kt = 0.0;              // sticking stiffness, force/length
  double mu = 0.0;              // Coulomb coefficient (MP,MU of the element's MAT)
  bool augmented = true;        // KEYOPT(2) = 0
  double toln = 0.0;            // absolute penetration tolerance; 0: relative rule (1 %)
  /// KEYOPT(7) = 1: under AUTOTS a converged substep with a penetration above toln is cut
  /// (elements/penetration_check.h).
  bool bisect_on_penetration = false;
  ContactBehaviour behaviour = ContactBehaviour::Standard;
  int start = 0;  // > 0 initially closed, < 0 initially open, 0 from the gap
};

/// The geometry of the contact point at u (see above), over the element's DOFs.
struct ContactKinematics {
  double gap = 0.0;             // g(u), CNOF included (negative: penetration)
  Vec3 normal = Vec3::UnitX();  // unit, from the target towards the contact node
  Vec3 ut = Vec3::Zero();       // tangential relative displacement u_t
  Eigen::VectorXd G;            // ∂g/∂u
  Eigen::MatrixXd T;            // ∂u_t/∂u (3 × n_dofs)
  Eigen::MatrixXd H;            // ∂²g/∂u² (empty: zero)
};

class ContactPoint : public Element, public PenetrationCheck {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  /// Augmented-Lagrange updates per substep; with the closing flip this stays below the status
  /// loop's chatter limit (4), so augmentation alone never freezes an element.
  static constexpr int kMaxAugmentations = 2;

  ContactPoint(int id, int node_i, int node_j, const ContactLawData& data);
  /// A point with its own DOF list (UX, UY, UZ of each node; a deformable target's facet nodes).
  ContactPoint(int id, std::vector<DofKey> dofs, const ContactLawData& data);

  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return true; }
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override {
    M.setZero(n_dofs(), n_dofs());
  }

  bool has_status() const override { return true; }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  void commit(const Eigen::VectorXd& u) override;
  void revert() override;
  void freeze_status(bool frozen) override { frozen_ = frozen; }
  GapStatus status() const override;
  /// The committed contact state for restart files: status, augmented-Lagrange multiplier, the
  /// slip of the tangential spring (the stick anchor), the accumulated sliding distance and the
  /// no-separation / bonded flags — kStateSize values. Without them a continued run would
  /// re-derive the anchor and the sliding distance from the displacements alone.
  static constexpr std::size_t kStateSize = 8;
  bool checks_penetration() const override { return data_.bisect_on_penetration; }
  /// (p(u) − p(start)) / toln where p(u) = max(−g(u), 0) > toln, for a closed contact with
  /// KEYOPT(7) = 1 and a tolerance (both gaps on the facet located at u); else 0.
  double penetration_ratio(const Eigen::VectorXd& start, const Eigen::VectorXd& u) const override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  double contact_stiffness() const override { return data_.kn; }

  /// STAT (0 open, 2 sliding, 3 sticking: MAPDL contact codes), FN (normal force, compression
  /// positive), PENE, GAP, FT (friction force), SLIDE (accumulated sliding distance).
  static const std::vector<std::string>& names();
  /// The CONT items of ETABLE / ESOL / *GET (APDL_MODELING §8.4) on names(): STAT, PRES (the
  /// normal force FN of a contact point), PENE, GAP, SFRIC (FT), SLIDE; shared by every
  /// contact element type's registration.
  static const std::vector<ResultSequence>& sequences();
  const std::vector<std::string>& result_names() const override { return names(); }
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  const ContactLawData& law() const { return data_; }

 protected:
  /// Contact search hook, called before each status update at u: sets data_.normal and
  /// data_.gap0 for the current closest target point and returns false when no target is
  /// within reach (the contact is then open). Node to node: fixed geometry, always true.
  virtual bool locate(const Eigen::VectorXd& u) { return true; }
  /// The geometry at u. Default: the pair I, J of the first constructor with the located normal
  /// and gap0: g = g0 + n·(u_J − u_I), u_t = P (u_J − u_I).
  virtual ContactKinematics kinematics(const Eigen::VectorXd& u) const;
  /// Adds Σ_k f_t,k ∂²u_t,k/∂u² at u for the friction force f_t (held fixed): the part of the
  /// friction tangent ∂(Tᵀ f_t)/∂u that comes from the variation of T itself. Default: none (a
  /// point pair's T = [−P, P] is constant between two searches).
  virtual void add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                                      Eigen::MatrixXd& K) const {}
  /// Sets the initial status from the geometry (call at the end of a derived constructor when
  /// locate() found the initial normal).
  void initialize();
  /// A new DOF list (large sliding on a deformable target, between steps); the contact state
  /// (status, multiplier, slip) is the point's and stays.
  void set_dofs(std::vector<DofKey> dofs) { dofs_ = std::move(dofs); }

  ContactLawData data_;

 private:
  enum class Contact { Open, Stick, Slide };
  struct State {
    Contact status = Contact::Open;
    double lambda = 0.0;       // augmented-Lagrange multiplier (compressive force)
    Vec3 slip = Vec3::Zero();  // slip s of the tangential spring
    double slide = 0.0;        // accumulated sliding distance
    bool tied = false;         // no separation / bonded: closed for good
    bool never = false;        // bonded-initial contact that started open
    int augmentations = 0;     // multiplier updates in this substep
  };
  struct Response {
    double gap = 0.0, pn = 0.0, kn = 0.0;  // gap, compressive force, its stiffness
    Vec3 ut = Vec3::Zero(), ft = Vec3::Zero();
    Eigen::Matrix3d kt = Eigen::Matrix3d::Zero();
  };

  bool always_tied() const;
  bool bonded() const;
  bool frictionless() const;
  bool never_slides() const;
  Response response(const State& s, const ContactKinematics& kin) const;
  /// The status the contact rules give at u, starting from the trial status.
  State next_state(const Eigen::VectorXd& u, bool in_range) const;

  std::vector<DofKey> dofs_;
  State committed_;
  State trial_;
  bool frozen_ = false;
};

/// Stiffness of the elements attached to `node` along n (Σ nᵀ K_nn n of their translational
/// blocks at u = 0): the base that a positive FKN scales. Status elements (gaps, contact) and
/// superelements are skipped; 0 when nothing stiff is attached.
double attached_stiffness(const ElementBuildContext& ctx, int node, const Vec3& n);

/// UX, UY, UZ of each node in order: the DOF list of a contact point over `nodes`.
std::vector<DofKey> translation_dofs(const std::vector<int>& nodes);
/// Contact depth of `node`: the cube root of the mean volume of the attached elements that
/// have one (bricks); 0 when none has a volume.
double attached_depth(const ElementBuildContext& ctx, int node);

}  // namespace impactfe
