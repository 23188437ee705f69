// Placeholder until the spar element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_spar(const ElementBuildContext&, const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (spar)", record.id));
}

}  // namespace impactfe
