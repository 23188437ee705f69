// Placeholders until the reduced transient, MSUP, expansion and substructuring drivers land.
#include "analysis/analyses.h"

namespace impactfe {

void run_reduced_transient(Structure&, const AnalysisRequest&, ResultsWriter&, const RunSettings&,
                           AnalysisStatistics&, std::unique_ptr<ReducedSolutionState>&) {
  throw NotImplementedError(
      "reduced transient analysis (KAN,5 / TRNOPT,REDUC) is not implemented yet");
}
void run_msup_transient(Structure&, const AnalysisRequest&, ResultsWriter&, const RunSettings&,
                        AnalysisStatistics&, std::unique_ptr<ReducedSolutionState>&) {
  throw NotImplementedError("mode-superposition transient (TRNOPT,MSUP) is not implemented yet");
}
void run_expansion_pass(const ExpansionPassRequest&, ReducedSolutionState*, ResultsWriter&,
                        const RunSettings&, AnalysisStatistics&) {
  throw NotImplementedError("expansion pass is not implemented yet");
}

}  // namespace impactfe
