#pragma once
/// Isotropic linear elasticity for 3-D continuum elements (SOLID45 / SOLID185).
#include <Eigen/Core>

#include <string>

#include "core/errors.h"
#include "core/model.h"

namespace impactfe {

/// 6x6 Voigt components in ANSYS order (xx, yy, zz, xy, yz, xz).
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Isotropic elastic constants of one material (units of the deck).
struct IsotropicElasticity {
  double young = 0.0;    // EX (force/area)
  double poisson = 0.3;  // NUXY / PRXY (ANSYS default 0.3)
  double density = 0.0;  // DENS (mass/volume), 0 when not given
};

/// Constitutive matrix D with sigma = D * epsilon, engineering shear strains
/// (gamma_xy = 2 eps_xy), Voigt order (xx, yy, zz, xy, yz, xz) — Bathe (4.22)/Cook (3.1-5).
/// Precondition: young > 0 and -1 < poisson < 0.5.
Matrix6d isotropic_elasticity_matrix(double young, double poisson);

/// Refuses the constants of an anisotropic (orthotropic) solid, which the elements here do not
/// compute: EY or EZ other than EX, NUYZ or NUXZ (PRYZ, PRXZ) other than NUXY, or a shear
/// modulus GXY, GYZ or GXZ other than EX / (2 (1 + NUXY)) (to 1e-4, for rounded input). A
/// constant left out takes its isotropic value, as MAPDL's defaults do. Throws InputError at
/// `where` naming the material, the element and the constant.
void require_isotropic(const Material& mat, int mat_id, int element_id,
                       const SourceLocation& where);

/// Reads EX, NUXY (or PRXY, default 0.3) and DENS of material `mat_id` for element `element_id`.
/// Throws InputError at `where` when the material or EX is missing, EX <= 0, or NUXY is outside
/// (-1, 0.5), and for anisotropic constants (require_isotropic).
IsotropicElasticity read_isotropic_elasticity(const Model& model, int mat_id, int element_id,
                                              const SourceLocation& where);

}  // namespace impactfe
