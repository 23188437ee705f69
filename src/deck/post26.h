#pragma once
/// POST26 variables as *GET and *VGET read them (APDL_SCRIPTING §B VARI, §C.13).
#include <vector>

#include "deck/post_support.h"

namespace impactfe::deck {

/// Values of variable n (1 = TIME) over the stored time points; fails for an undefined one.
/// A complex variable (harmonic) gives its real part, or its amplitude under PRCPLX,1.
std::vector<double> post26_values(DeckReader& r, const Command& c, int n);
/// The second part of a complex variable: imaginary part, or phase angle (degrees) under
/// PRCPLX,1; zeros for a real variable.
std::vector<double> post26_second_part(DeckReader& r, const Command& c, int n);

/// EXTREM data of variable n within PRTIME: extremes (first occurrence on ties) and last value.
struct Extremes {
  double vmin = 0.0, tmin = 0.0, vmax = 0.0, tmax = 0.0, vlast = 0.0, tlast = 0.0;
};
Extremes post26_extremes(DeckReader& r, const Command& c, int n);

/// Value of variable n at time t, linear between stored points (clamped to the ends);
/// `second_part`: of the imaginary part or phase (*GET ITIME).
double post26_value_at(DeckReader& r, const Command& c, int n, double t, bool second_part = false);

}  // namespace impactfe::deck
