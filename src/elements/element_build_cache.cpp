#include "elements/element_build_cache.h"

namespace impactfe {

ElementBuildCache& build_cache(const ElementBuildContext& ctx) {
  if (!ctx.cache) ctx.cache = std::make_shared<ElementBuildCache>();
  return *ctx.cache;
}

const std::vector<int>& elements_at_node(const ElementBuildContext& ctx, int node) {
  ElementBuildCache& cache = build_cache(ctx);
  if (!cache.node_index_built) {
    for (const auto& [id, record] : ctx.model.elements) {
      for (std::size_t k = 0; k < record.nodes.size(); ++k) {
        std::vector<int>& at = cache.elements_at_node[record.nodes[k]];
        // A node repeated in one element (a collapsed brick) lists the element once.
        if (at.empty() || at.back() != id) at.push_back(id);
      }
    }
    cache.node_index_built = true;
  }
  static const std::vector<int> none;
  const auto it = cache.elements_at_node.find(node);
  return it == cache.elements_at_node.end() ? none : it->second;
}

}  // namespace impactfe
