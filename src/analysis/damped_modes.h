#pragma once
/// Damped (complex) modes by the QR damped method (MODOPT,QRDAMP; MAPDL Theory Reference,
/// "QR Damped Method"): the free vibration projected on the undamped, mass-normalised modes Φ,
///   q̈ + C_m q̇ + Λ q = 0,  Φᵀ M Φ = I,  Φᵀ K Φ = Λ = diag(ω_j²),  C_m = Φᵀ C Φ (+ modal ratios),
/// is solved as the first-order eigenproblem of A = [0 I; −Λ −C_m] (2n × 2n, dense: n is the
/// number of modes). Each eigenvalue λ = σ ± i ω_d gives a stability σ (negative: decaying) and
/// a damped frequency ω_d; with C_m diagonal, σ = −ζ ω and ω_d = ω √(1 − ζ²).
#include <vector>

#include "core/model.h"
#include "linalg/sparse.h"

namespace impactfe {

struct DampedMode {
  double stability = 0.0;         // σ = Re λ (rad/s); negative when the mode decays
  double damped_frequency = 0.0;  // ω_d = Im λ ≥ 0 (rad/s); 0 for an overdamped mode
  /// The modulus the modes are ordered by: |λ| (for an overdamped pair √(λ₁ λ₂)), the undamped
  /// natural frequency when the damping is proportional.
  double natural_frequency = 0.0;
};

/// The n damped modes of the projected system, ordered by natural_frequency. A conjugate pair
/// counts once (the member with ω_d > 0); the real eigenvalues of overdamped modes are paired
/// in order of magnitude (each such mode reports ω_d = 0 and the slower decay rate as σ).
/// `omega`: undamped ω_j (rad/s); `modal_damping`: C_m (n × n, symmetric).
std::vector<DampedMode> damped_modes(const VectorXd& omega, const MatrixXd& modal_damping);

/// The damping matrix in the mass-normalised modes Φ (free DOFs x modes): Φᵀ C Φ (symmetrised;
/// `c_free` over the free DOFs, empty for none) + diag(2 ζ_j ω_j) with ζ_j = DMPRAT + MDAMP(j).
MatrixXd project_modal_damping(const MatrixXd& phi, const SparseMatrix& c_free,
                               const AnalysisOptions& options, const VectorXd& omega);

}  // namespace impactfe
