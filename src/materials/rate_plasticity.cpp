#include "materials/rate_plasticity.h"

#include <algorithm>

namespace impactfe {

double radial_return(double* s, double* beta, double& alpha, const RateMaterial& m) {
  const J2Plasticity& law = *m.plasticity;
  const double p = (s[0] + s[1] + s[2]) / 3.0;
  double xi[6] = {s[0] - p - beta[0], s[1] - p - beta[1], s[2] - p - beta[2],
                  s[3] - beta[3],     s[4] - beta[4],     s[5] - beta[5]};
  const double norm2 = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                       2.0 * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5]);
  const double q = std::sqrt(1.5 * norm2);
  if (q <= law.flow_stress(alpha)) return 0.0;
  // Newton on r(Δ) = q − (3G + H_kin) Δ − k(α + Δ): one step is exact when k is linear (BISO,
  // BKIN), a few for a multilinear curve; each piece of k is linear, so this converges in as
  // many steps as segments crossed.
  const double c = 3.0 * m.shear + law.kinematic_modulus();
  double delta = 0.0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double r = q - c * delta - law.flow_stress(alpha + delta);
    const double slope = c + law.flow_slope(alpha + delta);
    const double step = r / slope;
    delta = std::max(0.0, delta + step);
    if (std::abs(step) <= 1e-14 * (1.0 + delta)) break;
  }
  const double scale = delta / q;
  // Plastic strain increment Δε_p = (3/2) Δ ξ/q; σ:Δε_p with the returned stress.
  double work = 0.0;
  for (int i = 0; i < 6; ++i) {
    s[i] -= 3.0 * m.shear * scale * xi[i];
    beta[i] += law.kinematic_modulus() * scale * xi[i];
    work += (i < 3 ? 1.0 : 2.0) * s[i] * 1.5 * scale * xi[i];
  }
  alpha += delta;
  return work;
}

}  // namespace impactfe
