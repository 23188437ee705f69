#pragma once
/// An element that is a kinematic constraint rather than a stiffness (MPC184 rigid link and
/// rigid beam): it gives linear constraint equations, which the structure eliminates with those
/// of CE and CERIG (assembly/constraint_equations.h). Read from the element as built, before any
/// adapter wraps it (the equations then make the adapters), so it is not one of the optional
/// interfaces an adapter forwards (elements/element_capabilities.h).
#include <vector>

#include "core/model.h"

namespace impactfe {

class KinematicConstraint {
 public:
  virtual ~KinematicConstraint() = default;
  /// The equations, each slave first, in the element's nodal DOFs (global axes).
  virtual std::vector<ConstraintEquation> constraint_equations() const = 0;
  /// True when the constraint is a rigid body's, which NLGEOM would need in its large-rotation
  /// form (not implemented: the equations are those of small rotations).
  virtual bool is_rigid_body() const { return true; }
};

/// The equations of a rigid region of small rotations (CERIG; the MPC184 rigid beam):
///   u_s = u_m + θ_m × (x_s − x_m),  θ_s = θ_m,
/// one per slave DOF, slave first: u_s − u_m − (θ_m × d) = 0, d = x_s − x_m. `three_d`: the 3-D
/// form (UX UY UZ ROTX ROTY ROTZ); else the 2-D form in the XY plane (UX UY ROTZ). `dofs`:
/// which slave DOFs get an equation.
std::vector<ConstraintEquation> rigid_region_equations(int master, const Vec3& x_master, int slave,
                                                       const Vec3& x_slave, bool three_d,
                                                       const std::vector<Dof>& dofs,
                                                       const SourceLocation& where);

}  // namespace impactfe
