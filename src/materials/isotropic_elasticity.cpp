#include "materials/isotropic_elasticity.h"

#include <fmt/format.h>

#include <cmath>

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

void require_isotropic(const Material& mat, int mat_id, int element_id,
                       const SourceLocation& where) {
  const double young = mat.get("EX", 0.0);
  const double poisson = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  const double shear = young / (2.0 * (1.0 + poisson));
  const auto check = [&](const char* label, double isotropic_value, double tolerance) {
    if (!mat.has(label)) return;
    const double given = mat.get(label, 0.0);
    if (std::abs(given - isotropic_value) <= tolerance * std::abs(isotropic_value)) return;
    throw InputError(where, fmt::format("element {}: material {} is anisotropic ({} = {:g}, the "
                                        "isotropic value is {:g}): orthotropic elasticity is not "
                                        "implemented; give isotropic constants (EX, PRXY)",
                                        element_id, mat_id, label, given, isotropic_value));
  };
  check("EY", young, 1e-12);
  check("EZ", young, 1e-12);
  for (const char* label : {"PRYZ", "PRXZ", "NUYZ", "NUXZ"}) check(label, poisson, 1e-12);
  for (const char* label : {"GXY", "GYZ", "GXZ"}) check(label, shear, 1e-4);
}

IsotropicElasticity read_isotropic_elasticity(const Model& model, int mat_id, int element_id,
                                              const SourceLocation& where) {
  const auto it = model.materials.find(mat_id);
  if (it == model.materials.end() || !it->second.has("EX"))
    throw InputError(where, fmt::format("element {}: material {} has no EX (Young's modulus)",
                                        element_id, mat_id));
  const Material& mat = it->second;
  require_isotropic(mat, mat_id, element_id, where);
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
