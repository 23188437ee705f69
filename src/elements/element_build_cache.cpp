#include "elements/element_build_cache.h"

#include "elements/element_registry.h"

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

const AttachedElement* attached_element(const ElementBuildContext& ctx, int id) {
  auto& attached = build_cache(ctx).attached;
  const auto found = attached.find(id);
  if (found != attached.end()) return found->second.get();
  std::unique_ptr<AttachedElement>& slot = attached[id];
  const ElementRecord& rec = ctx.model.elements.at(id);
  const auto type = ctx.model.element_types.find(rec.type);
  if (type == ctx.model.element_types.end()) return nullptr;
  const ElementTypeDescriptor& d = element_type_descriptor(type->second);
  if (d.has_status || d.defined_by_file) return nullptr;
  const auto built = build_cache(ctx).built.find(id);
  std::unique_ptr<Element> made;
  if (built == build_cache(ctx).built.end()) made = d.create(ctx, rec);
  const Element* element = made ? made.get() : built->second;
  slot = std::make_unique<AttachedElement>();
  slot->dofs = element->dofs();
  slot->volume = element->volume();
  Eigen::VectorXd f;
  element->tangent(ElementContext{}, Eigen::VectorXd::Zero(element->n_dofs()), slot->stiffness, f);
  return slot.get();
}

}  // namespace impactfe
