#include "time/time_axis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/log.h"
#include "core/memory_budget.h"

namespace impactfe {

namespace {

[[noreturn]] void fail(const LoadStep& step, const std::string& message) {
  throw InputError(step.where, fmt::format("load step {}: {}", step.number, message));
}

}  // namespace

int substep_count(const LoadStep& step, double span, double dt) {
  if (!(dt > 0.0)) fail(step, fmt::format("time step {} must be > 0", dt));
  const double n = std::round(span / dt);
  if (!(n <= static_cast<double>(kMaxSubstepsPerLoadStep)))
    fail(step, fmt::format("a span of {:g} in steps of {:g} would need {:.4g} substeps (more than "
                           "{}); check DELTIM / DTIME and TIME",
                           span, dt, span / dt, kMaxSubstepsPerLoadStep));
  return std::max(1, static_cast<int>(n));
}

std::vector<ReducedPoint> reduced_time_axis(const std::vector<LoadStep>& steps, double& dt,
                                            std::vector<std::string>& notes,
                                            double bytes_per_point) {
  if (steps.empty()) throw InputError("reduced transient: no load steps were written");
  dt = 0.0;
  for (const LoadStep& s : steps)
    if (s.dt) {
      dt = *s.dt;
      break;
    }
  if (dt == 0.0 && steps.size() > 1 && steps[1].time_end)
    dt = *steps[1].time_end / std::max(1, steps[1].n_substeps.value_or(1));
  if (steps.size() > 1 && !(dt > 0.0))
    throw InputError(
        steps.front().where,
        fmt::format("reduced transient: time step {} must be > 0 (DTIME / DELTIM)", dt));
  struct Span {
    int n = 0;  // substeps
    bool exact = false;
    double start = 0.0;
  };
  std::vector<Span> spans(steps.size());
  double total = 1.0;  // points, t = 0 included
  double t_prev = 0.0;
  bool warned = false;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const LoadStep& step = steps[i];
    if (!step.time_end) fail(step, "TIME (end time) is required in a transient analysis");
    if (step.dt && std::abs(*step.dt - dt) > 1e-9 * dt && !warned) {
      const std::string note = fmt::format(
          "load step {}: DTIME {:g} ignored; a reduced / mode-superposition transient keeps the "
          "constant step {:g} of the first load step that gives one",
          step.number, *step.dt, dt);
      Log::warn("{}", note);
      notes.push_back(note);
      warned = true;
    }
    const double span = *step.time_end - t_prev;
    if (!(span > 0.0))
      fail(step,
           fmt::format("end time {} does not increase (previous end {})", *step.time_end, t_prev));
    const int n = substep_count(step, span, dt);
    const bool exact = std::abs(n * dt - span) <= 1e-6 * dt;
    if (!exact) {
      const std::string note = fmt::format(
          "load step {}: span {:g} is not a multiple of dt = {:g}; {} steps end at t = {:g}",
          step.number, span, dt, n, t_prev + n * dt);
      Log::warn("{}", note);
      notes.push_back(note);
    }
    spans[i] = {n, exact, t_prev};
    total += n;
    t_prev = exact ? *step.time_end : t_prev + n * dt;
  }
  const double per_point = static_cast<double>(sizeof(ReducedPoint)) + bytes_per_point;
  const MemoryAvailable available = memory_available();
  if (total * per_point > available.bytes)
    require_memory(total * per_point,
                   fmt::format("the {:.0f} time points of this reduced / mode-superposition "
                               "transient with their history ({:.0f} bytes each, kept for the "
                               "expansion pass)",
                               total, per_point),
                   fmt::format("at most about {:.0f} points fit: a larger DELTIM or a shorter TIME",
                               std::floor(available.bytes / per_point)));
  std::vector<ReducedPoint> points;
  points.reserve(static_cast<std::size_t>(total));
  points.push_back({0.0, steps.front().number, 1, 0, 1.0});
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const auto [n, exact, start] = spans[i];
    for (int k = 1; k <= n; ++k) {
      const double t = (k == n && exact) ? *steps[i].time_end : start + k * dt;
      points.push_back({t, steps[i].number, k, static_cast<int>(i), static_cast<double>(k) / n});
    }
  }
  return points;
}

namespace {

/// Index of the stored time nearest to t.
int nearest_time(const std::vector<double>& times, double t) {
  int best = 0;
  for (std::size_t i = 1; i < times.size(); ++i)
    if (std::abs(times[i] - t) < std::abs(times[static_cast<std::size_t>(best)] - t))
      best = static_cast<int>(i);
  return best;
}

}  // namespace

std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests,
                                  const std::vector<double>& times) {
  std::set<int> chosen;
  if (times.empty()) return {};
  const double t_last = times.back();
  for (const ExpansionRequest& r : requests) {
    double begin = r.t_begin, end = std::min(r.t_end, t_last);
    if (end <= begin && begin == 0.0) end = t_last;  // blank range: the whole run
    if (r.every_step) {
      for (std::size_t i = 0; i < times.size(); ++i)
        if (times[i] > begin - 1e-12 * t_last && times[i] <= end + 1e-12 * t_last)
          chosen.insert(static_cast<int>(i));
      continue;
    }
    const int n = std::max(1, r.count);
    for (int k = 1; k <= n; ++k) chosen.insert(nearest_time(times, begin + k * (end - begin) / n));
  }
  return {chosen.begin(), chosen.end()};
}

}  // namespace impactfe
