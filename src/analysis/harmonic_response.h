#pragma once
/// The harmonic response (ANTYPE,HARMIC) on matrices: the frequencies of the load steps
/// (HARFRQ + NSUBST + KBC) and the complex solutions of the full and the mode-superposition
/// methods. The driver (harmonic_analysis.cpp) assembles the matrices and writes the results.
#include <Eigen/Core>
#include <complex>
#include <vector>

#include "core/model.h"
#include "linalg/sparse.h"

namespace impactfe {

using VectorXcd = Eigen::VectorXcd;

/// One solution frequency: the load step (index into the analysis's steps), its substep, the
/// frequency in Hz and the load amplitude factor (1 when stepped, KBC,1; the substep's fraction
/// of the step, ramped from zero, when KBC,0).
struct HarmonicPoint {
  std::size_t step_index = 0;
  int substep = 1;
  double frequency = 0.0;
  double load_factor = 1.0;
};

/// The frequencies of each load step: NSUBST (default 1) evenly spaced in (FREQB, FREQE], the
/// last at FREQE; a single frequency (FREQB = FREQE) is solved NSUBST times as MAPDL does, once
/// here. InputError at the step's SOLVE when it has no HARFRQ.
std::vector<HarmonicPoint> harmonic_points(const std::vector<LoadStep>& steps);

/// The damping of the full method at angular frequency Ω: the matrix D of
/// (K − Ω² M + i D) u = F, D = Ω C + (g + 2ζ) K, with C the viscous damping (element dampers,
/// ALPHAD M, BETAD K), g the structural damping (DMPSTR) and ζ the constant damping ratio
/// (DMPRAT): MAPDL's full harmonic takes DMPRAT as the stiffness multiplier ζ/(π f) = 2ζ/Ω, so
/// Ω (2ζ/Ω) K = 2ζ K (Theory Reference, damping matrices).
/// Solves the full harmonic system on the free DOFs (all matrices n x n, full storage).
VectorXcd solve_full_harmonic(const SparseMatrix& k, const SparseMatrix& c, const SparseMatrix& m,
                              double omega, double structural_g, double damping_ratio,
                              const VectorXcd& f);

/// Mode superposition: (diag(ω_j²)(1 + i g) − Ω² I + i Ω C_q) q = Φᵀ F with mass-normalised
/// modes; `modal_c` the modal damping matrix (diagonal 2 ζ_j ω_j + α + β ω_j², plus the projected
/// element dampers). Returns the modal coordinates q.
VectorXcd solve_modal_harmonic(const Eigen::VectorXd& omega_modes, const Eigen::MatrixXd& modal_c,
                               double omega, double structural_g, const VectorXcd& f_modal);

}  // namespace impactfe
