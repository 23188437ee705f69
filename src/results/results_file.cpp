// The free functions of results_file.h shared by the writer and the reader.
#include "results/results_file.h"

#include <algorithm>
#include <cmath>

namespace impactfe {

const char* results_kind_name(ResultsKind kind) {
  switch (kind) {
    case ResultsKind::Static:
      return "static";
    case ResultsKind::Modal:
      return "modal";
    case ResultsKind::Transient:
      return "transient";
    case ResultsKind::ReducedTransient:
      return "reduced_transient";
    case ResultsKind::Expansion:
      return "expansion";
    case ResultsKind::Substructure:
      return "substructure";
    case ResultsKind::Harmonic:
      return "harmonic";
    case ResultsKind::Spectrum:
      return "spectrum";
  }
  return "unknown";
}

bool same_time(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace impactfe
