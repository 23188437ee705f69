#include "linalg/mass_solve.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "linalg/linear_solver.h"

namespace impactfe {

namespace {

/// Rows up to which the simplicial LDLᵀ is used directly.
constexpr int kDirectRows = 4096;
/// Relative residual of the scaled system the iterations aim at (as computed by the recurrence:
/// the true one then is about 2e-16), and the one a solution must have to be accepted. Aiming
/// at 1e-14 instead left accelerations of 2e-9 where a uniform body load gives none (shell dome:
/// the rotations), and a first displacement 1e-9 off free fall; at 1e-16 they are 1e-11 and
/// 1.4e-11, closer than the sparse factorization's 4e-11.
constexpr double kTargetResidual = 1e-16;
constexpr double kAcceptedResidual = 1e-12;
/// A diagonally scaled mass needs tens of iterations; hundreds mean it is not a mass matrix
/// the bounds above hold for.
constexpr int kMaxIterations = 300;

double relative_residual(const SparseMatrix& lower, const VectorXd& a, const VectorXd& r) {
  const double norm_r = r.norm();
  const VectorXd residual = r - lower.selfadjointView<Eigen::Lower>() * a;
  return norm_r > 0.0 ? residual.norm() / norm_r : residual.norm();
}

}  // namespace

MassSolveResult solve_mass_system(const SparseMatrix& lower_mass, const VectorXd& r) {
  MassSolveResult result;
  if (r.size() == 0 || r.isZero(0.0)) {
    result.a = VectorXd::Zero(r.size());
    return result;
  }
  if (lower_mass.rows() > kDirectRows) {
    // Symmetrically scaled by the diagonal, S = D^-1/2 M D^-1/2 (unit diagonal): the residual
    // is then measured where all DOFs weigh alike (a shell's rotary inertia is t²/12 of its
    // translational mass), and S's condition number is Wathen's bound.
    const VectorXd diagonal = lower_mass.diagonal();
    if ((diagonal.array() > 0.0).all()) {
      const VectorXd scale = diagonal.cwiseSqrt().cwiseInverse();
      SparseMatrix scaled = lower_mass;
      for (int j = 0; j < scaled.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(scaled, j); it; ++it)
          it.valueRef() *= scale(it.row()) * scale(it.col());
      const VectorXd rhs = scale.cwiseProduct(r);
      Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower, Eigen::IdentityPreconditioner> cg;
      cg.setTolerance(kTargetResidual);
      cg.setMaxIterations(kMaxIterations);
      cg.compute(scaled);
      const VectorXd y = cg.solve(rhs);
      result.iterations = static_cast<int>(cg.iterations());
      if (y.allFinite() && relative_residual(scaled, y, rhs) <= kAcceptedResidual) {
        result.a = scale.cwiseProduct(y);
        result.method = MassSolveMethod::ConjugateGradient;
        return result;
      }
    }
    result.iterations = 0;
    const auto solver = make_linear_solver(static_cast<int>(lower_mass.rows()));
    try {
      solver->analyze_pattern(lower_mass);
      solver->factorize(lower_mass);
      result.a = solver->solve(r);
      result.method = MassSolveMethod::SparseFactorization;
      return result;
    } catch (const SingularMatrixError&) {
    }
  }
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(lower_mass);
  result.a = ldlt.solve(r);
  result.method = MassSolveMethod::SimplicialLdlt;
  return result;
}

}  // namespace impactfe
