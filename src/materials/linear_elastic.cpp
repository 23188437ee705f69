#include "materials/linear_elastic.h"

#include <fmt/format.h>

#include "materials/isotropic_elasticity.h"

namespace impactfe {

ElasticMaterial elastic_material(const Model& model, const ElementRecord& record,
                                 std::string_view family) {
  const auto it = model.materials.find(record.mat);
  if (it == model.materials.end())
    throw InputError(record.where, fmt::format("element {} ({}): material {} is not defined",
                                               record.id, family, record.mat));
  const Material& mat = it->second;
  if (!mat.has("EX"))
    throw InputError(record.where, fmt::format("element {} ({}): material {} has no EX", record.id,
                                               family, record.mat));
  require_isotropic(mat, record.mat, record.id, record.where);
  ElasticMaterial out;
  out.youngs_modulus = mat.get("EX", 0.0);
  if (!(out.youngs_modulus > 0.0))
    throw InputError(record.where,
                     fmt::format("element {} ({}): material {} has EX = {} (must be positive)",
                                 record.id, family, record.mat, out.youngs_modulus));
  // NUXY and PRXY are the same constant here (isotropic use); NUXY wins if both are given.
  out.poisson_ratio = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  out.density = mat.get("DENS", 0.0);
  if (out.density < 0.0)
    throw InputError(record.where, fmt::format("element {} ({}): material {} has DENS = {} < 0",
                                               record.id, family, record.mat, out.density));
  return out;
}

}  // namespace impactfe
