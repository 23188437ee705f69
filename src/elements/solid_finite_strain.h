#pragma once
/// Large deflection (NLGEOM,ON) of the 3-D continuum elements with a committed state per
/// integration point: the finite-strain kinematics shared by SOLID185 (elements/brick8.h) and
/// SOLID186 / SOLID187 (elements/solid_quadratic.h). Updated Lagrangian, hypoelastic, the
/// midpoint configuration with the Hughes-Winget incremental rotation, Cauchy stress and the
/// logarithmic strain accumulated from increments: the formulation MAPDL documents for its 18x
/// solids (Theory Reference §3.2), the 3-D form of plane_solid_finite.cpp (equations in
/// solid_finite_strain.cpp).
#include <Eigen/Core>

#include <optional>
#include <vector>

#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// One integration point in the reference configuration.
struct FiniteStrainPoint {
  Eigen::Matrix3Xd grad;  ///< ∂N_a/∂X of the element's functions (reference configuration)
  double dv0 = 0.0;       ///< weight × det J (reference measure)
};

/// The committed state of one integration point, in global axes of the configuration of the
/// committed displacement.
struct FiniteStrainState {
  Vector6d strain = Vector6d::Zero();  ///< accumulated logarithmic strain, engineering shear
  PlasticState plastic;                ///< the J2 state (plastic elements)
};

/// The states at a displacement: what a converged step commits, and what results read.
struct FiniteStrainUpdate {
  std::vector<FiniteStrainState> states;  ///< rotated into the current configuration
  std::vector<Vector6d> stress;           ///< Cauchy stress, global axes (xx yy zz xy yz xz)
  std::vector<double> dv;                 ///< current measure det F dV₀ of each point
};

/// The element data the finite-strain sum reads.
struct FiniteStrainElement {
  int id = 0;  ///< for the messages
  const std::vector<FiniteStrainPoint>* points = nullptr;
  Matrix6d d;                                ///< isotropic elasticity (engineering shear)
  const J2Plasticity* plasticity = nullptr;  ///< nullptr: hypoelastic σ̂ = D ε
  /// Mean dilatation (B-bar): the volumetric part of every point's strain increment replaced
  /// by its mean over the element, reference-volume weights.
  bool mean_dilatation = false;
};

/// The tangent finite_strain_sum() forms. Exact: the derivative of the internal force (not
/// symmetric). Symmetric: the material term ∫ δε̄ᵀ C δε̄ dv (the law's algorithmic tangent
/// rotated by ΔR, the strain variations of the midpoint kinematics with the mean dilatation)
/// plus the initial-stress term ∫ ∇N_a·σ∇N_b I dv, the form of the symmetric solvers.
enum class FiniteStrainTangent { Exact, Symmetric };

/// Internal force f (3 per function, function order of FiniteStrainPoint::grad) at the total
/// displacement u (3 x n) from the committed displacement u_n and the committed states; the
/// tangent of the given form into K when given; the states at u into `update` when given.
/// Throws ElementSolutionError when a point turns inside out.
void finite_strain_sum(const FiniteStrainElement& element, const Eigen::Matrix3Xd& u_n,
                       const Eigen::Matrix3Xd& u, const std::vector<FiniteStrainState>& committed,
                       Eigen::MatrixXd* K, Eigen::VectorXd& f, FiniteStrainUpdate* update,
                       FiniteStrainTangent form = FiniteStrainTangent::Exact);

}  // namespace impactfe
