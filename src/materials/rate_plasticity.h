#pragma once
/// The stress update of explicit dynamics (docs/explicit_dynamics.md): hypoelastic, rate form
/// σ̇ = C:D + Wσ − σW (the Jaumann rate, in which the stress turns with the material's spin W),
/// integrated over one time step as
///   σ* = σ_n + Δt (Wσ_n − σ_n W)             rotation of the old stress,
///   σ_tr = σ* + Δt C:D                         elastic trial,
/// then, for a TB plasticity law (J2Plasticity: BISO, BKIN, MISO), the radial return in the
/// rotated frame (Simo & Hughes, Computational Inelasticity, Box 3.2 with combined hardening):
/// ξ = dev σ_tr − β, q = √(3/2 ξ:ξ), Δ solves q − (3G + H_kin) Δ = k(α + Δ), and
/// dev σ = dev σ_tr − 3G Δ ξ/q, β += H_kin Δ ξ/q, α += Δ.
/// Voigt order (xx, yy, zz, xy, yz, xz), tensor components (not engineering shears) for σ, β, D.
#include <cmath>
#include <optional>

#include "materials/j2_plasticity.h"

namespace impactfe {

/// The constants of one material in the rate form.
struct RateMaterial {
  double shear = 0.0;  // G
  double bulk = 0.0;   // K
  double density = 0.0;
  /// Dilatational wave speed √((K + 4G/3)/ρ) of the unscaled density.
  double wave_speed() const { return std::sqrt((bulk + 4.0 * shear / 3.0) / density); }
  std::optional<J2Plasticity> plasticity;
};

/// Rotates σ by the spin over dt: σ += dt (Wσ − σW), W = [[0, w01, w02], [−w01, 0, w12], ...]
/// given by its three upper components (w01 = W_xy, w12 = W_yz, w02 = W_xz).
inline void jaumann_rotate(double* s, double w01, double w12, double w02, double dt) {
  // (Wσ − σW) for symmetric σ and skew W, component by component.
  const double sxx = s[0], syy = s[1], szz = s[2], sxy = s[3], syz = s[4], sxz = s[5];
  const double rxx = 2.0 * (w01 * sxy + w02 * sxz);
  const double ryy = 2.0 * (-w01 * sxy + w12 * syz);
  const double rzz = 2.0 * (-w02 * sxz - w12 * syz);
  const double rxy = w01 * (syy - sxx) + w02 * syz + w12 * sxz;
  const double ryz = -w01 * sxz + w12 * (szz - syy) - w02 * sxy;
  const double rxz = w01 * syz + w02 * (szz - sxx) - w12 * sxy;
  s[0] += dt * rxx;
  s[1] += dt * ryy;
  s[2] += dt * rzz;
  s[3] += dt * rxy;
  s[4] += dt * ryz;
  s[5] += dt * rxz;
}

/// Adds the elastic increment dt C:D (tensor strain-rate components) to σ.
inline void elastic_increment(double* s, const double* d, double dt, const RateMaterial& m) {
  const double volumetric = (m.bulk - 2.0 * m.shear / 3.0) * (d[0] + d[1] + d[2]) * dt;
  const double g2 = 2.0 * m.shear * dt;
  s[0] += volumetric + g2 * d[0];
  s[1] += volumetric + g2 * d[1];
  s[2] += volumetric + g2 * d[2];
  s[3] += g2 * d[3];
  s[4] += g2 * d[4];
  s[5] += g2 * d[5];
}

/// Radial return of the trial stress `s` (changed in place) with back stress `beta` and
/// equivalent plastic strain `alpha`; returns the plastic work per unit volume σ:Δε_p (0 when
/// elastic).
double radial_return(double* s, double* beta, double& alpha, const RateMaterial& m);

}  // namespace impactfe
