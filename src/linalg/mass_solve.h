#pragma once
/// M a = r for a mass matrix M (the initial acceleration of a transient, M a0 = f(0) − C v0 −
/// f_int(u0)).
#include "linalg/sparse.h"

namespace impactfe {

/// How `solve_mass_system` solved its last system (for tests and the benchmark notes).
enum class MassSolveMethod { SimplicialLdlt, ConjugateGradient, SparseFactorization };

struct MassSolveResult {
  VectorXd a;
  MassSolveMethod method = MassSolveMethod::SimplicialLdlt;
  int iterations = 0;  // conjugate gradient iterations (0 for a factorization)
};

/// Solves M a = r, M symmetric positive (semi)definite given by its lower triangle.
/// - A small M (at most 4096 rows): Eigen's simplicial LDLᵀ, exact and cheaper than any set-up.
/// - A large one: conjugate gradients on M scaled symmetrically by its diagonal,
///   D^-1/2 M D^-1/2. A Galerkin mass matrix so scaled has eigenvalues in a fixed interval
///   whatever the mesh size (Wathen, IMA J. Numer. Anal. 7 (1987) 449–457: for bilinear
///   quadrilaterals [1/4, 9/4], for trilinear bricks [1/8, 27/8]), so the iterations needed do
///   not grow with the model: 29 to a relative residual of 2e-16 on the 155 522-DOF shell dome,
///   where the sparse factorization's fill-reducing ordering and factor took seconds and a
///   factor-sized block of memory (issue 11).
/// - When the iterations do not reach the residual (not a mass matrix those bounds hold for, a
///   singular one, a diagonal entry that is not positive): the run's sparse solver (CHOLMOD, or
///   MUMPS), then the simplicial LDLᵀ, which also solves a consistent semidefinite system.
MassSolveResult solve_mass_system(const SparseMatrix& lower_mass, const VectorXd& r);

}  // namespace impactfe
