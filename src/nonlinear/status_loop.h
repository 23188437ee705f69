#pragma once
/// The element status loop (spec §10.3 step 4; thesis §IV.B): after each equilibrium iteration
/// every status element (gap open/closed, slider sticking/sliding) re-evaluates its status at the
/// new iterate; a change makes the iteration unconverged. The chatter guard freezes an element
/// that changed `chatter_limit` times within one step, so that a gap bouncing between open and
/// closed cannot stall the step, and reports it.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "assembly/assembler.h"
#include "elements/element.h"

namespace impactfe {

/// Where a step is, for the messages: "load step 2 substep 5 (t = 0.0725)".
struct StepLabel {
  int load_step = 0;
  int substep = 0;
  double time = 0.0;
};

class StatusLoop {
 public:
  static constexpr int kDefaultChatterLimit = 4;

  /// `elements` and `assembler` (for gathering element displacements) outlive the loop.
  StatusLoop(const std::vector<std::unique_ptr<Element>>& elements, const Assembler& assembler,
             int chatter_limit = kDefaultChatterLimit);

  bool empty() const { return members_.empty(); }
  /// Starts a step: clears the per-step change counts.
  void begin_step();
  /// Updates every status element at iterate u (all active DOFs). Returns the number of
  /// elements whose status changed; an element reaching the chatter limit is frozen for the
  /// rest of the step and a warning names it.
  int update(const VectorXd& u, const StepLabel& where);
  /// The status the initial state u₀ gives every status element (a slider stretched past FSLIDE
  /// slips, a gap opens or closes), committed: updated until no status changes (at most
  /// chatter-limit passes), before the initial accelerations are computed. Returns the number
  /// of elements whose status changed.
  int settle(const VectorXd& u);
  /// Ends a step: unfreezes the elements frozen in it.
  void end_step();
  /// Accepts the converged step at u for every status element and every element with a
  /// material history (Element::has_history: plastic strains at u become the committed ones).
  void commit(const VectorXd& u);
  /// Returns every status and history element to its committed state (a step is restarted).
  void revert();
  /// True when some element carries a material history: its tangent changes with u even in
  /// small deflection, so Newton must re-form it.
  bool has_history() const { return has_history_; }

  /// True when some element reached the chatter limit in this step (automatic time stepping
  /// cuts the step instead of accepting it with a frozen status).
  bool chattered() const;
  /// Automatic time stepping reports the cut, not the freeze: no warning when freezing.
  void set_quiet_freeze(bool quiet) { quiet_freeze_ = quiet; }
  /// " 12(3x) 14(2x)": elements that changed status at least twice in this step.
  std::string chatter_report() const;
  /// Status changes since construction.
  int n_changes() const { return n_changes_; }

 private:
  const std::vector<std::unique_ptr<Element>>& elements_;
  const Assembler& assembler_;
  int chatter_limit_;
  std::vector<std::size_t> members_;    // indices of the elements that carry a status
  std::vector<std::size_t> committed_;  // ... that carry a status or a history
  bool has_history_ = false;
  std::map<std::size_t, int> flips_;  // element index -> status changes in this step
  int n_changes_ = 0;
  bool quiet_freeze_ = false;
  VectorXd ue_;  // scratch
};

}  // namespace impactfe
