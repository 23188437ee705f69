// Placeholder until the point_mass element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_point_mass(const ElementBuildContext&, const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (point_mass)", record.id));
}

}  // namespace impactfe
