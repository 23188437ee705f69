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

/// An error that can name the deck command that caused it. what() is "FILE:LINE: COMMAND:
/// message" when the location is known, else just the message.
class LocatedError : public std::runtime_error {
 public:
  LocatedError(const SourceLocation& where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

/// Bad deck or model (exit status 1).
class InputError : public LocatedError {
 public:
  InputError(const SourceLocation& where, const std::string& message)
      : LocatedError(where, message) {}
  explicit InputError(const std::string& message) : InputError(SourceLocation{}, message) {}
};

/// A model that cannot be solved as defined, e.g. an unrestrained DOF (exit status 1).
class ModelError : public LocatedError {
 public:
  ModelError(const SourceLocation& where, const std::string& message)
      : LocatedError(where, message) {}
  explicit ModelError(const std::string& message) : ModelError(SourceLocation{}, message) {}
};

/// The solution failed, e.g. a time step did not converge or the results file cannot be written
/// (exit status 2). Results written so far stay in the results file.
class SolutionError : public LocatedError {
 public:
  SolutionError(const SourceLocation& where, const std::string& message)
      : LocatedError(where, message) {}
  explicit SolutionError(const std::string& message) : SolutionError(SourceLocation{}, message) {}
};

/// A solution failure caused by one element (e.g. collapsed to zero length under large
/// deflection): the analysis layer adds where the element was defined.
class ElementSolutionError : public SolutionError {
 public:
  ElementSolutionError(int element, const std::string& message)
      : SolutionError(message), element_(element) {}
  int element() const { return element_; }

 private:
  int element_;
};

/// Feature recognised but not implemented yet (exit status 1, clear message).
class NotImplementedError : public LocatedError {
 public:
  NotImplementedError(const SourceLocation& where, const std::string& message)
      : LocatedError(where, message) {}
  explicit NotImplementedError(const std::string& message)
      : NotImplementedError(SourceLocation{}, message) {}
};

/// "FILE:LINE" of a known location ("" otherwise), for messages that cite a second command.
std::string location_text(const SourceLocation& where);

/// Rethrows the exception being handled (call inside a catch block) so that it names `where`
/// when it names no deck location yet: user errors (InputError, ModelError,
/// NotImplementedError, SolutionError) keep their kind and gain the location; running out of
/// memory and failures reported by libraries (std::runtime_error) become a SolutionError in the
/// program's words; InternalError and other logic errors become InternalError.
[[noreturn]] void rethrow_at(const SourceLocation& where);

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
