#pragma once
/// The program's exit statuses (README, "Exit status") and the report of an internal error.
#include "core/errors.h"

namespace impactfe::app {

constexpr int kExitOk = 0;
constexpr int kExitInput = 1;     // bad input or command line: nothing solved, or refused
constexpr int kExitSolution = 2;  // the solution failed; results so far are kept
constexpr int kExitInternal = 3;  // a bug in impactfe, not in the input

/// A broken internal invariant: the user's input is not to blame.
int report_internal_error(const InternalError& e);

}  // namespace impactfe::app
