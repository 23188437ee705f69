#include "geometry/spacing.h"

#include <algorithm>
#include <cmath>

namespace impactfe::geometry {

std::vector<double> division_fractions(int n, double space) {
  std::vector<double> h(static_cast<std::size_t>(std::max(n, 1)), 1.0);
  if (n > 1 && space > 0.0 && std::fabs(space - 1.0) > 1e-12) {
    const double r = std::pow(space, 1.0 / (n - 1));
    for (int i = 1; i < n; ++i)
      h[static_cast<std::size_t>(i)] = h[static_cast<std::size_t>(i - 1)] * r;
  } else if (n > 2 && space < 0.0 && std::fabs(space + 1.0) > 1e-12) {
    // Symmetric: the division k steps from the nearer end has length r^k, the middle one |SPACE|.
    const int half = (n - 1) / 2;
    const double r = half > 0 ? std::pow(-space, 1.0 / half) : 1.0;
    for (int i = 0; i < n; ++i)
      h[static_cast<std::size_t>(i)] = std::pow(r, std::min(i, n - 1 - i));
  }
  double total = 0.0;
  for (double v : h) total += v;
  std::vector<double> f{0.0};
  double acc = 0.0;
  for (int i = 0; i < n; ++i) {
    acc += h[static_cast<std::size_t>(i)];
    f.push_back(i == n - 1 ? 1.0 : acc / total);
  }
  return f;
}

}  // namespace impactfe::geometry
