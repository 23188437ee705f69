#pragma once
/// Progress of a running analysis, reported through an observer that the program (the CLI)
/// implements: libraries never print. Drivers call it after every converged substep.
#include <limits>
#include <string>

namespace impactfe {

struct ProgressEvent {
  std::string analysis;   // description, e.g. "full transient (Houbolt)"
  double time = 0.0;      // time reached
  double time_end = 0.0;  // end time of the load step being solved
  int load_step = 0;
  int substep = 0;
  int substeps = 0;  // substeps of the load step
  double dt = 0.0;
  int iterations = 0;      // equilibrium iterations of this substep
  int status_changes = 0;  // status changes of this substep (-1: not counted)
  /// Substeps of the analysis still to solve after this one, over every load step known so far
  /// (later SOLVEs of the deck are not read yet); -1 when not counted.
  long long substeps_left = -1;
  double run_time_end = 0.0;  // end time of the last load step known so far
  /// Explicit dynamics: the cycles run so far (the line shows them instead of substeps and
  /// iterations; -1 for the substep drivers) and the energy error of the last energy check,
  /// |total − put in| relative to the larger of what was put in and T + internal energy (NaN
  /// before the first check).
  long long cycles = -1;
  double energy_error = std::numeric_limits<double>::quiet_NaN();
};

class ProgressObserver {
 public:
  virtual ~ProgressObserver() = default;
  virtual void substep_done(const ProgressEvent& event) = 0;
};

}  // namespace impactfe
