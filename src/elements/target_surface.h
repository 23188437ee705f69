#pragma once
/// Contact targets (TARGE170, APDL_MODELING §8.4): the target facets of one real-constant set
/// (triangles and quadrilaterals, a quadrilateral as two triangles, so it should be planar).
/// Either **rigid**, moving with their pilot node (a one-node TARGE170; turning with the pilot's
/// rotations when the pilot carries rotational DOFs), or, without a pilot, **deformable**: the
/// facets are meshed on a deformable body and move with its nodes. A spatial bucket grid over the
/// facets in their initial position answers the closest-facet query of the rigid case (the target
/// moves rigidly, so the grid is built once and queried in the target's own frame) and the
/// candidate query of the deformable case (small sliding, DeformableTargetPoint).
#include <array>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/coordinate_system.h"
#include "elements/connectivity.h"
#include "elements/contact_point.h"
#include "elements/element.h"

namespace impactfe {

/// How far (a fraction of the facet, in its parametric or barycentric coordinates) a contact
/// node or integration point may lie beyond a free edge of a target and still touch it [A]: a
/// point on the rim of a target that deforms with it (two blocks of the same width) sits on the
/// edge to round-off and would otherwise chatter open and closed.
inline constexpr double kTargetEdgeTolerance = 0.01;

class TargetSurface {
 public:
  struct Triangle {
    Vec3 a, b, c;
    Vec3 normal;  // unit, right-hand rule of the node order: towards the contact side
    std::array<int, 3> nodes{};  // node numbers of a, b, c
  };
  struct Hit {
    Vec3 normal;
    double gap = 0.0;  // signed distance from the facet plane along the normal
  };

  /// `rotates`: the pilot carries rotations (an element with ROTX..ROTZ is attached to it).
  TargetSurface(int pilot, std::vector<Triangle> triangles, bool rotates = false);

  /// The pilot node of a rigid target; 0 for a deformable one.
  int pilot() const { return pilot_; }
  /// A rigid target that turns with its pilot's rotations (RigidTargetPoint).
  bool rotates() const { return rotates_; }
  bool deformable() const { return pilot_ == 0; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// The facet whose plane is nearest to y (in the target's initial frame) among the facets
  /// that y projects into and that lie within `reach` of it; nullopt when none does.
  std::optional<Hit> closest(const Vec3& y, double reach) const;
  /// The facets (indices into triangles()) whose bounding box comes within `reach` of y and
  /// whose plane is within `reach` of y: the candidates of a deformable target's contact node.
  std::vector<int> near(const Vec3& y, double reach) const;
  /// The same in the current configuration of a deformable target (large sliding): the facets
  /// whose current bounding box and plane come within `reach` of x. A bucket grid over the
  /// current facets is rebuilt only when a target node has moved more than a quarter of `reach`
  /// since the last build (checked once per refresh pass); in between a query widens its reach
  /// by the largest such movement and tests the current geometry, so it misses nothing.
  std::vector<int> near_current(const Vec3& x, double reach, const NodePositions& at) const;
  /// How many times near_current() built its grid (the first build included).
  int current_grid_builds() const;

 private:
  long long key(long long i, long long j, long long k) const;
  void cell_range(const Vec3& lo, const Vec3& hi, Eigen::Vector3i& a, Eigen::Vector3i& b) const;

  struct Current;  // near_current()'s grid over the deformed facets
  mutable std::shared_ptr<Current> current_;
  int pilot_;
  bool rotates_;
  std::vector<Triangle> triangles_;
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1.0;
  std::unordered_map<long long, std::vector<int>> buckets_;
};

/// The target of real-constant set `real`: every TARGE170 element of that set. With one
/// one-node pilot element the target is rigid; without a pilot it is deformable, and every facet
/// node must belong to a body element (one that is neither a target nor a contact element). Built
/// once per model and set and shared by the contact elements. InputError at `record`'s location
/// when the set has no target facets, two pilots, or a pilot-less facet on no body.
std::shared_ptr<const TargetSurface> contact_target(const ElementBuildContext& ctx,
                                                    const ElementRecord& record);

/// One contact node against the rigid target of its real set (CONTA175, and each face node of a
/// CONTA174): the point law of elements/contact_point.h with I = the target's pilot node and
/// J = the contact node. Before each status update the search finds the facet nearest to
/// y = X + u_node − u_pilot (the node in the target's frame) and sets the normal and
/// g₀ = distance − CNOF − n·(u_node − u_pilot).
///
/// A rotating target (TargetSurface::rotates(): the pilot carries ROTX, ROTY, ROTZ) turns with
/// the pilot's rotation vector ψ (the rotation DOFs are a rotation vector, as for the
/// co-rotational shell, elements/so3.h): a target point moves to x = x_P + R(ψ)(X − X_P). The
/// DOFs are then the pilot's UX, UY, UZ, the node's, then the pilot's ROTX, ROTY, ROTZ; the search
/// runs on y = X_P + R(ψ)ᵀ(x_s − x_P) (the node in the target's initial frame), the gap is
/// g = n₀·y − c₀ − CNOF (n₀, c₀ the facet's initial plane) and the tangential displacement is
/// that of the node against the target's material point that started at X_s,
/// u_t = (I − n nᵀ)(x_s − x_P − R(X_s − X_P)), n = R n₀. Their exact first and second
/// derivatives (elements/hyper_dual.h) give the force, the moment conjugate to ψ and the
/// consistent tangent with the rotation terms.
class RigidTargetPoint final : public ContactPoint {
 public:
  /// `pilot_x`: the pilot's initial position (used by a rotating target only).
  RigidTargetPoint(const char* family, int id, int node, const Vec3& x, const Vec3& pilot_x,
                   std::shared_ptr<const TargetSurface> target, double reach, double offset,
                   const ContactLawData& data);
  const char* family() const override { return family_; }

