#pragma once
/// A request from outside to stop the run (Ctrl-C: SIGINT, or SIGTERM), as a flag that the
/// stepping loops of the static and full transient drivers read between substeps: the step
/// being solved is finished, the last converged state is kept as a restart point, the results
/// file is marked "interrupted" and the program ends with 128 + the signal number (130, 143).
/// The flag is a lock-free atomic, so the program's signal handler (src/app) may set it.
#include <stdexcept>
#include <string>

namespace impactfe {

/// The signal that asked the run to stop (SIGINT or SIGTERM); 0 when none did.
int stop_requested();
/// Records the request (async-signal-safe). The first signal wins.
void request_stop(int signal);
/// Forgets a request (tests; a new run in the same process).
void clear_stop_request();

/// Whether a stepping loop that reads the flag is running: outside one, nothing would read it,
/// and the signal handler stops the program at once instead.
bool stop_points_active();

/// Marks a stepping loop that reads the flag between its substeps, for its lifetime.
class StopPoints {
 public:
  StopPoints();
  ~StopPoints();
  StopPoints(const StopPoints&) = delete;
  StopPoints& operator=(const StopPoints&) = delete;
};

/// Thrown by a stepping loop that stopped on request after a converged substep; not a failure
/// of the solution (exit status 128 + signal, not 2).
class RunInterrupted : public std::runtime_error {
 public:
  RunInterrupted(int signal, const std::string& message)
      : std::runtime_error(message), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// "SIGINT" / "SIGTERM" / "signal N".
std::string signal_name(int signal);

}  // namespace impactfe
