#pragma once
/// The constant-step time axis of the reduced / mode-superposition transients and the expansion
/// points (APDL_SUBSET §3.17, §3.18, §3.26); the substep count of a span shared with the full
/// drivers' schedule (time/time_schedule.h, which plans static and full transient load steps).
#include <cstddef>
#include <functional>
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

/// The computed points of a reduced / MSUP transient, generated on demand from one span per load
/// step (t_k = start + k Δt, the last point of an exact span at its TIME): memory does not grow
/// with the number of substeps. Point 0 is the initial state at t = 0.
class ReducedTimeAxis {
 public:
  struct Span {
    int n = 0;  // substeps
    bool exact = false;
    double start = 0.0;
    double end = 0.0;  // TIME of the load step (the last point when exact)
    int load_step = 1;
    int step_index = 0;  // index into the load-step list
  };
  ReducedTimeAxis() = default;
  ReducedTimeAxis(int first_load_step, std::vector<Span> spans, double dt);

  std::size_t size() const { return first_.empty() ? 0 : first_.back(); }
  bool empty() const { return size() == 0; }
  ReducedPoint operator[](std::size_t i) const;
  ReducedPoint front() const { return (*this)[0]; }
  ReducedPoint back() const { return (*this)[size() - 1]; }

  class Iterator {
   public:
    Iterator(const ReducedTimeAxis& axis, std::size_t i) : axis_(&axis), i_(i) {}
    ReducedPoint operator*() const { return (*axis_)[i_]; }
    Iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const Iterator& other) const { return i_ != other.i_; }

   private:
    const ReducedTimeAxis* axis_;
    std::size_t i_;
  };
  Iterator begin() const { return {*this, 0}; }
  Iterator end() const { return {*this, size()}; }

 private:
  int first_load_step_ = 1;
  std::vector<Span> spans_;
  std::vector<std::size_t> first_;  // first_[s]: index of span s's first point; back(): size
  double dt_ = 0.0;
};

/// Time axis of a reduced / MSUP transient (KAN=5 semantics, spec §3.17, §3.18): load step 1 is
/// the initial state at t = 0 (its TIME ignored); later steps advance with one constant Δt (the
/// DTIME of the first step that gives one, else the span of step 2 over its substeps) from the
/// previous TIME. `dt` receives Δt; `notes` receives what the run summary should say (a span
/// that is not a multiple of Δt, an ignored DTIME).
ReducedTimeAxis reduced_time_axis(const std::vector<LoadStep>& steps, double& dt,
                                  std::vector<std::string>& notes);

/// Stored time points selected by expansion requests (NUMEXP/NSTRES spacing in (t_begin, t_end],
/// each snapped to the nearest stored time; NUMEXP,ALL: every time in the range), ascending,
/// duplicates removed (spec §3.26). An end beyond the last time (or infinite) means the last.
std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests,
                                  const std::vector<double>& times);
/// The same over `count` ascending times given by `time_at` (a time axis not held in memory).
std::vector<int> expansion_points(const std::vector<ExpansionRequest>& requests, std::size_t count,
                                  const std::function<double(std::size_t)>& time_at);

}  // namespace impactfe
