#include "time/step_control.h"

#include <algorithm>
#include <cmath>

namespace impactfe {

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
