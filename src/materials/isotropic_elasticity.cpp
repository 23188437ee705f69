#include "materials/isotropic_elasticity.h"

#include <fmt/format.h>

namespace impactfe {

Matrix6d isotropic_elasticity_matrix(double young, double poisson) {
  // Lame constants; shear rows use G because the strains are engineering shear strains.
  const double lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double shear = young / (2.0 * (1.0 + poisson));
  Matrix6d d = Matrix6d::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) d(i, j) = lambda;
    d(i, i) = lambda + 2.0 * shear;
    d(i + 3, i + 3) = shear;
  }
  return d;
}

IsotropicElasticity read_isotropic_elasticity(const Model& model, int mat_id, int element_id,
                                              const SourceLocation& where) {
  const auto it = model.materials.find(mat_id);
  if (it == model.materials.end() || !it->second.has("EX"))
    throw InputError(where, fmt::format("element {}: material {} has no EX (Young's modulus)",
                                        element_id, mat_id));
  const Material& mat = it->second;
  IsotropicElasticity out;
  out.young = mat.get("EX", 0.0);
  out.poisson = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  out.density = mat.get("DENS", 0.0);
  if (!(out.young > 0.0))
    throw InputError(where, fmt::format("element {}: material {} has EX = {} (must be > 0)",
                                        element_id, mat_id, out.young));
  if (!(out.poisson > -1.0 && out.poisson < 0.5))
    throw InputError(where,
                     fmt::format("element {}: material {} has NUXY = {} (must be in (-1, 0.5))",
                                 element_id, mat_id, out.poisson));
  if (out.density < 0.0)
    throw InputError(where, fmt::format("element {}: material {} has DENS = {} (must be >= 0)",
                                        element_id, mat_id, out.density));
  return out;
}

}  // namespace impactfe
