#include <fmt/format.h>

#include "analysis/analyses.h"
#include "analysis/direct_solution.h"
#include "results/output_selection.h"
#include "time/time_axis.h"

namespace impactfe {

long long stored_points_at_most(const std::vector<LoadStep>& steps, bool transient) {
  long long points = transient ? 1 : 0;
  double t_end = 0.0;
  try {
    for (const LoadStep& step : steps) {
      const LoadStepTiming t = load_step_timing(step, t_end, transient);
      points += stored_substeps_at_most(step.output, t.n_substeps);
      t_end = t.t_end;
    }
  } catch (const std::exception&) {
    return 0;
  }
  return points;
}

std::unique_ptr<DirectSolution> begin_direct_analysis(Structure& structure, ResultsWriter& writer,
                                                      const RunSettings& settings,
                                                      AnalysisStatistics& stats,
                                                      long long expected_points) {
  const AnalysisOptions& o = structure.options();
  const bool transient = o.type == AnalysisType::Transient;
  if (transient) {
    const char* scheme = o.integrator == IntegratorKind::Houbolt ? "Houbolt"
                         : o.integrator == IntegratorKind::HHT   ? "HHT-alpha"
                                                                 : "Newmark";
    stats.description = fmt::format("full transient ({}{})", scheme,
                                    o.large_deflection ? ", large deflection" : "");
    writer.begin_analysis(ResultsKind::Transient, stats.description, expected_points);
    writer.set_attribute("integrator", scheme);
  } else {
    stats.description = "static";
    writer.begin_analysis(ResultsKind::Static, "static analysis", expected_points);
  }
  auto solution = std::make_unique<DirectSolution>(structure, writer, settings, stats);
  solution->begin(transient);
  return solution;
}

}  // namespace impactfe
