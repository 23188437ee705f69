#pragma once
/// The progress line of `impactfe run` on a terminal, as text: what a ProgressEvent says, cut to
/// the terminal's width (fields of least use dropped first, never wrapped), and the estimate of
/// the time left from the recent pace of the run (src/app/terminal_progress.h draws it).
#include <optional>
#include <string>

#include "analysis/progress.h"

namespace impactfe {

/// Wall seconds per unit of simulated time, as an exponential moving average over windows of
/// recent substeps (a window closes once it holds kWindowSeconds of wall time): the pace of the
/// last few seconds of the run, so that a factorization, a change of Δt or a contact phase moves
/// the estimate without making it jump at every substep.
class TimeLeftEstimate {
 public:
  static constexpr double kWindowSeconds = 0.25;
  /// Weight of the newest window: r ← α·r_window + (1 − α)·r (about the last 1 / α windows).
  static constexpr double kAlpha = 0.3;

  /// A substep took `wall_seconds` and advanced the simulated time by `simulated`.
  void add(double wall_seconds, double simulated);
  /// The wall seconds to advance `simulated` more; nullopt before a pace is known.
  std::optional<double> seconds_for(double simulated) const;
  /// Smoothed wall seconds per unit of simulated time (before the first window closes, the mean
  /// of the substeps seen); nullopt before any.
  std::optional<double> pace() const;
  void reset() { *this = TimeLeftEstimate{}; }

 private:
  double window_wall_ = 0.0;
  double window_simulated_ = 0.0;
  std::optional<double> pace_;
};

/// "12.3 s", "4:05 min", "1.5 h".
std::string duration_text(double seconds);

/// The line for `event`, at most `width` characters. `elapsed`: wall seconds since the run
/// started; `left`: the estimate of the wall seconds to the end of the load steps known
/// (event.run_time_end when the driver counts them, else the end of the load step).
std::string progress_line(const ProgressEvent& event, double elapsed, std::optional<double> left,
                          int width);

/// The simulated time the estimate runs to: the end of the last load step known, or the end of
/// the load step when the driver does not look ahead.
double progress_end_time(const ProgressEvent& event);

}  // namespace impactfe
