// Placeholder until the substructuring driver lands.
#include "analysis/analyses.h"

namespace impactfe {

void run_substructure_generation(Structure&, const AnalysisRequest&, ResultsWriter&,
                                 const RunSettings&, AnalysisStatistics&, const std::string&) {
  throw NotImplementedError("substructure generation (KAN,7) is not implemented yet");
}

}  // namespace impactfe
