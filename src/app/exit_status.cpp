#include "app/exit_status.h"

#include <iostream>

#include "core/log.h"

namespace impactfe::app {

int report_internal_error(const InternalError& e) {
  std::cerr << "error: " << e.what()
            << "\nThis is a bug in impactfe, not in your input; please report it with the deck.\n";
  Log::write(LogLevel::Error, e.what());
  return kExitInternal;
}

}  // namespace impactfe::app