 protected:
  bool locate(const Eigen::VectorXd& u) override;
  ContactKinematics kinematics(const Eigen::VectorXd& u) const override;
  void add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                              Eigen::MatrixXd& K) const override;

 private:
  const char* family_;
  Vec3 x_;
  Vec3 pilot_x_;
  std::shared_ptr<const TargetSurface> target_;
  double reach_;   // pinball radius
  double offset_;  // CNOF
  bool rotating_;
  Vec3 n0_ = Vec3::UnitZ();  // rotating: the located facet's normal and plane n₀·X = c₀
  double c0_ = 0.0;
};

/// One contact node against a deformable target (no pilot). Its DOFs are the contact node's
/// then the nodes of its **candidate** facets, UX, UY, UZ; before each status update the search
/// picks, among the candidates in their current (deformed) position, the facet the node projects
/// into with the smallest |gap|; a node in none of them (the gap between the projections on two
/// facets meeting at a convex edge) takes the nearest one when it lies beyond an edge shared with
/// another candidate. The candidates are fixed within a step (a static assembly pattern while
/// Newton iterates) and found:
///
/// * **large sliding** (the default, MAPDL's): after each accepted step (refresh_dofs) the node
///   checks the facets within its pinball in the current configuration
///   (TargetSurface::near_current); when one of them is not a candidate, the candidates become
///   the facets within kLargeSlidingMargin × the pinball (plus the facet in use) and the driver
///   renumbers. The margin keeps the set valid while the node slides another half pinball, so the
///   DOF lists change once per half pinball of travel, not every step. A node that still leaves
///   its candidates within one step is an ElementSolutionError asking for smaller steps.
/// * **small sliding** [A] (KEYOPT(18) = 1): the candidates are those near() the node's initial
///   position within the pinball, for the whole run; a node that leaves them across an edge
///   shared with a non-candidate facet within the pinball is an ElementSolutionError telling
///   the user to enlarge PINB.
///
/// Kinematics on the chosen facet (a triangle x₁ x₂ x₃, current positions): n = e₁×e₂/|e₁×e₂|,
/// e_α = x_{α+1} − x₁; the projection x_p = Σ N_a x_a with N = (1−ξ₁−ξ₂, ξ₁, ξ₂) solving
/// e_α·(x_s − x_p) = 0; g = n·(x_s − x₁) − CNOF. Its variation δg = n·(δx_s − Σ N_a δx_a) and
/// the Hessian from Δn = (I − nnᵀ)(Δe₁×e₂ + e₁×Δe₂)/|e₁×e₂| and
/// Δξ = M⁻¹[e_α·Δr + g n·Δe_α], M_αβ = e_α·e_β (Wriggers §9.3 / Laursen §5.2, node-to-segment):
/// Δδg = Δn·δr − Δξ_α n·δe_α. The tangential relative displacement is u_t = P (u_s − Σ N_a u_a)
/// = P (Σ N_a X_a − X_s) (x_s − x_p = g n): the tangential distance of the target's material
/// point under the node from the node's initial place, continuous from facet to facet, so it
/// also measures the slip of large sliding; T its exact first derivative.
class DeformableTargetPoint final : public ContactPoint, public ConnectivityUpdate {
 public:
  /// The candidate set is re-found over this multiple of the pinball (large sliding).
  static constexpr double kLargeSlidingMargin = 1.5;
  /// `facets`: the candidate facet indices; `nodes`: the contact node then the distinct nodes of
  /// the candidates (the element's DOF order), with `x` their initial positions.
  DeformableTargetPoint(const char* family, int id, std::vector<int> nodes, std::vector<Vec3> x,
                        std::shared_ptr<const TargetSurface> target, std::vector<int> facets,
                        double reach, double offset, const ContactLawData& data,
                        bool large_sliding = false);
  const char* family() const override { return family_; }
  /// The candidate facet in use (index into the target's triangles), -1 without candidates.
  int facet() const { return facets_.empty() ? -1 : facets_[static_cast<std::size_t>(current_)]; }
  const std::vector<int>& candidates() const { return facets_; }
  bool refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) override;

