#pragma once
/// The numerics of a single-point response spectrum analysis (MAPDL Theory Reference, spectrum
/// analysis chapter): the spectrum value of a mode read from the input curves, and the mode
/// combination methods that turn the modal responses into one (SRSS, CQC, GRP, DSUM, NRLSUM).
/// Pure functions of their arguments; the driver is spectrum_analysis.cpp.
#include <Eigen/Core>

#include <vector>

namespace impactfe {

/// One response spectrum curve: spectrum values over ascending frequencies (Hz) at one damping
/// ratio (FREQ + SV).
struct SpectrumCurve {
  double damping = 0.0;
  std::vector<double> values;  // one per frequency of the table
};

/// The spectrum table of SPOPT,SPRS: the frequencies (FREQ) and the curves (SV), ascending in
/// damping. `linear`: SVTYP KeyInterp ON (else logarithmic, the default).
struct SpectrumTable {
  std::vector<double> frequencies;
  std::vector<SpectrumCurve> curves;
  bool linear = false;
};

/// The spectrum value at frequency f (Hz) and damping ratio zeta: interpolated between the table
/// frequencies, then between the two curves that bracket zeta, log-log by default (linear with
/// KeyInterp ON); beyond the ends the extreme value is used (SV command notes).
double spectrum_value(const SpectrumTable& table, double f, double zeta);

enum class CombinationMethod { SRSS, CQC, GRP, DSUM, NRLSUM };

/// The mode correlation coefficients ε_ij of the double-sum methods (Theory Reference,
/// "Combination of Modes"): CQC (Der Kiureghian), GRP (closely spaced groups: ε = 1 within a
/// group whose frequencies stay within 10 % of its first), DSUM (Rosenblueth, with the
/// earthquake duration td), SRSS (identity). `omega`: rad/s, `zeta`: effective damping ratios.
Eigen::MatrixXd mode_correlation(CombinationMethod method, const Eigen::VectorXd& omega,
                                 const Eigen::VectorXd& zeta, double duration);

/// Combines modal responses: rows of `responses` are the modes (only the significant ones),
/// columns the response quantities. R = sqrt(|Σ_i Σ_j ε_ij R_i R_j|) (with |R_i R_j| for GRP and
/// DSUM), NRLSUM: |R_max| + sqrt(Σ of the others' squares). NaN columns stay NaN.
Eigen::VectorXd combine_modes(CombinationMethod method, const Eigen::MatrixXd& responses,
                              const Eigen::VectorXd& omega, const Eigen::VectorXd& zeta,
                              double duration);

}  // namespace impactfe
