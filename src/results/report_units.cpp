// Axis units of the report (report_units.h). The systems are MAPDL's /UNITS labels; force,
// stress and energy follow from the base units of each (MPA: mm, t, s: N, MPa, mJ; uMKS: μm,
// kg, s: μN, MPa, pJ; BIN: in, lbf s²/in, s: lbf, psi, in·lbf).
#include "results/report_units.h"

#include <map>

namespace impactfe {

std::optional<UnitLabels> unit_labels(const std::string& system) {
  static const std::map<std::string, UnitLabels> systems = {
      {"SI", {"s", "m", "m/s", "m/s²", "N", "Pa", "J"}},
      {"MKS", {"s", "m", "m/s", "m/s²", "N", "Pa", "J"}},
      {"UMKS", {"s", "μm", "μm/s", "μm/s²", "μN", "MPa", "pJ"}},
      {"CGS", {"s", "cm", "cm/s", "cm/s²", "dyn", "dyn/cm²", "erg"}},
      {"MPA", {"s", "mm", "mm/s", "mm/s²", "N", "MPa", "mJ"}},
      {"BFT", {"s", "ft", "ft/s", "ft/s²", "lbf", "lbf/ft²", "ft·lbf"}},
      {"BIN", {"s", "in", "in/s", "in/s²", "lbf", "psi", "in·lbf"}},
  };
  std::string key;
  for (char c : system) key += static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  const auto it = systems.find(key);
  if (it == systems.end()) return std::nullopt;
  return it->second;
}

std::string unit_of_quantity(const UnitLabels& units, const std::string& quantity) {
  const std::string first = quantity.substr(0, quantity.find(' '));
  if (first == "Time") return units.time;
  if (first == "Displacement") return units.length;
  if (first == "Velocity") return units.velocity;
  if (first == "Acceleration") return units.acceleration;
  if (first == "Energy" || first == "SENE") return units.energy;
  // Stress items: SX .. SEQV, SAXL, SEPL, SEQV_TOP, ...; not STAT, SLIDE, STRETCH, the strain
  // energy SENE or the ratio SRAT.
  if (first == "Stress" || (first.size() >= 2 && first[0] == 'S' && first != "STAT" &&
                            first != "SLIDE" && first != "STRETCH" && first != "SRAT"))
    return units.stress;
  if (first == "FORC" || first == "FN" || first == "FT" || first == "Gap" || first == "Contact")
    return units.force;
  return "";
}

}  // namespace impactfe
