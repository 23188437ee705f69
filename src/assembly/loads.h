#pragma once
/// External loads of a load step at a fraction of its time span: nodal forces (F), the inertia
/// load of the frame acceleration (ACEL: f = -M r a, spec §3.19) and prescribed displacements
/// (D), ramped or stepped per KBC (spec §3.20).
#include <array>

#include "assembly/dof_map.h"
#include "core/model.h"
#include "linalg/sparse.h"

namespace impactfe {

/// Interpolation of one load step: `previous` is the step before (nullptr for the first step)
/// and `fraction` in [0, 1] the position within the step (1 = end of step).
struct LoadPoint {
  const LoadStep* current = nullptr;
  const LoadStep* previous = nullptr;
  double fraction = 1.0;
};

/// Value of a DOF entry of a load table at a load point (KBC ramp from the previous value).
double interpolate(const LoadPoint& at, double previous_value, double current_value);

/// Nodal forces F over all active DOFs (entries on constrained DOFs are dropped: the constraint
/// wins).
VectorXd nodal_forces(const DofMap& dofs, const LoadPoint& at);
/// Frame acceleration (ACEL) at a load point.
Vec3 frame_acceleration(const LoadPoint& at);
/// Inertia load of a frame acceleration over all active DOFs, summed from each element's
/// Element::frame_acceleration_load (−M r a, or −Σ a_d g_d exactly for a superelement).
VectorXd inertia_load(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                      const ElementContext& ctx, const Vec3& acel);
/// The frame-acceleration load is linear in a: f(a) = Σ_d a_d f(e_d). The three unit loads are
/// assembled once per DOF numbering (through the element hook, so superelements are exact) and
/// each time step costs three vector updates.
class FrameAccelerationLoad {
 public:
  FrameAccelerationLoad() = default;
  FrameAccelerationLoad(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                        const ElementContext& ctx);
  /// −M r a over all active DOFs.
  VectorXd operator()(const Vec3& acel) const;

 private:
  std::array<VectorXd, 3> unit_;
};

/// Prescribed displacements: values on constrained DOFs (index >= n_free), zero elsewhere.
VectorXd prescribed_displacements(const DofMap& dofs, const LoadPoint& at);
/// Constrained DOF set of a load step (D entries).
std::set<DofKey> constrained_set(const LoadStep& step);

}  // namespace impactfe
