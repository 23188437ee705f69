#pragma once
/// 2-D contact targets (TARGE169, APDL_MODELING §8.4): the straight target segments (TSHAP,LINE,
/// nodes I, J) and the pilot node (TSHAP,PILO) of one real-constant set, in the X-Y plane.
/// A segment's normal is MAPDL's 2-D rule: with t = (x_J − x_I)/|x_J − x_I| the normal is
/// n = t × e_z = (t_y, −t_x), so a boundary numbered counter-clockwise around the target body
/// has its normal pointing out of the body, towards the contact side.
///
/// The target moves in one of three ways:
/// * **fixed rigid**: no pilot and none of its nodes on a body element; with TARGE169
///   KEYOPT(2) = 0 MAPDL constrains such target nodes itself, so the segments never move and a
///   contact point has the contact node's DOFs only;
/// * **rigid with a pilot**: x_a = x_P + R(θ)(X_a − X_P), the pilot's UX, UY and — when an element
///   gives the pilot a ROTZ (a MASS21 with rotary inertia, a beam) — its rotation θ;
/// * **deformable**: no pilot, every segment node on a body element (PLANE182/183 ...), the
///   segment ends moving with their nodes.
///
/// A contact node against the target (LineTargetPoint) uses the point law of
/// elements/contact_point.h with 2-D kinematics: UX, UY per node only (a 2-D model's nodes have
/// no UZ; a UZ without stiffness would make the system singular), the law's 3-D vectors with
/// z = 0 and T a 3 × n_dofs matrix with a zero third row.
#include <array>
#include <memory>
#include <vector>

#include "elements/connectivity.h"
#include "elements/contact_point.h"

namespace impactfe {

class LineTarget {
 public:
  enum class Motion { Fixed, Pilot, Deformable };
  struct Segment {
    std::array<int, 2> nodes{};  // I, J
    Vec3 a, b;                   // initial positions of I and J (z = 0)
    /// The segment sharing end I (resp. J), -1 at a free end.
    std::array<int, 2> neighbour{-1, -1};
  };

  LineTarget(Motion motion, int pilot, const Vec3& pilot_x, bool rotates,
             std::vector<Segment> segments);

  Motion motion() const { return motion_; }
  int pilot() const { return pilot_; }
  const Vec3& pilot_position() const { return pilot_x_; }
  /// A pilot target that turns with the pilot's ROTZ.
  bool rotates() const { return rotates_; }
  const std::vector<Segment>& segments() const { return segments_; }
  /// The outward normal n = (t_y, −t_x, 0) of the segment from a to b.
  static Vec3 normal(const Vec3& a, const Vec3& b);
  /// The distance from x to the segment a-b (to its nearest point, ends included).
  static double distance(const Vec3& x, const Vec3& a, const Vec3& b);
  /// The segments (indices) within `reach` of x, at the positions `at` gives for a node.
  template <typename Position>
  std::vector<int> near(const Vec3& x, double reach, const Position& at) const {
    std::vector<int> out;
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Segment& seg = segments_[s];
      if (distance(x, at(seg.nodes[0], seg.a), at(seg.nodes[1], seg.b)) <= reach)
        out.push_back(static_cast<int>(s));
    }
    return out;
  }

 private:
  Motion motion_;
  int pilot_;
  Vec3 pilot_x_;
  bool rotates_;
  std::vector<Segment> segments_;
};

/// True when real-constant set `real` holds TARGE169 elements (its contact is 2-D).
bool has_line_target(const Model& model, int real);

/// The 2-D target of `record`'s real set (every TARGE169 element of it), built once per build
/// pass. InputError at `record`'s location for a set without segments, two pilots, a pilot-less
/// target with nodes both on and off body elements, or a pilot-less target on no body with
/// TARGE169 KEYOPT(2) = 1 (its nodes would move with the user's own constraints).
std::shared_ptr<const LineTarget> line_target(const ElementBuildContext& ctx,
                                              const ElementRecord& record);

