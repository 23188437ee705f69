// Placeholder until the shell4 element lands.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

std::unique_ptr<Element> make_shell4(const ElementBuildContext&, const ElementRecord& record) {
  throw NotImplementedError(
      fmt::format("element {}: element not implemented yet (shell4)", record.id));
}

}  // namespace impactfe
