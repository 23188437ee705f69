#include "core/model.h"

#include <fmt/format.h>

namespace impactfe {

const Node& Model::node(int id) const {
  auto it = nodes.find(id);
  if (it == nodes.end()) throw InputError(fmt::format("node {} is not defined", id));
  return it->second;
}

const ElementType& Model::element_type(int id) const {
  auto it = element_types.find(id);
  if (it == element_types.end())
    throw InputError(fmt::format("element type {} is not defined", id));
  return it->second;
}

}  // namespace impactfe