/// One contact node against a TARGE169 target (see above). DOFs: the contact node's UX, UY,
/// then the pilot's UX, UY (and ROTZ), or the nodes of the candidate segments of a deformable
/// target. Before each status update the search picks, among the segments (rigid) or the
/// candidates (deformable) at their current positions, the one the node projects onto with the
/// smallest |gap| within the pinball; a node beyond the end of every segment takes the nearest
/// one extended when that end is shared with another segment (a convex corner) or lies within
/// kTargetEdgeTolerance of a free end.
///
/// Kinematics on segment x₁ x₂ (current positions), L = |x₂ − x₁|, t = (x₂ − x₁)/L,
/// n = (t_y, −t_x): gap g = n·(x_s − x₁) − CNOF, projection ξ = t·(x_s − x₁)/L, and the
/// tangential relative displacement u_t = t t·(u_s − (1 − ξ) u₁ − ξ u₂) (the node against the
/// target's material point under it; for a rigid target u_a = x_a − X_a). G = ∂g/∂u,
/// H = ∂²g/∂u² (non-zero on a deformable or rotating target: the variation of the normal and of
/// the projection point, Wriggers, Computational Contact Mechanics, 2nd ed., §9.3 eq. 9.23 for
/// the 2-D node-to-segment element), T = ∂u_t/∂u and the friction curvature Σ_k f_t,k ∂²u_t,k/∂u²
/// come exactly from second-order automatic differentiation of these formulas
/// (elements/hyper_dual.h), so the tangent is consistent.
///
/// Deformable targets: large sliding (KEYOPT(18) = 0, MAPDL's default) re-finds the candidates
/// between steps as DeformableTargetPoint does (elements/target_surface.h: within the pinball,
/// re-found over kLargeSlidingMargin × the pinball when a segment within the pinball is not a
/// candidate); small sliding (KEYOPT(18) = 1) keeps those found at setup.
class LineTargetPoint final : public ContactPoint, public ConnectivityUpdate {
 public:
  static constexpr double kLargeSlidingMargin = 1.5;
  /// `x`: the contact node's initial position; `candidates`: the deformable target's candidate
  /// segments (ignored for rigid targets, which search all their segments).
  LineTargetPoint(const char* family, int id, int node, const Vec3& x,
                  std::shared_ptr<const LineTarget> target, std::vector<int> candidates,
                  double reach, double offset, const ContactLawData& data, bool large_sliding);
  const char* family() const override { return family_; }
  /// The segment in use (index into the target's segments), -1 when none was found yet.
  int segment() const { return current_; }
  bool refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) override;
  bool updates_connectivity() const override {
    return target_->motion() == LineTarget::Motion::Deformable && large_sliding_;
  }

 protected:
  bool locate(const Eigen::VectorXd& u) override;
  ContactKinematics kinematics(const Eigen::VectorXd& u) const override;
  void add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                              Eigen::MatrixXd& K) const override;

 private:
  /// Element DOF index of local variable k of segment s (us, then u₁ or the pilot's UX UY, u₂ or
  /// the pilot's ROTZ), -1 when unused.
  std::array<int, 6> slots(int s) const;
  /// The current positions of the ends of segment s at u.
  std::array<Vec3, 2> ends(int s, const Eigen::VectorXd& u) const;
  /// Position of `node` in nodes_ (deformable), -1 when absent.
  int local(int node) const;
  /// The DOF list of nodes_ (and the pilot's ROTZ).
  std::vector<DofKey> dof_list() const;
  /// The segments to search: all (rigid) or the candidates (deformable).
  const std::vector<int>& searched() const;

  const char* family_;
  std::shared_ptr<const LineTarget> target_;
  std::vector<int> nodes_;  // the contact node, then the pilot or the candidate segments' nodes
  std::vector<Vec3> x_;     // their initial positions
  std::vector<int> candidates_;
  std::vector<int> all_;  // every segment (rigid targets)
  int current_ = -1;
  double reach_;
  double offset_;
  bool large_sliding_;
};

/// The law of contact node `node` of `record` (a CONTA175 against a TARGE169, or a node of a
/// CONTA171/172) against the 2-D target of its real set, read as target_point() reads it
/// (elements/target_surface.h: KEYOPTs, real constants 3 FKN, 4 FTOLN, 6 PINB, 10 CNOF, 12 FKT,
/// MP,MU), with 2-D lengths: the depth of the underlying elements is √A of their in-plane area.
/// A positive FKN scales the stiffness attached to the node along the initial normal, times
/// `share`; a negative FKN or FKT is absolute: force/length when `length` = 0 (CONTA175, a
/// point contact), else force/length³ times the node's contact area, `length` (its tributary
/// length) times the out-of-plane extent of the underlying body elements (volume / in-plane
/// area: the plane-stress thickness, 1 in plane strain).
std::unique_ptr<ContactPoint> line_target_point(const ElementBuildContext& ctx,
                                                const ElementRecord& record, const Node& node,
                                                const char* family, const char* name, double share,
                                                double length);

}  // namespace impactfe
