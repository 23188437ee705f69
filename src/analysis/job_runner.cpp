#include "analysis/job_runner.h"

#include <chrono>

#include "analysis/analyses.h"
#include "core/log.h"

namespace impactfe {

namespace {

void run_analysis(const Job::Step& step, const std::string& jobname, const RunSettings& settings,
                  ResultsWriter& writer, AnalysisStatistics& stats,
                  std::unique_ptr<ReducedSolutionState>& reduced_state) {
  const AnalysisRequest& request = *step.analysis;
  Structure structure(step.model_snapshot, request.options, settings, &request.load_steps);
  switch (request.options.type) {
    case AnalysisType::Static:
      run_static_analysis(structure, request, writer, settings, stats);
      break;
    case AnalysisType::Modal:
      run_modal_analysis(structure, request, writer, settings, stats);
      break;
    case AnalysisType::Transient:
      switch (request.options.method) {
        case TransientMethod::Full:
          run_full_transient(structure, request, writer, settings, stats);
          break;
        case TransientMethod::Reduced:
          run_reduced_transient(structure, request, writer, settings, stats, reduced_state);
          break;
        case TransientMethod::ModeSuperposition:
          run_msup_transient(structure, request, writer, settings, stats, reduced_state);
          break;
      }
      break;
    case AnalysisType::Substructure:
      run_substructure_generation(structure, request, writer, settings, stats, jobname);
      break;
  }
}

}  // namespace

void run_job(const Job& job, const std::string& jobname, const RunSettings& settings,
             ResultsWriter& writer, RunStatistics& stats) {
  std::unique_ptr<ReducedSolutionState> reduced_state;
  for (const Job::Step& step : job.steps) {
    stats.analyses.emplace_back();
    AnalysisStatistics& current = stats.analyses.back();
    const auto start = std::chrono::steady_clock::now();
    try {
      if (step.analysis) {
        run_analysis(step, jobname, settings, writer, current, reduced_state);
      } else if (step.expansion) {
        current.description = "expansion pass";
        run_expansion_pass(*step.expansion, reduced_state.get(), writer, settings, current);
      }
    } catch (const std::exception& e) {
      current.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      try {
        writer.end_analysis(std::string("failed: ") + e.what());
      } catch (...) {
        // No analysis group was opened; nothing to mark.
      }
      throw;
    }
    current.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writer.set_attribute("wall_seconds", current.wall_seconds);
    writer.set_attribute("factorizations", static_cast<double>(current.n_factorizations));
    if (current.factor_nonzeros > 0) {  // linear solver figures (docs/results_file.md)
      writer.set_attribute("solves", static_cast<double>(current.n_solves));
      writer.set_attribute("analyze_seconds", current.analyze_seconds);
      writer.set_attribute("factorize_seconds", current.factorize_seconds);
      writer.set_attribute("solve_seconds", current.solve_seconds);
      writer.set_attribute("matrix_nonzeros", static_cast<double>(current.matrix_nonzeros));
      writer.set_attribute("factor_nonzeros", static_cast<double>(current.factor_nonzeros));
      writer.set_attribute("factor_bytes", static_cast<double>(current.factor_bytes));
    }
    writer.end_analysis("complete");
  }
}

}  // namespace impactfe
