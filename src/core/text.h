#pragma once
/// Small text helpers shared by the deck reader, DOF labels and the results queries.
#include <string>
#include <string_view>

namespace impactfe {

/// ASCII upper case (APDL names and labels are case-insensitive).
std::string to_upper(std::string_view text);
/// ASCII lower case (macro file names on disk).
std::string to_lower(std::string_view text);

}  // namespace impactfe
