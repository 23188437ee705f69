#pragma once
/// The constant-step time axis of the reduced / mode-superposition transients and the expansion
/// points (APDL_SUBSET §3.17, §3.18, §3.26); the substep count of a span shared with the full
/// drivers' schedule (time/time_schedule.h, which plans static and full transient load steps).
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// More substeps than this in one load step is refused as absurd input (a DELTIM far below the
/// span, or an overflowing count), before anything is attempted.
inline constexpr long kMaxSubstepsPerLoadStep = 100'000'000;

/// Number of constant steps of size dt in `span` (nearest integer, at least 1). Throws
/// InputError at the step's command when dt <= 0 or the count exceeds kMaxSubstepsPerLoadStep.
int substep_count(const LoadStep& step, double span, double dt);

/// One load step of a full analysis: substep k (1-based) ends at t_start + k h (planned by
/// TimeSchedule, time/time_schedule.h).
struct LoadStepTiming {
  double t_start = 0.0;
  double t_end = 0.0;
  int n_substeps = 1;
  double h = 0.0;
};

/// One computed time point of a reduced / mode-superposition transient.
struct ReducedPoint {
  double time = 0.0;
  int load_step = 1;
  int substep = 1;
  int step_index = 0;     // index into the load-step list
  double fraction = 1.0;  // position within the load step (KBC interpolation)
};

/// Time axis of a reduced / MSUP transient (KAN=5 semantics, spec §3.17, §3.18): load step 1 is
/// the initial state at t = 0 (its TIME ignored); later steps advance with one constant Δt (the
/// DTIME of the first step that gives one, else the span of step 2 over its substeps) from the
/// previous TIME. `dt` receives Δt; `notes` receives what the run summary should say (a span
/// that is not a multiple of Δt, an ignored DTIME). The run keeps `bytes_per_point` for every
/// point (its state history, for the expansion pass): a time axis whose points and history do not
/// fit in the memory the run may take is refused before anything is allocated
/// (MemoryLimitError, saying how many steps would fit).
std::vector<ReducedPoint> reduced_time_axis(const std::vector<LoadStep>& steps, double& dt,
                                            std::vector<std::string>& notes,
                                            double bytes_per_point = 0.0);

/// Stored time points selected by expansion requests (NUMEXP/NSTRES spacing in (t_begin, t_end],
/// each snapped to the nearest stored time; NUMEXP,ALL: every time in the range), ascending,
/// duplicates removed (spec §3.26). An end beyond the last time (or infinite) means the last.
std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests,
                                  const std::vector<double>& times);

}  // namespace impactfe
