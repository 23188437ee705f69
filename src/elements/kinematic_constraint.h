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

/// The equations of a distributing coupling (RBE3): the master moves with the weighted
/// least-squares rigid fit of its slaves' translations. With weights w_i, W = Σ w_i, the
/// weighted centroid x_c and r_i = x_i − x_c, J = Σ w_i (|r_i|² I − r_i r_iᵀ):
///   θ = J⁻¹ Σ w_i r_i × u_i,   u_c = Σ w_i u_i / W,   u_m = u_c + θ × (x_m − x_c),  θ_m = θ;
/// their transpose hands a force F and a moment M on the master to the slaves as
/// f_i = (w_i / W) F + w_i (J⁻¹ M_c) × r_i, M_c the moment about x_c (the force in proportion
/// to the weights, the moment as forces in proportion to weight times distance). One equation
/// per master DOF of `dofs`, master first (it is the dependent DOF): −u_m + Σ c u_i = 0.
/// Throws InputError at `where` when the slaves cannot carry what is asked: J singular (fewer
/// than three slaves off one line) with a rotation asked, or with the master off the centroid.
std::vector<ConstraintEquation> distributing_coupling_equations(int master, const Vec3& x_master,
                                                                const std::vector<int>& slaves,
                                                                const std::vector<Vec3>& x_slaves,
                                                                const std::vector<double>& weights,
                                                                const std::vector<Dof>& dofs,
                                                                const SourceLocation& where);

}  // namespace impactfe
