#pragma once
/// Rigid contact targets (TARGE170, APDL_MODELING §8.4): the target facets of one real-constant
/// set (triangles and quadrilaterals, a quadrilateral as two triangles, so it should be planar)
/// moving rigidly with their pilot node (a one-node TARGE170; translations only: the pilot's
/// rotations do not turn the target). A spatial bucket grid over the facets in their initial
/// position answers the closest-facet query of the contact nodes (CONTA175); the target only
/// translates, so the grid is built once and queried in the target's own frame.
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/coordinate_system.h"
#include "elements/contact_point.h"
#include "elements/element.h"

namespace impactfe {

class TargetSurface {
 public:
  struct Triangle {
    Vec3 a, b, c;
    Vec3 normal;  // unit, right-hand rule of the node order: towards the contact side
  };
  struct Hit {
    Vec3 normal;
    double gap = 0.0;  // signed distance from the facet plane along the normal
  };

  TargetSurface(int pilot, std::vector<Triangle> triangles);

  int pilot() const { return pilot_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// The facet whose plane is nearest to y (in the target's initial frame) among the facets
  /// that y projects into and that lie within `reach` of it; nullopt when none does.
  std::optional<Hit> closest(const Vec3& y, double reach) const;

 private:
  long long key(long long i, long long j, long long k) const;
  void cell_range(const Vec3& lo, const Vec3& hi, Eigen::Vector3i& a, Eigen::Vector3i& b) const;

  int pilot_;
  std::vector<Triangle> triangles_;
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1.0;
  std::unordered_map<long long, std::vector<int>> buckets_;
};

/// The rigid target of real-constant set `real`: every TARGE170 element of that set (exactly one
/// of them a one-node pilot). Built once per model and set and shared by the contact elements.
/// InputError at `record`'s location when the set has no target facets or no single pilot.
std::shared_ptr<const TargetSurface> rigid_target(const ElementBuildContext& ctx,
                                                  const ElementRecord& record);

/// One contact node against the rigid target of its real set (CONTA175, and each face node of a
/// CONTA174): the point law of elements/contact_point.h with I = the target's pilot node and
/// J = the contact node. Before each status update the search finds the facet nearest to
/// y = X + u_node − u_pilot (the node in the target's frame) and sets the normal and
/// g₀ = distance − CNOF − n·(u_node − u_pilot).
class RigidTargetPoint final : public ContactPoint {
 public:
  RigidTargetPoint(const char* family, int id, int node, const Vec3& x,
                   std::shared_ptr<const TargetSurface> target, double reach, double offset,
                   const ContactLawData& data);
  const char* family() const override { return family_; }

 protected:
  bool locate(const Eigen::VectorXd& u) override;

 private:
  const char* family_;
  Vec3 x_;
  std::shared_ptr<const TargetSurface> target_;
  double reach_;   // pinball radius
  double offset_;  // CNOF
};

/// The law of contact node `node` of `record` (a CONTA175, or a CONTA174 face node) against the
/// rigid target of its real set, from its type's KEYOPTs, its real constants (3 FKN, 4 FTOLN,
/// 6 PINB, 10 CNOF, 12 FKT) and MP,MU of its MAT (docs/elements/conta175.md). A positive FKN
/// scales the stiffness attached to the node along the initial normal, times `share` (the
/// node's part of it that this element carries); a negative FKN or FKT is absolute: force/length
/// when `area` = 0 (CONTA175), force/length³ times `area` (a CONTA174 node's tributary area).
/// InputError names `record` and `name` for unsupported KEYOPTs or real constants.
std::unique_ptr<RigidTargetPoint> rigid_target_point(const ElementBuildContext& ctx,
                                                     const ElementRecord& record, const Node& node,
                                                     const char* family, const char* name,
                                                     double share, double area);

}  // namespace impactfe
