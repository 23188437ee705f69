#include "app/terminal_progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace impactfe {

namespace {
std::string seconds(double s) {
  if (s < 60.0) return fmt::format("{:.1f} s", s);
  if (s < 3600.0)
    return fmt::format("{}:{:02d} min", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  return fmt::format("{:.1f} h", s / 3600.0);
}
}  // namespace

TerminalProgress::TerminalProgress()
    : enabled_(isatty(STDERR_FILENO) != 0),
      start_(Clock::now()),
      last_draw_(Clock::time_point{}),
      step_start_wall_(start_),
      analysis_start_wall_(start_),
      last_event_wall_(start_) {}

void TerminalProgress::substep_done(const ProgressEvent& e) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (e.analysis != analysis_) {
    analysis_ = e.analysis;
    status_changes_ = 0;
    analysis_substeps_ = 0;
    // The first substep's own wall time is not seen: start the clock one substep back.
    analysis_start_wall_ = last_event_wall_;
  }
  ++analysis_substeps_;
  last_event_wall_ = now;
  status_changes_ += std::max(e.status_changes, 0);
  if (e.load_step != load_step_) {  // the estimate is made per load step (its rate and end)
    load_step_ = e.load_step;
    step_start_wall_ = now;
    step_start_time_ = e.time - e.dt;
  }
  const bool last = e.substep == e.substeps;
  if (!last && now - last_draw_ < std::chrono::milliseconds(100)) return;  // 10 lines/s at most
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double in_step = std::chrono::duration<double>(now - step_start_wall_).count();
  const double done = e.time - step_start_time_;
  std::string left = "";
  if (e.substeps_left >= 0) {
    // The whole run as far as the deck has been read: the mean wall time per substep of this
    // analysis (load steps with another dt cost about the same per substep) times the
    // substeps still to solve.
    const double per_substep = std::chrono::duration<double>(now - analysis_start_wall_).count() /
                               static_cast<double>(analysis_substeps_);
    if (e.substeps_left > 0)
      left =
          fmt::format(", ~{} left (to t = {:.6g})",
                      seconds(per_substep * static_cast<double>(e.substeps_left)), e.run_time_end);
  } else if (done > 0.0 && e.time_end > e.time) {
    left = fmt::format(", ~{} left in load step", seconds(in_step * (e.time_end - e.time) / done));
  }
  const std::string line = fmt::format(
      "{}: t = {:.6g} of {:.6g}, load step {}, substep {}/{}, dt {:.3g}, {} iter, {}{} elapsed{}",
      e.analysis, e.time, e.time_end, e.load_step, e.substep, e.substeps, e.dt, e.iterations,
      e.status_changes < 0 ? "" : fmt::format("{} status changes, ", status_changes_),
      seconds(elapsed), left);
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void TerminalProgress::clear() {
  if (!shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace impactfe
