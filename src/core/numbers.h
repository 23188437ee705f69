#pragma once
/// Constants shared by the whole program: one definition each (a file-local copy in every file
/// that needs it collides with the others where files are compiled together, CMake's unity build).
#include <limits>

namespace impactfe {

/// "No value": result rows never written, items an element does not have.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace impactfe
