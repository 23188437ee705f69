// Placeholder until the combination_gap element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_combination_gap(const ElementBuildContext&,
                                              const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (combination_gap)", record.id));
}

}  // namespace impactfe
