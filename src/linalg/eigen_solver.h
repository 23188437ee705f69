#pragma once
/// Generalized symmetric eigenproblem K x = λ M x for the lowest modes (modal analysis):
/// shift-invert Lanczos (Spectra) on the sparse factorization of K − σM, or a dense
/// Cholesky-based solve for small systems. M may be singular (massless DOFs give λ = ∞).
#include <vector>

#include "linalg/sparse.h"

namespace impactfe {

struct EigenResult {
  VectorXd eigenvalues;   // λ = ω², ascending
  MatrixXd eigenvectors;  // columns, mass-normalised (xᵀ M x = 1)
};

/// `k_lower`, `m_lower`: lower triangles of K and M (free DOFs). `n_modes`: modes wanted.
/// `shift`: σ of the shift-invert (below the lowest wanted eigenvalue; negative handles rigid
/// body modes).
EigenResult lowest_eigenpairs(const SparseMatrix& k_lower, const SparseMatrix& m_lower, int n_modes,
                              double shift);

}  // namespace impactfe
