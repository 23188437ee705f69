#pragma once
/// POST26 variables as *GET and *VGET read them (APDL_SCRIPTING §B VARI, §C.13).
#include <vector>

#include "deck/post_support.h"

namespace impactfe::deck {

/// Values of variable n (1 = TIME) over the stored time points; fails for an undefined one.
std::vector<double> post26_values(DeckReader& r, const Command& c, int n);

/// EXTREM data of variable n within PRTIME: extremes (first occurrence on ties) and last value.
struct Extremes {
  double vmin = 0.0, tmin = 0.0, vmax = 0.0, tmax = 0.0, vlast = 0.0, tlast = 0.0;
};
Extremes post26_extremes(DeckReader& r, const Command& c, int n);

/// Value of variable n at time t, linear between stored points (clamped to the ends).
double post26_value_at(DeckReader& r, const Command& c, int n, double t);

}  // namespace impactfe::deck
