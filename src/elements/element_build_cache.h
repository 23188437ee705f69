#pragma once
/// Lookups shared by the elements of one build pass (ElementBuildContext::cache): made on the
/// first request and dropped with the context, so they never outlive the model state they were
/// made from (a deck may change the model between two solutions).
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "elements/element.h"

namespace impactfe {

class TargetSurface;
class LineTarget;
struct SegmentFacets;

/// What contact elements need of a body element at their node (contact_point.h: the default
/// penalty stiffness and depth), computed once per element instead of once per contact node.
struct AttachedElement {
  std::vector<DofKey> dofs;
  std::optional<double> volume;
  Eigen::MatrixXd stiffness;  // tangent at u = 0
};

struct ElementBuildCache {
  /// node → the ids of the elements that reference it, ascending (filled on first use).
  std::unordered_map<int, std::vector<int>> elements_at_node;
  bool node_index_built = false;
  /// real-constant set → its contact target (elements/target_surface.h).
  std::map<int, std::shared_ptr<const TargetSurface>> targets;
  /// real-constant set → its 2-D contact target (elements/target_line.h).
  std::map<int, std::shared_ptr<const LineTarget>> line_targets;
  /// element id → its AttachedElement; nullptr for elements that are no body (unknown type,
  /// status elements such as gaps and contact, superelements).
  std::unordered_map<int, std::unique_ptr<AttachedElement>> attached;
  /// element id → the element the build pass already made for the model (owned by the caller,
  /// which outlives the pass), so an AttachedElement need not make it again.
  std::unordered_map<int, const Element*> built;
  /// real-constant set → its facets unsplit, for CONTA174 segment-to-segment (contact_segment.cpp).
  std::map<int, std::shared_ptr<const SegmentFacets>> segment_facets;
};

/// The cache of `ctx`, made on first use.
ElementBuildCache& build_cache(const ElementBuildContext& ctx);

/// The ids of the elements that reference `node`, ascending (model order); empty for none.
const std::vector<int>& elements_at_node(const ElementBuildContext& ctx, int node);

/// The body element `id` as seen by a contact element at one of its nodes; nullptr when it is
/// no body element (see ElementBuildCache::attached).
const AttachedElement* attached_element(const ElementBuildContext& ctx, int id);

}  // namespace impactfe
