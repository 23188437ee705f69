// Superelement generation and expansion drivers (spec §10.6). Generation (KAN,7 / ANTYPE,SUBSTR)
// condenses the substructure, writes <Sename>.sub.h5 (default <jobname>) next to the results
// file and records a summary in the results file; expansion (EXPASS + SEEXP) expands a use pass.
#include <fmt/format.h>

#include <filesystem>

#include "analysis/analyses.h"
#include "analysis/superelement_expansion.h"
#include "analysis/superelement_generation.h"
#include "core/log.h"

namespace impactfe {

void run_substructure_generation(Structure& structure, const AnalysisRequest& request,
                                 ResultsWriter& writer, const RunSettings& settings,
                                 AnalysisStatistics& stats, const std::string& jobname) {
  stats.description = "substructure generation (Guyan)";
  writer.begin_analysis(ResultsKind::Substructure, stats.description);
  const std::string name = structure.options().superelement_name.empty()
                               ? jobname
                               : structure.options().superelement_name;
  GenerationSummary summary;
  const SuperelementData se = generate_superelement(structure, request, name, summary);

  // The file goes beside the results file (the working directory of the run).
  const std::filesystem::path dir = std::filesystem::path(writer.path()).parent_path();
  // SEOPT Sename names the file (default: the jobname), so SE,Sename finds it.
  const std::string path = (dir / (name + ".sub.h5")).string();
  write_superelement(path, se);

  stats.n_dofs = summary.n_masters;
  stats.n_load_steps = static_cast<int>(request.load_steps.size());
  stats.n_analyses = summary.factorizations;
  stats.n_factorizations = summary.factorizations;
  stats.notes.push_back(fmt::format(
      "superelement {} -> {}: {} masters, {} slaves condensed, {} constrained; matrices {}", name,
      path, summary.n_masters, summary.n_slaves, summary.n_constrained,
      se.matrices == 1   ? "K"
      : se.matrices == 2 ? "K, M"
                         : "K, M, C"));
  stats.notes.push_back(fmt::format(
      "superelement mass per direction X/Y/Z: total {:.6g} / {:.6g} / {:.6g}, carried by "
      "masters {:.6g} / {:.6g} / {:.6g}",
      summary.total_mass[0], summary.total_mass[1], summary.total_mass[2], summary.reduced_mass[0],
      summary.reduced_mass[1], summary.reduced_mass[2]));
  for (const auto& note : stats.notes) Log::info("{}", note);

  writer.set_attribute("superelement_name", name);
  writer.set_attribute("superelement_file", path);
  writer.set_count("n_masters", static_cast<long long>(summary.n_masters));
  writer.set_count("n_slaves", static_cast<long long>(summary.n_slaves));
  writer.set_count("n_constrained", static_cast<long long>(summary.n_constrained));
  writer.set_count("n_load_vectors", static_cast<long long>(request.load_steps.size()));
  writer.set_count("matrices", static_cast<long long>(se.matrices));
  writer.set_attribute("generation_seconds", summary.seconds);
  const char* axes[3] = {"x", "y", "z"};
  for (int d = 0; d < 3; ++d) {
    writer.set_attribute(fmt::format("total_mass_{}", axes[d]), summary.total_mass[d]);
    writer.set_attribute(fmt::format("master_mass_{}", axes[d]), summary.reduced_mass[d]);
  }
}

void run_superelement_expansion(const ExpansionPassRequest& request, ResultsWriter& writer,
                                AnalysisStatistics& stats) {
  const SuperelementExpansionSource& source = *request.superelement;
  const std::string sub_file = superelement_file_of(source);
  const std::string use_file = use_results_file_of(source);
  stats.description = fmt::format("superelement {} expansion", source.name);
  const SuperelementExpansion expansion(read_superelement(sub_file, source.where));
  const ResultsReader use(use_file);
  stats.n_stored = expand_superelement_use_pass(expansion, use, request, writer);
  stats.n_dofs = expansion.dofs().n_free();
  writer.set_attribute("superelement_file", sub_file);
  stats.notes.push_back(
      fmt::format("expanded {} solutions of {} with {}", stats.n_stored, use_file, sub_file));
}

}  // namespace impactfe
