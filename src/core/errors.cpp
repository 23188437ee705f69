#include "core/errors.h"

#include <fmt/format.h>

namespace impactfe {

namespace {
std::string format_location(const SourceLocation& where, const std::string& message) {
  if (!where.known()) return message;
  return fmt::format("{}:{}: {}: {}", where.file, where.line, where.command, message);
}
}  // namespace

void fail_internal_check(const char* file, int line, const std::string& message) {
  throw InternalError(fmt::format("{}:{}: internal error: {}", file, line, message));
}

InputError::InputError(const SourceLocation& where, const std::string& message)
    : std::runtime_error(format_location(where, message)), where_(where), message_(message) {}

}  // namespace impactfe
