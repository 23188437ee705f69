#include "app/interrupt_handlers.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

#include "core/interruption.h"

namespace impactfe::app {

namespace {

/// Whether stderr is a terminal, read once when the handlers are installed: there the message
/// starts on a line of its own (after the progress line or the echoed ^C); in a file or a pipe
/// it starts at once.
volatile sig_atomic_t stderr_is_terminal = 0;

/// write(2) of a literal: the only output a signal handler may do (async-signal-safe).
void say(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void on_stop_signal(int signal) {
  const bool again = stop_requested() != 0;
  if (stderr_is_terminal) say("\n");
  if (again || !stop_points_active()) {
    say(again ? "impactfe: stopped at once (second interrupt); the results file is left as it "
                "was last flushed\n"
              : "impactfe: stopped at once (no step loop running); the results file is left as "
                "it was last flushed\n");
    _exit(128 + signal);
  }
  request_stop(signal);
  say(signal == SIGINT ? "impactfe: interrupt received: stopping after the current substep (press "
                         "Ctrl-C again to stop at once)\n"
                       : "impactfe: SIGTERM received: stopping after the current substep (send "
                         "it again to stop at once)\n");
}

}  // namespace

void install_interrupt_handlers() {
  stderr_is_terminal = isatty(STDERR_FILENO) != 0 ? 1 : 0;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a read or write in progress goes on (the results file)
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupted_exit_status(int signal) {
  return 128 + signal;
}

}  // namespace impactfe::app