 protected:
  bool locate(const Eigen::VectorXd& u) override;
  ContactKinematics kinematics(const Eigen::VectorXd& u) const override;
  /// Σ_k f_t,k ∂²u_t,k/∂u² on the facet in use, by second-order automatic differentiation.
  void add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                              Eigen::MatrixXd& K) const override;

 private:
  struct Candidate {
    std::array<int, 3> local{};  // positions of the facet's nodes in nodes_
    // The edge opposite vertex a: 0 a free edge of the target, 1 shared with another candidate,
    // 2 shared with a non-candidate facet only.
    std::array<int, 3> edge{};
  };
  /// candidates_ from nodes_ and facets_ (edge neighbours found in the initial configuration).
  void classify();
  const char* family_;
  std::vector<int> nodes_;
  std::vector<Vec3> x_;
  std::shared_ptr<const TargetSurface> target_;
  std::vector<int> facets_;
  std::vector<Candidate> candidates_;
  int current_ = 0;
  double reach_;
  double offset_;
  bool large_sliding_;
};

/// The KEYOPTs and real constants of a surface contact element (CONTA171/172/174/175) that
/// impactfe carries out; any other value is an InputError naming `record` and `name`.
void check_surface_contact_fields(const ElementRecord& record, const char* name,
                                  const ElementType& type, const RealSet& real);

/// The point law of contact node `node` of `record` from its type (KEYOPT(2) augmented Lagrange
/// or penalty, 7 bisection, 12 behaviour), its real set (3 FKN, 12 FKT) and MP,MU of its MAT,
/// shared by the 3-D (target_point) and the 2-D (line_target_point) contact: a positive FKN
/// scales the stiffness attached to the node along `n0`, times `share`; a negative FKN or FKT is
/// absolute, times `per` (1 for a point, the tributary area of a surface node). The penetration
/// tolerance is the caller's (its depth rule differs in 2-D and 3-D). InputError at `record`,
/// named `name`, for a stiffness that cannot be formed or a negative MU.
ContactLawData surface_contact_law(const ElementBuildContext& ctx, const ElementRecord& record,
                                   const char* name, const RealSet& real, int node, const Vec3& n0,
                                   double share, double per);

/// The law of contact node `node` of `record` (a CONTA175, or a CONTA174 face node) against the
/// target of its real set (rigid: RigidTargetPoint; deformable: DeformableTargetPoint), from its
/// type's KEYOPTs, its real constants (3 FKN, 4 FTOLN, 6 PINB, 10 CNOF, 12 FKT) and MP,MU of its
/// MAT (docs/elements/conta175.md). A positive FKN scales the stiffness attached to the node
/// along the initial normal, times `share` (the node's part of it that this element carries); a
/// negative FKN or FKT is absolute: force/length when `area` = 0 (CONTA175), force/length³ times
/// `area` (a CONTA174 node's tributary area). InputError names `record` and `name` for
/// unsupported KEYOPTs or real constants.
std::unique_ptr<ContactPoint> target_point(const ElementBuildContext& ctx,
                                           const ElementRecord& record, const Node& node,
                                           const char* family, const char* name, double share,
                                           double area);

}  // namespace impactfe
