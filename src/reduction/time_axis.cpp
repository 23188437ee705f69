// KAN=5 / MSUP time axis and expansion-time selection (spec §3.17, §3.18, §3.26).
#include <algorithm>
#include <cmath>
#include <set>

#include "core/log.h"
#include "reduction/reduced_run.h"

namespace impactfe {

std::vector<ReducedPoint> reduced_time_axis(const std::vector<LoadStep>& steps, double& dt,
                                            AnalysisStatistics& stats) {
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
  std::vector<ReducedPoint> points;
  points.push_back({0.0, steps.front().number, 1, 0, 1.0});
  double t_prev = 0.0;
  bool warned = false;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const LoadStep& step = steps[i];
    if (!step.time_end)
      throw InputError(step.where,
                       fmt::format("load step {}: TIME (end time) is required in a transient "
                                   "analysis",
                                   step.number));
    if (step.dt && std::abs(*step.dt - dt) > 1e-9 * dt && !warned) {
      Log::warn(
          "load step {}: DTIME {:g} ignored; a reduced / mode-superposition transient keeps the "
          "constant step {:g} of the first load step",
          step.number, *step.dt, dt);
      warned = true;
    }
    const double span = *step.time_end - t_prev;
    if (!(span > 0.0))
      throw InputError(step.where,
                       fmt::format("load step {}: end time {} does not increase (previous end {})",
                                   step.number, *step.time_end, t_prev));
    const int n = std::max(1, static_cast<int>(std::lround(span / dt)));
    const bool exact = std::abs(n * dt - span) <= 1e-6 * dt;
    if (!exact) {
      const std::string note = fmt::format(
          "load step {}: span {:g} is not a multiple of dt = {:g}; {} steps end at t = {:g}",
          step.number, span, dt, n, t_prev + n * dt);
      Log::warn("{}", note);
      stats.notes.push_back(note);
    }
    for (int k = 1; k <= n; ++k) {
      const double t = (k == n && exact) ? *step.time_end : t_prev + k * dt;
      points.push_back({t, step.number, k, static_cast<int>(i), static_cast<double>(k) / n});
    }
    t_prev = exact ? *step.time_end : t_prev + n * dt;
  }
  return points;
}

namespace {

/// Index of the computed point nearest to t.
int nearest_point(const std::vector<ReducedPoint>& points, double t) {
  int best = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (std::abs(points[i].time - t) < std::abs(points[static_cast<std::size_t>(best)].time - t))
      best = static_cast<int>(i);
  return best;
}

}  // namespace

std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests,
                                  const std::vector<ReducedPoint>& points) {
  std::set<int> chosen;
  const double t_last = points.back().time;
  for (const ExpansionRequest& r : requests) {
    double begin = r.t_begin, end = r.t_end;
    if (end <= begin && begin == 0.0) end = t_last;  // blank range: the whole run
    if (r.every_step) {
      for (std::size_t i = 0; i < points.size(); ++i)
        if (points[i].time > begin - 1e-12 * t_last && points[i].time <= end + 1e-12 * t_last)
          chosen.insert(static_cast<int>(i));
      continue;
    }
    const int n = std::max(1, r.count);
    for (int k = 1; k <= n; ++k)
      chosen.insert(nearest_point(points, begin + k * (end - begin) / n));
  }
  return {chosen.begin(), chosen.end()};
}

}  // namespace impactfe
