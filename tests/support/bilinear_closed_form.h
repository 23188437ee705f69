#pragma once
/// Test support: the closed-form uniaxial response of bilinear elastic-plastic material along a
/// strain path (isotropic or kinematic hardening), and a cyclic strain path.
#include <algorithm>
#include <cmath>
#include <vector>

namespace impactfe::testing {

/// Strain path 0 → +a → −a → +a → −a/2 in steps of at most `h` (a branch ends on its turning
/// point).
inline std::vector<double> cyclic_strain_path(double a, double h) {
  std::vector<double> path;
  double e = 0.0;
  for (double target : {a, -a, a, -0.5 * a}) {
    const double dir = target > e ? 1.0 : -1.0;
    while (dir * (target - e) > 1e-15) {
      e = dir * (target - e) > h ? e + dir * h : target;
      path.push_back(e);
    }
  }
  return path;
}

/// Stress along `path`: slope E inside the elastic range, slope Et beyond it. Isotropic: the
/// range is [−R, R] with R the largest stress reached (σy at first); kinematic: a range of width
/// 2σy that moves with the stress.
inline std::vector<double> bilinear_closed_form(const std::vector<double>& path, double young,
                                                double yield, double tangent, bool kinematic) {
  std::vector<double> out;
  double e_prev = 0.0, s = 0.0, radius = yield, centre = 0.0;
  for (double e : path) {
    const double trial = s + young * (e - e_prev);
    const double upper = kinematic ? centre + yield : radius;
    const double lower = kinematic ? centre - yield : -radius;
    if (trial > upper)
      s = upper + tangent * (trial - upper) / young;  // (trial − upper)/E: strain beyond yield
    else if (trial < lower)
      s = lower + tangent * (trial - lower) / young;
    else
      s = trial;
    if (kinematic) {
      if (s > centre + yield) centre = s - yield;
      if (s < centre - yield) centre = s + yield;
    } else {
      radius = std::max(radius, std::abs(s));
    }
    out.push_back(s);
    e_prev = e;
  }
  return out;
}

}  // namespace impactfe::testing
