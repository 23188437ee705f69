#pragma once
/// Deck-reading state of the solution commands that is not yet part of the Job: the analysis
/// being defined (4x: KAN, the LWRITE load steps, the AFWRITE freeze, the /STRESS block; modern:
/// the open ANTYPE, the LSWRITE files, the expansion pass being set up) and the MDAMP pointer.
/// Written by the solution handlers; /CLEAR replaces it with a new one.
#include <cstddef>
#include <map>
#include <optional>
#include <vector>

#include "core/model.h"

namespace impactfe::deck {

struct SolutionState {
  // 4x analysis definition (APDL_SUBSET §3).
  int kan = 0;
  std::vector<LoadStep> load_steps_4x;  // LWRITE
  std::optional<Job::Step> frozen;      // AFWRITE
  bool exec_armed = false;              // /EXEC
  // 4x /STRESS block: the expansion requests and the NSTRES spacing memory (§3.26).
  std::vector<ExpansionRequest> stress_requests;
  int stress_count = 1;
  double stress_t_prev = 0.0;
  SourceLocation stress_where;

  // Modern analysis definition.
  std::optional<std::size_t> open_analysis;  // index in job.steps
  /// FINISH left /SOLU with an analysis open: that analysis is over, and the next SOLVE that
  /// is not a restart (ANTYPE,,REST) or an expansion pass begins a new analysis, which
  /// supersedes the earlier ones in the results file (SolutionHost::begin_new_analysis).
  bool finished_analysis = false;
  std::map<int, LoadStep> lswrite_steps;
  bool expass = false;
  ExpansionPassRequest expansion;
  std::optional<SuperelementExpansionSource> seexp;  // SEEXP of the current expansion pass
  std::optional<double> last_solved_time;            // end time of the last solved load step

  int mdamp_next = 1;  // MDAMP: the next mode's position

  // Implicit creep (docs/materials.md, "Creep"): RATE,ON|OFF (default OFF) and TOFF, the offset
  // from the temperature scale to absolute zero. They are read when a SOLVE / LSSOLVE solves:
  // the creep clock of the model solved (Model::creep_clock) takes them then.
  bool creep_rate = false;          // RATE
  double temperature_offset = 0.0;  // TOFF
  /// STEF: the Stefan-Boltzmann constant of radiation (MAPDL's default 0.119E-10, in Btu/hr,
  /// in, °R). Kept for *GET and the archive; nothing radiates here (radiation elements, RDSF
  /// and RADOPT are refused where given), so it acts on no result.
  double stefan_boltzmann = 0.119e-10;
};

}  // namespace impactfe::deck
