#pragma once
/// Elements whose DOF list follows the deformation: a contact node against a deformable target
/// with large sliding takes the nodes of the target facets near it as DOFs, and those change as
/// it slides (elements/target_surface.h DeformableTargetPoint). Such an element implements this
/// interface beside Element; a driver reaches it with dynamic_cast (kept out of element.h, which
/// much of the program includes) after each accepted step and, when a list changed, renumbers
/// the DOFs (DofMap, Assembler, condensation) before the next step. Within a step the lists are
/// fixed, so the assembly pattern is static while Newton iterates.
#include <Eigen/Core>
#include <functional>

namespace impactfe {

/// The current position of a node (its initial position plus its displacement) at the state
/// being refreshed, with the number of the refresh pass: a shared search structure rebuilt at
/// most once per pass compares it with the pass it was built in.
struct NodePositions {
  std::function<Eigen::Vector3d(int node)> at;
  long long pass = 0;
};

class ConnectivityUpdate {
 public:
  virtual ~ConnectivityUpdate() = default;
  /// False when the element's DOFs never change (an adapter over an element without this
  /// interface, elements/element_capabilities.h): the driver skips it.
  virtual bool updates_connectivity() const { return true; }
  /// At a converged (committed) state, `u` over the element's current DOFs: re-finds the DOFs
  /// the element needs from here on. True when its dofs() changed (the caller renumbers).
  virtual bool refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) = 0;
};

}  // namespace impactfe
