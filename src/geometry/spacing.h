#pragma once
/// Node spacing along a line (APDL_MODELING §4.1; FILL, APDL_SUBSET §3.8): division lengths in
/// geometric progression.
#include <vector>

namespace impactfe::geometry {

/// Positions 0 = f_0 < f_1 < ... < f_n = 1 of the ends of n divisions. SPACE > 0: ratio of the
/// last division to the first (h_i = h_1 r^(i−1), r = SPACE^(1/(n−1))); SPACE < 0: |SPACE| is the
/// ratio of the middle divisions to the end ones, the same progression on each half; 0 or 1:
/// uniform.
std::vector<double> division_fractions(int n, double space);

}  // namespace impactfe::geometry
