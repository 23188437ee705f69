#pragma once
/// Segment-to-segment integration of CONTA174 (KEYOPT(4) = 0 or 3, MAPDL's Gauss-point detection;
/// docs/elements/conta174.md): the contact pressure is integrated over the contact face at
/// integration points, each one a ContactPoint (elements/contact_point.h: penalty / augmented
/// Lagrange, Coulomb friction, KEYOPT(12)) whose stiffness is the face's stiffness per area times
/// the point's weight.
///
/// * Deformable target (no pilot): the integration cells are the polygons of the contact face ∩
///   each target facet, both projected on the face's plane (Sutherland–Hodgman clipping of the
///   convex polygons), cut into triangles with a 6-point degree-4 Dunavant rule each (Puso &
///   Laursen 2004, "A mortar segment-to-segment contact method for large deformation solid
///   mechanics", CMAME 193, §3; Wriggers, Computational Contact Mechanics, 2nd ed., §9.5). The
///   cells are made once, in the initial configuration (small sliding, like the candidate facets
///   of the node-to-surface law): a point keeps its coordinates on the contact face and its
///   weight, and its gap is found by the closest-point projection of x_s = Σ φ_i(ξ_s) x_i on the
///   target's **bilinear** quadrilateral (or linear triangle) facets, by Newton on (ξ, η).
///   With a uniform pressure the contact face gets ∫φ_i p dA and the target facet ∫N_a p dA
///   exactly (both integrands are of degree ≤ 2 on each cell), which passes the patch test on
///   non-matching meshes.
/// * Rigid target (pilot): the points are the face's own Gauss points (2 × 2 on a quadrilateral,
///   3 on a triangle); each searches the nearest target facet (large sliding) as CONTA175 does.
///   The facets of a rigid target are planar, so the distribution to its nodes does not matter:
///   everything goes to the pilot.
#include <array>
#include <memory>
#include <vector>

#include "elements/contact_point.h"

namespace impactfe {

class TargetSurface;  // elements/target_surface.h

/// The integration points of CONTA174 face `record` with corner nodes `corners` (3 or 4).
/// `nodal`: the node-to-surface points of the same corners (elements/target_surface.h
/// target_point, with the tributary-area shares): their law data give the face's stiffness per
/// area, k = Σ k_node / A, so the face carries the same total stiffness as with nodal detection.
std::vector<std::unique_ptr<ContactPoint>> segment_points(
    const ElementBuildContext& ctx, const ElementRecord& record, const std::vector<int>& corners,
    const std::vector<std::unique_ptr<ContactPoint>>& nodal, const char* family);

/// Shape functions of a contact face or a target facet: m = 4 the bilinear quadrilateral on
/// (ξ, η) ∈ [−1, 1]² (node order 1-2-3-4 counter-clockwise about the outward normal), m = 3 the
/// linear triangle with N = (1 − ξ − η, ξ, η).
struct FacetShape {
  int m = 4;
  double N[4] = {0, 0, 0, 0};
  double dN[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};  // ∂N/∂ξ, ∂N/∂η
  double dN12[4] = {0, 0, 0, 0};                       // ∂²N/∂ξ∂η (the others are 0)
};
FacetShape facet_shape(int m, double xi, double eta);
/// How far (ξ, η) lies outside the facet, as a fraction of its size; 0 inside.
double facet_outside(int m, double xi, double eta);

/// A candidate target facet of an integration point: its nodes' positions in the point's node
/// list and, for each edge e (nodes e, e+1), 0 a free edge of the target, 1 shared with another
/// candidate, 2 shared with a non-candidate facet only.
struct SegmentCandidate {
  std::vector<int> local;
  std::array<int, 4> edge{};
};
/// The edge (nodes e, e+1) across which (ξ, η) lies farthest outside the facet.
int facet_exit_edge(int m, double xi, double eta);

/// One integration point of a contact face against a deformable target (see above). `nodes`:
/// the face's corners (the first `n_face`) then the distinct nodes of the candidate facets, `x`
/// their initial positions; `candidates`: the candidate facets;
/// `current`: the facet of the point's cell.
class SegmentPoint final : public ContactPoint {
 public:
  SegmentPoint(const char* family, int id, std::vector<int> nodes, std::vector<Vec3> x, int n_face,
               std::vector<double> phi, std::vector<SegmentCandidate> candidates, int current,
               double reach, double offset, const ContactLawData& data);
  const char* family() const override { return family_; }

 protected:
  /// The candidate the point projects into (the current one while it does, for hysteresis),
  /// else the nearest one extended across an edge shared with another candidate or less than
  /// kTargetEdgeTolerance beyond a free edge; false (open) when none. A point that leaves the
  /// candidates across an edge shared with a non-candidate facet is an ElementSolutionError
  /// (enlarge PINB), as for a contact node.
  bool locate(const Eigen::VectorXd& u) override;
  /// g = n·(x_s − x_m(ξ)) − CNOF with the closest point ξ on the current bilinear facet and its
  /// exact first and second variations (see the .cpp).
  ContactKinematics kinematics(const Eigen::VectorXd& u) const override;

 private:
  const char* family_;
  std::vector<int> nodes_;
  std::vector<Vec3> x_;
  int n_face_;
  std::vector<double> phi_;
  std::vector<SegmentCandidate> candidates_;
  int current_;
  double reach_;
  double offset_;
};

/// One Gauss point of a contact face against a rigid target: CONTA175's law (RigidTargetPoint)
/// at x_s = Σ φ_i x_i. DOFs: the pilot's, then the face corners'.
class RigidGaussPoint final : public ContactPoint {
 public:
  RigidGaussPoint(const char* family, int id, int pilot, const std::vector<int>& corners,
                  const Vec3& xs, std::vector<double> phi,
                  std::shared_ptr<const TargetSurface> target, double reach, double offset,
                  const ContactLawData& data);
  const char* family() const override { return family_; }

 protected:
  bool locate(const Eigen::VectorXd& u) override;
  ContactKinematics kinematics(const Eigen::VectorXd& u) const override;

 private:
  Vec3 relative(const Eigen::VectorXd& u) const;  // Σ φ_i u_i − u_pilot
  const char* family_;
  Vec3 xs_;
  std::vector<double> phi_;
  std::shared_ptr<const TargetSurface> target_;
  double reach_;
  double offset_;
};

}  // namespace impactfe
