#include "core/load_values.h"

#include <algorithm>

namespace impactfe {

double TimeFunction::at(double t) const {
  if (time.size() == 1 || t <= time.front()) return value.front();
  if (t >= time.back()) return value.back();
  const auto it = std::upper_bound(time.begin(), time.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - time.begin());
  const double t0 = time[k - 1], t1 = time[k];
  if (t1 <= t0) return value[k];
  return value[k - 1] + (value[k] - value[k - 1]) * (t - t0) / (t1 - t0);
}

}  // namespace impactfe
