#include <fmt/format.h>

#include "analysis/analyses.h"
#include "analysis/direct_solution.h"

namespace impactfe {

void run_static_analysis(Structure& structure, const AnalysisRequest& request,
                         ResultsWriter& writer, const RunSettings& settings,
                         AnalysisStatistics& stats) {
  stats.description = "static";
  writer.begin_analysis(ResultsKind::Static, "static analysis");
  DirectSolution solution(structure, writer, settings, stats);
  solution.run(request.load_steps, /*transient=*/false);
}

void run_full_transient(Structure& structure, const AnalysisRequest& request, ResultsWriter& writer,
                        const RunSettings& settings, AnalysisStatistics& stats) {
  const AnalysisOptions& o = structure.options();
  const char* scheme = o.integrator == IntegratorKind::Houbolt ? "Houbolt"
                       : o.integrator == IntegratorKind::HHT   ? "HHT-alpha"
                                                               : "Newmark";
  stats.description =
      fmt::format("full transient ({}{})", scheme, o.large_deflection ? ", large deflection" : "");
  writer.begin_analysis(ResultsKind::Transient, stats.description);
  writer.set_attribute("integrator", scheme);
  DirectSolution solution(structure, writer, settings, stats);
  solution.run(request.load_steps, /*transient=*/true);
}

}  // namespace impactfe
