#pragma once
/// Houbolt stability table for the CLI command `impactfe houbolt-spectrum` (thesis Fig. 3-4).
#include <string>
#include <vector>

namespace impactfe {

/// CSV with header "dt_over_T,xi,spectral_radius": one row per (xi, dt/T) pair, xi outer, dt/T
/// inner, each the spectral radius of houbolt_amplification_matrix(dt/T, xi) (thesis eq. 3-11).
std::string houbolt_spectrum_csv(const std::vector<double>& dt_over_T,
                                 const std::vector<double>& xi);

/// n values of dt/T spaced evenly in log10 from lo to hi (both included; n >= 2), the default
/// grid of the spectrum command (Fig. 3-4 spans roughly 1e-3..1e3).
std::vector<double> log_grid(double lo, double hi, int n);

}  // namespace impactfe
