#include "elements/kinematic_constraint.h"

#include <vector>

namespace impactfe {

std::vector<ConstraintEquation> rigid_region_equations(int master, const Vec3& x_master, int slave,
                                                       const Vec3& x_slave, bool three_d,
                                                       const std::vector<Dof>& dofs,
                                                       const SourceLocation& where) {
  const Vec3 d = x_slave - x_master;
  const auto m = [master](Dof dof, double c) { return ConstraintTerm{DofKey{master, dof}, c}; };
  std::vector<ConstraintEquation> out;
  for (Dof dof : dofs) {
    ConstraintEquation eq;
    eq.where = where;
    eq.terms.push_back({DofKey{slave, dof}, 1.0});
    // u_s − u_m − θ_m × d = 0, component by component (small rotations):
    //   (θ × d)_x = θy dz − θz dy, (θ × d)_y = θz dx − θx dz, (θ × d)_z = θx dy − θy dx.
    switch (dof) {
      case Dof::UX:
        eq.terms.push_back(m(Dof::UX, -1.0));
        if (three_d) eq.terms.push_back(m(Dof::ROTY, -d.z()));
        eq.terms.push_back(m(Dof::ROTZ, d.y()));
        break;
      case Dof::UY:
        eq.terms.push_back(m(Dof::UY, -1.0));
        eq.terms.push_back(m(Dof::ROTZ, -d.x()));
        if (three_d) eq.terms.push_back(m(Dof::ROTX, d.z()));
        break;
      case Dof::UZ:
        eq.terms.push_back(m(Dof::UZ, -1.0));
        eq.terms.push_back(m(Dof::ROTX, -d.y()));
        eq.terms.push_back(m(Dof::ROTY, d.x()));
        break;
      default:  // θ_s = θ_m
        eq.terms.push_back(m(dof, -1.0));
        break;
    }
    std::erase_if(eq.terms, [](const ConstraintTerm& t) { return t.coefficient == 0.0; });
    out.push_back(std::move(eq));
  }
  return out;
}

}  // namespace impactfe
