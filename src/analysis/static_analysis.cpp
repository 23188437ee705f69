#include <fmt/format.h>

#include "analysis/analyses.h"
#include "analysis/direct_solution.h"
#include "results/output_selection.h"

namespace impactfe {

std::unique_ptr<DirectSolution> begin_direct_analysis(Structure& structure, ResultsWriter& writer,
                                                      const RunSettings& settings,
                                                      AnalysisStatistics& stats,
                                                      const std::vector<LoadStep>& known_steps,
                                                      bool count_points) {
  const AnalysisOptions& o = structure.options();
  const bool transient = o.type == AnalysisType::Transient;
  const char* scheme = o.integrator == IntegratorKind::Houbolt ? "Houbolt"
                       : o.integrator == IntegratorKind::HHT   ? "HHT-alpha"
                                                               : "Newmark";
  stats.description = transient ? fmt::format("full transient ({}{})", scheme,
                                              o.large_deflection ? ", large deflection" : "")
                                : "static";
  auto solution = std::make_unique<DirectSolution>(structure, writer, settings, stats, transient);
  // The load steps known now are planned once: the count of stored points fits the file's
  // time blocks to them, and the solution takes their plans when it reaches them.
  solution->look_ahead(known_steps);
  const long long expected_points = count_points ? solution->stored_points_at_most(known_steps) : 0;
  if (transient) {
    writer.begin_analysis(ResultsKind::Transient, stats.description, expected_points);
    writer.set_attribute("integrator", scheme);
  } else {
    writer.begin_analysis(ResultsKind::Static, "static analysis", expected_points);
  }
  solution->begin();
  return solution;
}

}  // namespace impactfe
