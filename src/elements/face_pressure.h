#pragma once
/// Consistent nodal forces of a pressure on a bilinear quadrilateral face, shared by the
/// elements that take surface loads (bricks, shells).
#include <array>

#include "core/coordinate_system.h"

namespace impactfe {

/// f_a = ∫ N_a p (∂x/∂ξ × ∂x/∂η) dξ dη over the bilinear face x(ξ, η) = Σ N_a x_a (ξ along
/// corner 0 → 1, η along 0 → 3), with the pressure interpolated from its corner values p_a;
/// 3 × 3 Gauss points, exact for a flat face (Zienkiewicz & Taylor vol. 1 §9.4). The forces point
/// along the normal of the corner order (right-hand rule): callers give the sign of the load.
std::array<Vec3, 4> bilinear_face_pressure_forces(const std::array<Vec3, 4>& x,
                                                  const std::array<double, 4>& p);

}  // namespace impactfe
