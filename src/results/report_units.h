#pragma once
/// Axis units of the report from the deck's /UNITS label (the results file's `units`
/// attribute). As in MAPDL, /UNITS converts nothing: the labels only say which consistent
/// system the deck's numbers are in. An unknown or absent label gives no units.
#include <optional>
#include <string>

namespace impactfe {

struct UnitLabels {
  std::string time, length, velocity, acceleration, force, stress, energy;
};

/// The units of SI, MKS, uMKS, CGS, MPA, BFT, BIN; nullopt for USER, blank or anything else.
std::optional<UnitLabels> unit_labels(const std::string& system);

/// The unit of an axis quantity ("Time", "Displacement UX", "Stress", "Gap force", "Energy",
/// ...) by its first word; "" when it has none here (a status, a count).
std::string unit_of_quantity(const UnitLabels& units, const std::string& quantity);

}  // namespace impactfe
