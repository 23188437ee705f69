// Placeholder until the superelement element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_superelement(const ElementBuildContext&,
                                           const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (superelement)", record.id));
}

}  // namespace impactfe
