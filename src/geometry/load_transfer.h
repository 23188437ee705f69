#pragma once
/// Transfer of the loads on solid-model entities to the mesh (SBCTRAN, done at every SOLVE;
/// APDL_MODELING §5.6): DK/FK to the keypoint nodes, DL to the line nodes, DA to the area nodes
/// (SYMM/ASYM as the DOFs of a symmetry plane normal to a global axis), SFA to the element faces
/// on the area. Loads on unselected entities or nodes are not transferred. Transferred loads
/// overwrite direct FE loads on the same item; what the previous transfer wrote is removed
/// first, so the mesh always carries the current solid loads.
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/model.h"

namespace impactfe::geometry {

/// Transfers; returns notes about loads that could not be transferred (entity not meshed).
std::vector<std::string> transfer_solid_loads(Model& model, const SourceLocation& where);

/// The DOFs a symmetry (or antisymmetry) condition fixes on a plane of unit normal `normal`,
/// which must be parallel to a global axis: symmetry fixes the normal translation and the two
/// rotations about in-plane axes; antisymmetry the two in-plane translations and the rotation
/// about the normal. Throws InputError at `where` otherwise.
std::vector<Dof> symmetry_dofs(const Vec3& normal, SymmetryKind kind, const SourceLocation& where,
                               const std::string& what);

}  // namespace impactfe::geometry
