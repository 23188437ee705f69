// Large deflection of the plastic brick (elements/brick8.h): the updated-Lagrangian finite
// strain of elements/solid_finite_strain.h on the 8 Gauss points, with the mean dilatation
// (B-bar, SOLID185 KEYOPT(2) = 0) applied to the strain increment.
#include <Eigen/Dense>

#include "core/errors.h"
#include "elements/brick8.h"

namespace impactfe {

void Brick8::finite_sum(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd* kc,
                        Eigen::VectorXd& fc, FiniteStrainUpdate* update,
                        FiniteStrainTangent form) const {
  FiniteStrainElement e;
  e.id = id();
  e.points = &finite_points_;
  e.d = d_;
  e.plasticity = &*plasticity_;
  e.mean_dilatation = true;  // bbar_active(): a plastic brick without internal parameters
  const Eigen::Map<const Eigen::Matrix<double, 3, 8>> u(uc.data());
  finite_strain_sum(e, committed_u_, u, finite_, kc, fc, update, form);
}

void Brick8::finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f_int,
                            bool symmetric) const {
  IMPACTFE_CHECK(finite_strain(), "finite_tangent of a brick built without finite strain");
  Eigen::MatrixXd kc;
  Eigen::VectorXd fc;
  finite_sum(to_corners(u), &kc, fc, nullptr,
             symmetric ? FiniteStrainTangent::Symmetric : FiniteStrainTangent::Exact);
  if (symmetric) kc = 0.5 * (kc + kc.transpose()).eval();
  from_corners(kc, fc, K, f_int);
}

Vector6d Brick8::finite_point_stress(const Eigen::VectorXd& u, int p) const {
  FiniteStrainUpdate at;
  Eigen::VectorXd fc;
  finite_sum(to_corners(u), nullptr, fc, &at);
  return at.stress.at(static_cast<std::size_t>(p));
}

void Brick8::finite_commit(const Eigen::Matrix<double, 24, 1>& uc) {
  FiniteStrainUpdate at;
  Eigen::VectorXd fc;
  finite_sum(uc, nullptr, fc, &at);
  finite_ = at.states;
  for (std::size_t p = 0; p < finite_.size(); ++p) committed_[p] = finite_[p].plastic;
  committed_u_ = Eigen::Map<const Eigen::Matrix<double, 3, 8>>(uc.data());
}

}  // namespace impactfe
