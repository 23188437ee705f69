#include "analysis/progress_line.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace impactfe {

void TimeLeftEstimate::add(double wall_seconds, double simulated) {
  window_wall_ += std::max(wall_seconds, 0.0);
  window_simulated_ += std::max(simulated, 0.0);
  if (window_simulated_ <= 0.0 || window_wall_ < kWindowSeconds) return;
  const double window_pace = window_wall_ / window_simulated_;
  pace_ = pace_ ? kAlpha * window_pace + (1.0 - kAlpha) * *pace_ : window_pace;
  window_wall_ = 0.0;
  window_simulated_ = 0.0;
}

std::optional<double> TimeLeftEstimate::pace() const {
  if (pace_) return pace_;
  // Before the first window closes: the pace of the substeps seen so far.
  if (window_simulated_ > 0.0 && window_wall_ > 0.0) return window_wall_ / window_simulated_;
  return std::nullopt;
}

std::optional<double> TimeLeftEstimate::seconds_for(double simulated) const {
  const std::optional<double> p = pace();
  if (!p) return std::nullopt;
  return *p * std::max(simulated, 0.0);
}

std::string duration_text(double s) {
  if (s < 60.0) return fmt::format("{:.1f} s", s);
  if (s < 3600.0)
    return fmt::format("{}:{:02d} min", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  return fmt::format("{:.1f} h", s / 3600.0);
}

double progress_end_time(const ProgressEvent& e) {
  return e.substeps_left >= 0 ? e.run_time_end : e.time_end;
}

namespace {

/// A field of the line: its text and a shorter form (empty when it has none).
struct Field {
  std::string text;
  std::string shorter;
  bool present = true;  // the driver reports it
  bool shown = true;
};

enum FieldName {
  kAnalysis,
  kTime,
  kStep,
  kDt,
  kEnergy,
  kIterations,
  kChanges,
  kElapsed,
  kLeft,
  kFields
};

/// What a narrower terminal costs, in order: each action shortens or drops a field; the time
/// reached is never dropped (what the line is for), the time left last.
struct Cut {
  FieldName field;
  bool drop;  // else shorten
};
constexpr Cut kCuts[] = {{kChanges, false}, {kIterations, true}, {kStep, false}, {kEnergy, false},
                         {kAnalysis, true}, {kChanges, true},    {kDt, true},    {kLeft, false},
                         {kEnergy, true},   {kElapsed, true},    {kStep, true},  {kLeft, true}};

std::string joined(const std::vector<Field>& fields) {
  std::string line;
  for (const Field& f : fields) {
    if (!f.present || !f.shown) continue;
    if (!line.empty()) line += " | ";
    line += f.text;
  }
  return line;
}

}  // namespace

std::string progress_line(const ProgressEvent& e, double elapsed, std::optional<double> left,
                          int width) {
  std::vector<Field> fields(kFields);
  fields[kAnalysis] = {e.analysis, ""};
  fields[kTime] = {fmt::format("t {:.6g}/{:.6g}", e.time, e.time_end), ""};
  const bool explicit_run = e.cycles >= 0;
  if (explicit_run)
    fields[kStep] = {fmt::format("load step {} cycle {}", e.load_step, e.cycles),
                     fmt::format("cycle {}", e.cycles)};
  else
    fields[kStep] = {fmt::format("load step {} substep {}/{}", e.load_step, e.substep, e.substeps),
                     fmt::format("ls {} {}/{}", e.load_step, e.substep, e.substeps)};
  fields[kDt] = {fmt::format("dt {:.3g}", e.dt), ""};
  fields[kEnergy] = {fmt::format("energy error {:.2g} %", 100.0 * e.energy_error),
                     fmt::format("err {:.2g} %", 100.0 * e.energy_error)};
  fields[kEnergy].present = std::isfinite(e.energy_error);
  fields[kIterations] = {fmt::format("{} iter", e.iterations), ""};
  fields[kIterations].present = !explicit_run;
  fields[kChanges] = {fmt::format("{} status changes", e.status_changes),
                      fmt::format("{} chg", e.status_changes)};
  fields[kChanges].present = !explicit_run && e.status_changes >= 0;  // -1: not counted
  fields[kElapsed] = {fmt::format("{} elapsed", duration_text(elapsed)), ""};
  const double end = progress_end_time(e);
  if (left && end > e.time)
    fields[kLeft] = {fmt::format("~{} left to t {:.6g}", duration_text(*left), end),
                     fmt::format("~{} left", duration_text(*left))};
  else
    fields[kLeft].present = false;
  const auto too_long = [&] { return static_cast<int>(joined(fields).size()) > width; };
  for (const Cut& cut : kCuts) {
    if (!too_long()) break;
    Field& f = fields[cut.field];
    if (!f.present || !f.shown) continue;
    if (cut.drop)
      f.shown = false;
    else if (!f.shorter.empty())
      f.text = f.shorter;
  }
  std::string line = joined(fields);
  if (static_cast<int>(line.size()) > width)
    line.resize(static_cast<std::size_t>(std::max(width, 0)));
  return line;
}

}  // namespace impactfe
