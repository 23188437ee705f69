#pragma once
/// What watches a static or full transient run from outside the equations: after every
/// accepted substep the progress line, the stored results point (OUTRES) and the restart point
/// (RESCONTROL); after every load step the contact summary; at the end the energy balance's
/// summary and warning. Each observer reads the run's parts (RunParts) and writes its own output.
#include <memory>
#include <string>
#include <vector>

#include "analysis/discretisation.h"
#include "analysis/energy_balance.h"
#include "analysis/motion_state.h"
#include "analysis/run_statistics.h"
#include "results/output_selection.h"
#include "results/results_file.h"
#include "time/time_integrator.h"
#include "time/time_schedule.h"

namespace impactfe {

/// The parts of a run the observers read (owned by the driver; the discretisation and the
/// integrator are replaced by a renumbering or a new analysis, so they are held by pointer).
struct RunParts {
  const Structure& structure;
  const std::unique_ptr<Discretisation>& disc;
  const MotionState& state;
  const EnergyBalance& energy;
  const std::unique_ptr<TimeIntegrator>& integrator;
  const TimeSchedule& schedule;
  const bool& integrator_running;  // the integrator's history is the state's (dynamic steps)
  AnalysisStatistics& stats;
};

/// An accepted substep of load step `step` (ramping from `previous`).
struct AcceptedSubstep {
  const LoadStep& step;
  const LoadStep* previous;
  const Substep& substep;
  int iterations;
  int status_changes;
  bool dynamic;   // a transient step with time integration
  bool last;      // the last substep of the load step
  bool stopping;  // the run stops after it on request (core/interruption.h)
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void substep_accepted(const AcceptedSubstep&) {}
  virtual void load_step_solved(const LoadStep&) {}
  virtual void run_finished() {}
};

/// Stores results points in the results file: the OUTRES selection of a substep (the nominal
/// grid's points as with constant steps; between them under AUTOTS the items written at every
/// substep), and the initial state of a transient.
class ResultStorage final : public RunObserver {
 public:
  ResultStorage(const RunParts& run, ResultsWriter& writer) : run_(run), writer_(writer) {}
  void substep_accepted(const AcceptedSubstep& s) override;
  /// One point at `time` with the items of `selection`.
  void store(double time, int load_step, int substep, bool dynamic,
             const OutputSelection& selection);

 private:
  const RunParts& run_;
  ResultsWriter& writer_;
};

/// The progress observer of the program (the CLI's progress line), told after every substep.
class ProgressReport final : public RunObserver {
 public:
  ProgressReport(const RunParts& run, ProgressObserver* progress)
      : run_(run), progress_(progress) {}
  void substep_accepted(const AcceptedSubstep& s) override;

 private:
  const RunParts& run_;
  ProgressObserver* progress_;
};

/// Writes the restart points RESCONTROL asks for into <jobname>.rst.h5, and the point of the
/// substep after which the run stops on request (whatever RESCONTROL says).
class RestartRecorder final : public RunObserver {
 public:
  RestartRecorder(const RunParts& run, std::string path) : run_(run), path_(std::move(path)) {}
  void substep_accepted(const AcceptedSubstep& s) override;

 private:
  const RunParts& run_;
  std::string path_;
};

/// Logs the contact summary (CONTSTAT-like) at the end of every load step.
class ContactSummaryLog final : public RunObserver {
 public:
  explicit ContactSummaryLog(const RunParts& run) : run_(run) {}
  void load_step_solved(const LoadStep& step) override;

 private:
  const RunParts& run_;
};

/// The energy balance of a transient: after every accepted step the check
/// (EnergyBalance::creation past its bound for kStepsOver steps in a row: a SolutionError naming
/// the step, the term and the likely cause,
/// after the step is stored; a warning once when `accept_error`), at the end the run summary's
/// line and the warning when it does not balance.
class EnergyReport final : public RunObserver {
 public:
  EnergyReport(const RunParts& run, bool accept_error) : run_(run), accept_error_(accept_error) {}
  void substep_accepted(const AcceptedSubstep& s) override;
  void run_finished() override;
  /// Accepted steps in a row past the bound before the run stops: the start of a multi-step
  /// integrator (Houbolt's first velocities) may pass it for a step or two and come back, an
  /// unstable step or a contact that creates energy stays past it.
  static constexpr int kStepsOver = 3;

 private:
  const RunParts& run_;
  bool accept_error_;
  int steps_over_ = 0;
  bool warned_ = false;
};

}  // namespace impactfe
