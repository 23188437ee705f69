#pragma once
/// Ctrl-C (SIGINT) and SIGTERM during `impactfe run`: the first one asks the stepping loop to
/// stop after the substep being solved (core/interruption.h); a second one, or one that comes
/// when no stepping loop is running (reading the deck, a modal analysis, writing the summary),
/// ends the program at once with 128 + the signal number, as the default action would.

namespace impactfe::app {

/// Installs the handlers of SIGINT and SIGTERM (for the rest of the process).
void install_interrupt_handlers();

/// The exit status of a run stopped by `signal`: 128 + its number (130 SIGINT, 143 SIGTERM).
int interrupted_exit_status(int signal);

}  // namespace impactfe::app
