// MPC184 rigid link (KEYOPT(1) = 0) and rigid beam (KEYOPT(1) = 1) by direct elimination
// (docs/elements/mpc184.md). The element has no stiffness and no mass of its own: it gives the
// constraint equations of its kinematics (elements/kinematic_constraint.h), which the structure
// eliminates with those of CE and CERIG (assembly/constraint_equations.h). MAPDL's KEYOPT(2)
// chooses direct elimination (0) or Lagrange multipliers (1); both are eliminated here, which
// gives the same displacements (the multipliers are the constraint forces, not solved for).
// MPC184's joints, slider and other forms (KEYOPT(1) > 1) are refused (element_fields.cpp).
#include <fmt/format.h>

#include "elements/element_registry.h"
#include "elements/kinematic_constraint.h"
#include "elements/line_element_data.h"

namespace impactfe {

namespace {

const std::vector<std::string> kNoResults;

class RigidLink final : public Element, public KinematicConstraint {
 public:
  RigidLink(int id, bool beam, const Node& i, const Node& j, SourceLocation where)
      : Element(id), beam_(beam), i_(i.id), j_(j.id), xi_(i.x), xj_(j.x), where_(std::move(where)) {
    const int per_node = beam ? 6 : 3;
    for (int node : {i_, j_})
      for (int d = 0; d < per_node; ++d) dofs_.push_back(DofKey{node, kAllDofs[d]});
  }

  const char* family() const override { return "RigidLink"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  // No stiffness and no mass: the element acts only through its equations.
  void tangent(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    K.setZero(n_dofs(), n_dofs());
    f_int.setZero(n_dofs());
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override {
    M.setZero(n_dofs(), n_dofs());
  }
  const std::vector<std::string>& result_names() const override { return kNoResults; }
  void results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out.clear();
  }

  std::vector<ConstraintEquation> constraint_equations() const override {
    if (beam_) {
      // Rigid beam: node J follows node I as a rigid body, u_J = u_I + θ_I × (x_J − x_I),
      // θ_J = θ_I (small rotations): node I is retained, node J eliminated.
      return rigid_region_equations(i_, xi_, j_, xj_, true, {kAllDofs.begin(), kAllDofs.end()},
                                    where_);
    }
    // Rigid link (pin-jointed): its length is kept, linearised e · (u_J − u_I) = 0 with e the
    // unit vector from I to J. The slave is J's component along which e is largest (the best
    // conditioned of the three), the one DOF the equation removes.
    const Vec3 e = (xj_ - xi_).normalized();
    int k = 0;
    e.cwiseAbs().maxCoeff(&k);
    ConstraintEquation eq;
    eq.where = where_;
    eq.terms.push_back({DofKey{j_, kAllDofs[k]}, e(k)});
    for (int d = 0; d < 3; ++d) {
      if (d != k && e(d) != 0.0) eq.terms.push_back({DofKey{j_, kAllDofs[d]}, e(d)});
      if (e(d) != 0.0) eq.terms.push_back({DofKey{i_, kAllDofs[d]}, -e(d)});
    }
    return {eq};
  }

 private:
  bool beam_;
  int i_, j_;
  Vec3 xi_, xj_;
  SourceLocation where_;
  std::vector<DofKey> dofs_;
};

std::unique_ptr<Element> make_rigid_link(const ElementBuildContext& ctx,
                                         const ElementRecord& record) {
  constexpr const char* family = "RigidLink";
  const ElementType& type = line_data::element_type(ctx.model, record);
  const Node& i = line_data::node(ctx.model, record, 0, 2, family);
  const Node& j = line_data::node(ctx.model, record, 1, 2, family);
  if ((j.x - i.x).norm() == 0.0)
    throw InputError(record.where, fmt::format("element {} (MPC184): nodes {} and {} coincide; a "
                                               "rigid link needs a length",
                                               record.id, i.id, j.id));
  if (i.rotated() || j.rotated())
    throw InputError(record.where,
                     fmt::format("element {} (MPC184): node {} has a rotated nodal coordinate "
                                 "system; rigid links are written in global axes here",
                                 record.id, i.rotated() ? i.id : j.id));
  return std::make_unique<RigidLink>(record.id, type.key(1) == 1, i, j, record.where);
}

const ElementRegistration kMpc184{{.name = "MPC184",
                                   .number = 184,
                                   .family = "RigidLink",
                                   .n_nodes = 2,
                                   .real_constants = RealConstantUse::None,
                                   .vtk_cell = VtkCell::Line,
                                   .role = ShapeRole::Line,
                                   .result_names = kNoResults,
                                   .create = make_rigid_link}};

}  // namespace

}  // namespace impactfe
