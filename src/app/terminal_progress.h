#pragma once
/// The progress line of `impactfe run` on a terminal (stderr): one line, never wider than the
/// terminal (analysis/progress_line.h chooses the fields that fit), redrawn at most 10 times a
/// second, with an estimate of the time left to the end of the load steps known so far from the
/// recent pace of the run (wall seconds per unit of simulated time, smoothed).
/// Nothing is written when stderr is not a terminal.
#include <chrono>
#include <string>

#include "analysis/progress.h"
#include "analysis/progress_line.h"

namespace impactfe {

/// The width the line may take: the terminal's columns (TIOCGWINSZ on stderr), else $COLUMNS,
/// else 100; one column less, since a character in the last column makes some terminals wrap.
int progress_width();

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
  Clock::time_point start_, last_draw_, last_event_wall_;
  double last_time_ = 0.0;  // simulated time of the previous event
  std::string analysis_;
  TimeLeftEstimate estimate_;
};

}  // namespace impactfe
