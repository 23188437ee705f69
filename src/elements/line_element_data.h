#pragma once
/// Look-ups shared by the line and point elements (spar, spring-damper, point mass, gap):
/// element type, real-constant set and nodes of an element record, with user errors at the
/// E command's location.
#include <fmt/format.h>

#include <string_view>
#include <utility>

#include "core/errors.h"
#include "core/model.h"

namespace impactfe::line_data {

/// The element type of `record` (ET must exist).
inline const ElementType& element_type(const Model& model, const ElementRecord& record) {
  const auto it = model.element_types.find(record.type);
  if (it == model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  return it->second;
}

/// The real-constant set of `record` (R must exist).
inline const RealSet& real_set(const Model& model, const ElementRecord& record,
                               std::string_view family) {
  const auto it = model.real_sets.find(record.real);
  if (it == model.real_sets.end())
    throw InputError(record.where,
                     fmt::format("element {} ({}): real constant set {} is not defined", record.id,
                                 family, record.real));
  return it->second;
}

/// Checks that `record` has at least `count` nodes, all defined, and returns node `index`.
inline const Node& node(const Model& model, const ElementRecord& record, std::size_t index,
                        std::size_t count, std::string_view family) {
  if (record.nodes.size() < count)
    throw InputError(record.where, fmt::format("element {} ({}): needs {} nodes, {} given",
                                               record.id, family, count, record.nodes.size()));
  const int id = record.nodes[index];
  const auto it = model.nodes.find(id);
  if (it == model.nodes.end())
    throw InputError(record.where,
                     fmt::format("element {} ({}): node {} is not defined", record.id, family, id));
  return it->second;
}

/// Nodes I and J of a two-node element, which must be distinct nodes.
inline std::pair<const Node&, const Node&> distinct_node_pair(const Model& model,
                                                              const ElementRecord& record,
                                                              std::string_view family) {
  const Node& ni = node(model, record, 0, 2, family);
  const Node& nj = node(model, record, 1, 2, family);
  if (ni.id == nj.id)
    throw InputError(record.where, fmt::format("element {} ({}): both nodes are node {}", record.id,
                                               family, ni.id));
  return {ni, nj};
}

}  // namespace impactfe::line_data
