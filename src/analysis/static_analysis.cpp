#include <fmt/format.h>

#include "analysis/analyses.h"
#include "analysis/direct_solution.h"

namespace impactfe {

std::unique_ptr<DirectSolution> begin_direct_analysis(Structure& structure, ResultsWriter& writer,
                                                      const RunSettings& settings,
                                                      AnalysisStatistics& stats) {
  const AnalysisOptions& o = structure.options();
  const bool transient = o.type == AnalysisType::Transient;
  if (transient) {
    const char* scheme = o.integrator == IntegratorKind::Houbolt ? "Houbolt"
                         : o.integrator == IntegratorKind::HHT   ? "HHT-alpha"
                                                                 : "Newmark";
    stats.description = fmt::format("full transient ({}{})", scheme,
                                    o.large_deflection ? ", large deflection" : "");
    writer.begin_analysis(ResultsKind::Transient, stats.description);
    writer.set_attribute("integrator", scheme);
  } else {
    stats.description = "static";
    writer.begin_analysis(ResultsKind::Static, "static analysis");
  }
  auto solution = std::make_unique<DirectSolution>(structure, writer, settings, stats);
  solution->begin(transient);
  return solution;
}

}  // namespace impactfe
