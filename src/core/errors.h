#pragma once
/// User-facing errors. Every error that can reach the user carries where it came from.
#include <stdexcept>
#include <string>

namespace impactfe {

/// Where a command came from: deck file, 1-based line, upper-cased command name.
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string command;
  bool known() const { return !file.empty(); }
};

/// Bad deck or model (exit status 1). what() is "FILE:LINE: COMMAND: message" when the location
/// is known, else just the message.
class InputError : public std::runtime_error {
 public:
  InputError(const SourceLocation& where, const std::string& message);
  explicit InputError(const std::string& message) : InputError(SourceLocation{}, message) {}
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

/// A model that cannot be solved as defined, e.g. an unrestrained DOF (exit status 1).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The solution failed, e.g. a time step did not converge (exit status 2). Results written so
/// far stay in the results file.
class SolutionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Feature recognised but not implemented yet (exit status 1, clear message).
class NotImplementedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A broken internal invariant: a programming error, never the user's (exit status 3, reported
/// as an internal error to be filed as a bug). Checked in release builds too (IMPACTFE_CHECK).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Throws InternalError("FILE:LINE: internal error: <message>") when the condition is false.
[[noreturn]] void fail_internal_check(const char* file, int line, const std::string& message);

}  // namespace impactfe

#define IMPACTFE_CHECK(condition, message)                                          \
  do {                                                                              \
    if (!(condition)) ::impactfe::fail_internal_check(__FILE__, __LINE__, message); \
  } while (false)
