// Expansion-time selection of the expansion pass (spec §3.26).
#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/reduced_run.h"
#include "core/log.h"

namespace impactfe {

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
