// Placeholder until the spring_damper element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_spring_damper(const ElementBuildContext&,
                                            const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (spring_damper)", record.id));
}

}  // namespace impactfe
