#pragma once
/// The equivalent of an inelastic (plastic or creep) strain tensor as MAPDL reports EPPL,EQV and
/// EPCR,EQV: the von Mises equivalent strain with the effective Poisson's ratio ν' = 0.5 of an
/// incompressible flow (MAPDL Theory Reference, "Combined Stresses and Strains"),
///   ε_eq = 1/(1 + ν') · √(½[(εx − εy)² + (εy − εz)² + (εz − εx)² + 3/2 (γxy² + γyz² + γxz²)])
/// Voigt order (xx, yy, zz, xy, yz, xz) with engineering shears γ = 2ε. Under uniaxial flow
/// (εx, −εx/2, −εx/2) it is |εx|; for a proportional history it equals the accumulated
/// equivalent strain ∫√(2/3)|dε|.
#include <Eigen/Core>

#include <cmath>

namespace impactfe {

inline double equivalent_inelastic_strain(const Eigen::Matrix<double, 6, 1>& e) {
  const double dxy = e(0) - e(1), dyz = e(1) - e(2), dzx = e(2) - e(0);
  const double shear = e(3) * e(3) + e(4) * e(4) + e(5) * e(5);
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx + 1.5 * shear)) / 1.5;
}

}  // namespace impactfe
