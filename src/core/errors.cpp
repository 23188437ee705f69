#include "core/errors.h"

#include <fmt/format.h>

#include <new>

#include "core/interruption.h"

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

LocatedError::LocatedError(const SourceLocation& where, const std::string& message)
    : std::runtime_error(format_location(where, message)), where_(where), message_(message) {}

std::string location_text(const SourceLocation& where) {
  return where.known() ? fmt::format("{}:{}", where.file, where.line) : std::string();
}

void rethrow_at(const SourceLocation& where) {
  try {
    throw;
  } catch (const RunInterrupted&) {
    throw;  // a stop on request, not a failure: it keeps its kind (and its exit status)
  } catch (const LocatedError& e) {
    if (e.where().known() || !where.known()) throw;
    if (dynamic_cast<const InputError*>(&e)) throw InputError(where, e.message());
    if (dynamic_cast<const ModelError*>(&e)) throw ModelError(where, e.message());
    if (dynamic_cast<const NotImplementedError*>(&e)) throw NotImplementedError(where, e.message());
    throw SolutionError(where, e.message());
  } catch (const InternalError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw SolutionError(where,
                        "out of memory: the model (or the results kept in memory) is too large "
                        "for this machine");
  } catch (const std::logic_error& e) {
    throw InternalError(fmt::format("unexpected error: {}", e.what()));
  } catch (const std::exception& e) {
    throw SolutionError(where, fmt::format("the solution failed: {}", e.what()));
  }
}

}  // namespace impactfe
