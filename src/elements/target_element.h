#pragma once
/// The element of a TARGE169 segment or a TARGE170 facet or pilot. It carries nothing itself:
/// its target acts through the contact elements of its real set (elements/target_surface.h,
/// target_line.h), which take the pilot's DOFs (rigid target) or the target nodes' (deformable
/// target). Its nodes' translations (UX, UY in 2-D; UX, UY, UZ in 3-D) are listed so that the
/// element is well formed; on a rigid target, without stiffness or mass, they are constrained
/// automatically (what MAPDL does for KEYOPT(2) = 0), unless the pilot.
#include <fmt/format.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "core/errors.h"
#include "elements/element.h"

namespace impactfe {

class TargetElement final : public Element {
 public:
  TargetElement(int id, const char* family, const std::vector<int>& nodes,
                std::initializer_list<Dof> per_node)
      : Element(id), family_(family) {
    for (int n : nodes)
      for (Dof d : per_node) dofs_.push_back({n, d});
  }
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  const char* family() const override { return family_; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  void tangent(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    K.setZero(n_dofs(), n_dofs());
    f_int.setZero(n_dofs());
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override {
    M.setZero(n_dofs(), n_dofs());
  }
  static const std::vector<std::string>& names() {
    static const std::vector<std::string> n;
    return n;
  }
  const std::vector<std::string>& result_names() const override { return names(); }
  void results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out.clear();
  }

 private:
  const char* family_;
  std::vector<DofKey> dofs_;
};

/// A target type carries out KEYOPT(2) (0 automatic, 1 given boundary conditions of a rigid
/// target) only: any other nonzero KEYOPT is refused at `record`.
inline void check_target_keyopts(const ElementType& type, const ElementRecord& record,
                                 const char* name) {
  for (int k = 1; k < static_cast<int>(type.keyopt.size()); ++k)
    if (type.key(k) != 0 && !(k == 2 && type.key(k) == 1))
      throw InputError(record.where,
                       fmt::format("element {} ({}): KEYOPT({}) = {} is not supported "
                                   "(KEYOPT(2) 0 or 1; the others 0)",
                                   record.id, name, k, type.key(k)));
}

}  // namespace impactfe
