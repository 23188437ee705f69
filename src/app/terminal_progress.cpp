#include "app/terminal_progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace impactfe {

int progress_width() {
  int columns = 0;
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) columns = size.ws_col;
  if (columns <= 0)
    if (const char* env = std::getenv("COLUMNS"); env != nullptr) columns = std::atoi(env);
  if (columns <= 0) columns = 100;
  return std::max(columns - 1, 20);
}

TerminalProgress::TerminalProgress()
    : enabled_(isatty(STDERR_FILENO) != 0),
      start_(Clock::now()),
      last_draw_(Clock::time_point{}),
      last_event_wall_(start_) {}

void TerminalProgress::substep_done(const ProgressEvent& e) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (e.analysis != analysis_) {  // another analysis: another pace
    // The wall time before its first substep is set-up (reading, meshing, the first factor),
    // not stepping: the pace is measured from this substep on.
    analysis_ = e.analysis;
    estimate_.reset();
  } else {
    estimate_.add(std::chrono::duration<double>(now - last_event_wall_).count(),
                  e.time - last_time_);
  }
  last_event_wall_ = now;
  last_time_ = e.time;
  const bool last = e.substep == e.substeps;
  if (!last && now - last_draw_ < std::chrono::milliseconds(100)) return;  // 10 lines/s at most
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string line = progress_line(
      e, elapsed, estimate_.seconds_for(progress_end_time(e) - e.time), progress_width());
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
