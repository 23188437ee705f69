#pragma once
/// Two-node axial spar: LINK1 (2-D, UX UY), LINK8 / LINK180 (3-D, UX UY UZ). Spec §11.1.
#include <string>
#include <vector>

#include "elements/corotational.h"
#include "elements/element.h"

namespace impactfe {

/// Pin-jointed bar with axial stiffness EA/L, optional initial strain ISTRN, stress stiffening
/// and co-rotational large deflection. Results: FORC (axial force N, tension +), SAXL (N/A),
/// EPEL (N/EA), LENGTH (current length).
class Spar final : public Element {
 public:
  /// `member` holds the reference direction (2 or 3 components) and length L > 0.
  Spar(int id, std::vector<DofKey> dofs, corotational::AxialMember member, double area,
       double youngs_modulus, double density, double initial_strain);

  const char* family() const override { return "Spar"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent (ρAL/6)[2I I; I 2I] or lumped (ρAL/2) I per node.
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  std::optional<double> volume() const override { return area_ * member_.length; }
  double area() const { return area_; }
  double length() const { return member_.length; }

 private:
  corotational::AxialKinematics kinematics(const ElementContext& ctx) const;

  std::vector<DofKey> dofs_;
  corotational::AxialMember member_;
  double area_;
  double youngs_modulus_;
  double density_;
  double initial_strain_;
};

}  // namespace impactfe
