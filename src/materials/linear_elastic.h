#pragma once
/// Linear-elastic material lookup for the elements: the few constants an element needs, with
/// the defaults of the spec (§3.6) and user errors that name the element and the material.
#include <string_view>

#include "core/model.h"

namespace impactfe {

/// Isotropic linear-elastic constants in deck units (e.g. psi and lbf·s²/in⁴ in the thesis).
struct ElasticMaterial {
  double youngs_modulus = 0.0;  ///< EX (> 0, required)
  double poisson_ratio = 0.3;   ///< NUXY (or PRXY); 0.3 when not given
  double density = 0.0;         ///< DENS (mass per volume); 0 when not given
};

/// Constants of material `record.mat` for element `record`. Throws InputError at the E command's
/// location when the material is undefined or has no positive EX; `family` names the element
/// family in the message (e.g. "Spar").
ElasticMaterial elastic_material(const Model& model, const ElementRecord& record,
                                 std::string_view family);

}  // namespace impactfe
