#include "time/step_control.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace impactfe {

namespace {

[[noreturn]] void fail(const LoadStep& step, const std::string& message) {
  throw InputError(step.where, fmt::format("load step {}: {}", step.number, message));
}

}  // namespace

AutoStepPlan auto_step_plan(const LoadStep& step, const StepControl& c, const LoadStepTiming& t,
                            bool transient, bool default_on, std::optional<double> carried) {
  AutoStepPlan p;
  p.automatic = c.automatic.value_or(default_on);
  p.t_start = t.t_start;
  p.t_end = t.t_end;
  p.dt0 = t.h;
  p.n_nominal = t.n_substeps;
  const double span = t.t_end - t.t_start;
  // The largest step defaults to the first one in a transient (growth then only recovers from
  // cuts), to the whole span in a static step (§9.1 [A]).
  const double default_max = transient ? p.dt0 : span;
  if (step.dt) {  // DELTIM,DTIME,DTMIN,DTMAX in time units
    p.dt_min = c.dt_min.value_or(p.dt0 / 1000.0);
    p.dt_max = c.dt_max.value_or(default_max);
    if (c.dt_min && !(*c.dt_min > 0.0)) fail(step, fmt::format("DTMIN {} must be > 0", *c.dt_min));
    if (p.dt_min > p.dt0 * (1.0 + 1e-9))
      fail(step,
           fmt::format("DTMIN {:g} is larger than the time step {:g} (DELTIM)", p.dt_min, p.dt0));
    if (p.dt_max < p.dt0 * (1.0 - 1e-9))
      fail(step,
           fmt::format("DTMAX {:g} is smaller than the time step {:g} (DELTIM)", p.dt_max, p.dt0));
  } else {  // NSUBST,NSBSTP,NSBMX,NSBMN in substep counts (or one substep by default)
    if (c.n_max && *c.n_max < p.n_nominal)
      fail(step, fmt::format("NSBMX {} (most substeps) is smaller than NSBSTP {}", *c.n_max,
                             p.n_nominal));
    if (c.n_min && *c.n_min > p.n_nominal)
      fail(step, fmt::format("NSBMN {} (fewest substeps) is larger than NSBSTP {}", *c.n_min,
                             p.n_nominal));
    p.dt_min = c.n_max ? span / *c.n_max : p.dt0 / 1000.0;
    p.dt_max = c.n_min ? span / *c.n_min : default_max;
  }
  p.dt_min = std::min(p.dt_min, p.dt0);
  p.dt_max = std::min(std::max(p.dt_max, p.dt0), span);
  p.dt_first = p.dt0;
  if (c.carry && carried) p.dt_first = std::clamp(*carried, p.dt_min, p.dt_max);
  return p;
}

StepController::StepController(const AutoStepPlan& plan, std::vector<int> output_strides)
    : plan_(plan), t_(plan.t_start), dt_(plan.dt_first) {
  for (int s : output_strides)
    if (s > 1 && s < plan.n_nominal) strides_.push_back(s);
  std::sort(strides_.begin(), strides_.end());
  strides_.erase(std::unique(strides_.begin(), strides_.end()), strides_.end());
}

double StepController::grid_time(long long j) const {
  if (j >= plan_.n_nominal) return plan_.t_end;
  return plan_.t_start + (plan_.t_end - plan_.t_start) * static_cast<double>(j) / plan_.n_nominal;
}

double StepController::next_landing(int& grid_index) const {
  double best = plan_.t_end;
  grid_index = plan_.n_nominal;
  // Position of t_ on the nominal grid; a point just landed on counts as passed (round-off).
  const double position = (t_ - plan_.t_start) / (plan_.t_end - plan_.t_start) * plan_.n_nominal;
  for (int s : strides_) {
    const long long j = (static_cast<long long>(std::floor(position / s + 1e-9)) + 1) * s;
    if (j >= plan_.n_nominal) continue;
    const double tj = grid_time(j);
    if (tj < best) {
      best = tj;
      grid_index = static_cast<int>(j);
    }
  }
  return best;
}

StepController::Proposal StepController::propose() const {
  Proposal p;
  int grid = 0;
  const double landing = next_landing(grid);
  double h = dt_;
  if (ceiling_) h = std::min(h, std::max(*ceiling_, plan_.dt_min));
  const double remaining = landing - t_;
  if (h >= remaining * (1.0 - 1e-9)) return {remaining, landing, grid};
  // Equal steps up to the landing time: no sliver step just before it.
  const double n = std::ceil(remaining / h - 1e-9);
  p.h = remaining / n;
  p.time = t_ + p.h;
  p.grid_index = 0;
  return p;
}

double StepController::next_step() const {
  return propose().h;
}
double StepController::next_time() const {
  return propose().time;
}
int StepController::next_grid_index() const {
  return propose().grid_index;
}

void StepController::accept(bool easy) {
  const Proposal p = propose();
  t_ = p.time;
  done_ = p.grid_index == plan_.n_nominal;
  if (!easy) {
    easy_ = 0;
    return;
  }
  if (++easy_ >= kEasyStreak) {
    dt_ = std::min(kGrowth * dt_, plan_.dt_max);
    easy_ = 0;
  }
}

bool StepController::cut() {
  const double h = next_step();
  if (h <= plan_.dt_min * (1.0 + 1e-9)) return false;
  dt_ = std::max(kCutFactor * h, plan_.dt_min);
  easy_ = 0;
  return true;
}

void StepController::restore(const State& s) {
  t_ = s.time;
  dt_ = s.dt;
  ceiling_ = s.ceiling;
  easy_ = s.easy;
  done_ = s.done;
}

void StepController::set_ceiling(std::optional<double> ceiling) {
  ceiling_ = ceiling;
  // Growth after the ceiling is lifted starts from the step taken under it.
  if (ceiling_) dt_ = std::min(dt_, std::max(*ceiling_, plan_.dt_min));
}

}  // namespace impactfe
