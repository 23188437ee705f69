#include "analysis/job_runner.h"

#include <chrono>

#include "analysis/analyses.h"
#include "analysis/superelement_expansion.h"
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

Model results_model(const Job& job) {
  for (const Job::Step& step : job.steps) {
    if (!step.expansion || !step.expansion->superelement) continue;
    const SuperelementExpansionSource& source = *step.expansion->superelement;
    if (job.steps.size() != 1)
      throw InputError(step.expansion->where,
                       "a superelement expansion pass (EXPASS + SEEXP) must be the only solution "
                       "of its job (MAPDL runs it as a job of its own: /CLEAR, /FILNAME,Sename)");
    const SuperelementData data = read_superelement(superelement_file_of(source), source.where);
    bool lumped = false, sstif = false;
    Model model = deserialize_generation_model(data.model_text, lumped, sstif);
    model.title = data.title;
    model.jobname = job.model.jobname;
    return model;
  }
  return job.model;
}

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
      } else if (step.expansion && step.expansion->superelement) {
        run_superelement_expansion(*step.expansion, writer, current);
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
    writer.end_analysis("complete");
  }
}

}  // namespace impactfe
