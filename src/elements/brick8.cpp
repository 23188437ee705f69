// Placeholder until the brick8 element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_brick8(const ElementBuildContext&, const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (brick8)", record.id));
}

}  // namespace impactfe
