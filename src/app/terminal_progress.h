#pragma once
/// The progress line of `impactfe run` on a terminal (stderr): time, load step, substep, Δt,
/// iterations, status changes, elapsed time and an estimate of the time left: in the whole
/// analysis over the load steps known so far (wall time per substep of the analysis times the
/// substeps still to solve), or in the load step when the driver does not count them.
/// Nothing is written when stderr is not a terminal.
#include <chrono>
#include <string>

#include "analysis/progress.h"

namespace impactfe {

class TerminalProgress final : public ProgressObserver {
 public:
  TerminalProgress();
  void substep_done(const ProgressEvent& e) override;
  /// Clears the line (before a warning or the summary is printed).
  void clear();
  bool active() const { return enabled_; }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_ = false;
  bool shown_ = false;
  Clock::time_point start_, last_draw_, step_start_wall_, analysis_start_wall_, last_event_wall_;
  long long analysis_substeps_ = 0;  // substeps of the current analysis reported so far
  double step_start_time_ = 0.0;
  int load_step_ = -1;
  std::string analysis_;
  int status_changes_ = 0;
};

}  // namespace impactfe
