// Expansion ("stress") pass of a reduced / mode-superposition transient (spec §10.5, §3.26;
// APDL_SCRIPTING §E.11): full displacements from the generalized histories (Guyan: slaves with
// the static correction K_ss⁻¹ f_s), V and A by the same transformation, element results and
// reactions at the requested times, snapped to computed steps, duplicates removed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "analysis/analyses.h"
#include "analysis/reduced_run.h"
#include "core/log.h"

namespace impactfe {

void run_expansion_pass(const ExpansionPassRequest& request, ReducedSolutionState* base,
                        ResultsWriter& writer, const RunSettings&, AnalysisStatistics& stats) {
  auto* state = dynamic_cast<ReducedRunState*>(base);
  if (!state || state->points.empty() || !state->history)
    throw InputError(request.where,
                     "expansion pass: no reduced or mode-superposition transient ran before it");
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  stats.description = "expansion pass";
  writer.begin_analysis(ResultsKind::Expansion,
                        fmt::format("expansion of the {} transient",
                                    state->method == "msup" ? "mode-superposition" : "reduced"));
  std::vector<ExpansionRequest> requests = request.requests;
  if (requests.empty()) requests.push_back({1, 0.0, state->points.back().time, false});
  const std::vector<int> selected = expansion_points(
      requests, state->points.size(), [&](std::size_t i) { return state->points[i].time; });

  const DofMap& dofs = *state->dofs;
  const int nf = dofs.n_free();
  const Structure& structure = *state->structure;
  const bool correction = request.static_correction && state->guyan != nullptr;
  for (int index : selected) {
    const ReducedPoint p = state->points[static_cast<std::size_t>(index)];
    const GeneralizedHistory::Record h = state->history->at(static_cast<std::size_t>(index));
    const VectorXd f = state->external_force(p);
    const VectorXd f_free = f.head(nf);
    const VectorXd u = state->to_active(state->expand(h.q, correction ? &f_free : nullptr));
    const VectorXd v = state->to_active(state->expand(h.v, nullptr));
    const VectorXd a = state->to_active(state->expand(h.a, nullptr));
    // Reactions at the constrained DOFs: K u + C v + M a − f (gap forces act on free DOFs).
    VectorXd f_int, f_damp;
    state->assembler->assemble({}, u, v, Assembler::Output{nullptr, &f_int, &f_damp});
    VectorXd reactions = f_int - f + state->mass_all * a;
    if (state->assembler->has_damping()) reactions += f_damp;
    TimePoint tp;
    tp.time = p.time;
    tp.load_step = p.load_step;
    tp.substep = p.substep;
    tp.displacement = structure.nodal_table(dofs, u);
    tp.velocity = structure.nodal_table(dofs, v);
    tp.acceleration = structure.nodal_table(dofs, a);
    tp.reaction = structure.reaction_table(dofs, reactions);
    tp.element_results = structure.element_results(*state->assembler, u, v);
    tp.gap_forces = h.gap_forces;
    tp.energy["kinetic"] = 0.5 * v.dot(state->mass_all * v);
    writer.append(std::move(tp));
    ++stats.n_stored;
  }
  const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
  stats.n_dofs = nf;
  writer.set_count("expanded_solutions", static_cast<long long>(selected.size()));
  writer.set_attribute("expansion_seconds", seconds);
  stats.notes.push_back(fmt::format("expansion: {} solutions ({} requested groups) in {:.3g} s",
                                    selected.size(), requests.size(), seconds));
}

}  // namespace impactfe
