#include "time/time_axis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/log.h"

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

ReducedTimeAxis reduced_time_axis(const std::vector<LoadStep>& steps, double& dt,
                                  std::vector<std::string>& notes) {
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
  std::vector<ReducedTimeAxis::Span> spans;
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
    spans.push_back({n, exact, t_prev, *step.time_end, step.number, static_cast<int>(i)});
    t_prev = exact ? *step.time_end : t_prev + n * dt;
  }
  return ReducedTimeAxis(steps.front().number, std::move(spans), dt);
}

ReducedTimeAxis::ReducedTimeAxis(int first_load_step, std::vector<Span> spans, double dt)
    : first_load_step_(first_load_step), spans_(std::move(spans)), dt_(dt) {
  std::size_t next = 1;  // point 0: the initial state
  for (const Span& span : spans_) {
    first_.push_back(next);
    next += static_cast<std::size_t>(span.n);
  }
  first_.push_back(next);
}

ReducedPoint ReducedTimeAxis::operator[](std::size_t i) const {
  if (i == 0) return {0.0, first_load_step_, 1, 0, 1.0};
  // The span holding point i: the last whose first point is at or before it.
  const auto it = std::upper_bound(first_.begin(), first_.end() - 1, i);
  const auto s = static_cast<std::size_t>(it - first_.begin()) - 1;
  const Span& span = spans_[s];
  const int k = static_cast<int>(i - first_[s]) + 1;
  // Same expression as the points had when they were stored: start + k Δt, TIME at the end.
  const double t = (k == span.n && span.exact) ? span.end : span.start + k * dt_;
  return {t, span.load_step, k, span.step_index, static_cast<double>(k) / span.n};
}

namespace {

/// Index of the stored time nearest to t (ascending times; the earlier of two as near).
std::size_t nearest_time(std::size_t count, const std::function<double(std::size_t)>& time_at,
                         double t) {
  std::size_t lo = 0, hi = count;  // first index with time_at >= t, by bisection
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (time_at(mid) < t)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == count) return count - 1;
  if (lo > 0 && std::abs(time_at(lo - 1) - t) <= std::abs(time_at(lo) - t)) return lo - 1;
  return lo;
}

}  // namespace

std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests, std::size_t count,
                                  const std::function<double(std::size_t)>& time_at) {
  std::set<int> chosen;
  if (count == 0) return {};
  const double t_last = time_at(count - 1);
  for (const ExpansionRequest& r : requests) {
    double begin = r.t_begin, end = std::min(r.t_end, t_last);
    if (end <= begin && begin == 0.0) end = t_last;  // blank range: the whole run
    if (r.every_step) {
      for (std::size_t i = 0; i < count; ++i) {
        const double t = time_at(i);
        if (t > begin - 1e-12 * t_last && t <= end + 1e-12 * t_last)
          chosen.insert(static_cast<int>(i));
      }
      continue;
    }
    const int n = std::max(1, r.count);
    for (int k = 1; k <= n; ++k)
      chosen.insert(static_cast<int>(nearest_time(count, time_at, begin + k * (end - begin) / n)));
  }
  return {chosen.begin(), chosen.end()};
}

std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests,
                                  const std::vector<double>& times) {
  return expansion_points(requests, times.size(), [&](std::size_t i) { return times[i]; });
}

}  // namespace impactfe
