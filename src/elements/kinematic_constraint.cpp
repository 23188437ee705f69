#include "elements/kinematic_constraint.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"

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

std::vector<ConstraintEquation> distributing_coupling_equations(int master, const Vec3& x_master,
                                                                const std::vector<int>& slaves,
                                                                const std::vector<Vec3>& x_slaves,
                                                                const std::vector<double>& weights,
                                                                const std::vector<Dof>& dofs,
                                                                const SourceLocation& where) {
  const std::size_t n = slaves.size();
  double total = 0.0;
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    total += weights[i];
    centre += weights[i] * x_slaves[i];
  }
  if (!(total > 0.0))
    throw InputError(where, "the slaves' weights add up to zero: give positive weights");
  centre /= total;
  const auto cross = [](const Vec3& v) {
    Eigen::Matrix3d m;
    m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return m;
  };
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  double size = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 r = x_slaves[i] - centre;
    j += weights[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    size = std::max(size, r.norm());
  }
  const Vec3 offset = x_master - centre;
  bool rotations = false;
  for (Dof d : dofs) rotations = rotations || d == Dof::ROTX || d == Dof::ROTY || d == Dof::ROTZ;
  // J's smallest eigenvalue against its largest: zero when the slaves lie on one line (no
  // rotation about it is seen) or are one point.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(j, Eigen::EigenvaluesOnly);
  const bool singular = !(es.eigenvalues()(0) > 1e-10 * es.eigenvalues()(2));
  const bool lever = offset.norm() > 1e-12 * std::max(size, offset.norm());
  if (singular && (rotations || lever))
    throw InputError(
        where,
        fmt::format("RBE3 master node {}: the {} slave node(s) lie on one line or at "
                    "one point, so they cannot carry {}; give at least three slaves "
                    "off one line",
                    master, n,
                    rotations ? "the master's rotations" : "a force off their weighted centroid"));
  const Eigen::Matrix3d j_inv = singular ? Eigen::Matrix3d::Zero() : Eigen::Matrix3d(j.inverse());
  // u_m = Σ A_i u_i with A_i = (w_i/W) I − [d]× J⁻¹ w_i [r_i]×; θ = Σ B_i u_i, B_i = J⁻¹ w_i
  // [r_i]×.
  std::vector<Eigen::Matrix3d> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    b[i] = j_inv * (weights[i] * cross(x_slaves[i] - centre));
    a[i] = (weights[i] / total) * Eigen::Matrix3d::Identity() - cross(offset) * b[i];
  }
  constexpr Dof kTranslations[3] = {Dof::UX, Dof::UY, Dof::UZ};
  std::vector<ConstraintEquation> out;
  for (Dof dof : dofs) {
    const bool turn = dof == Dof::ROTX || dof == Dof::ROTY || dof == Dof::ROTZ;
    const int row = turn ? static_cast<int>(dof) - static_cast<int>(Dof::ROTX)
                         : static_cast<int>(dof) - static_cast<int>(Dof::UX);
    ConstraintEquation eq;
    eq.where = where;
    eq.terms.push_back({DofKey{master, dof}, -1.0});
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        const double coefficient = turn ? b[i](row, k) : a[i](row, k);
        if (coefficient != 0.0)
          eq.terms.push_back({DofKey{slaves[i], kTranslations[k]}, coefficient});
      }
    // Round-off of the products (1e-17 where a lever arm cancels) is not a term.
    double largest = 0.0;
    for (const ConstraintTerm& t : eq.terms) largest = std::max(largest, std::abs(t.coefficient));
    std::erase_if(eq.terms, [&](const ConstraintTerm& t) {
      return std::abs(t.coefficient) < 1e-13 * largest;
    });
    out.push_back(std::move(eq));
  }
  return out;
}

}  // namespace impactfe
