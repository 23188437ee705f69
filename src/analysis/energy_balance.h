#pragma once
/// Work and energy bookkeeping of a static or transient run on all DOFs: external work, internal
/// (strain) work, the work done on status elements (gaps: energy stored in or dissipated by the
/// contact springs), damping dissipation, each by the trapezoidal rule over the converged steps;
/// the plastic work ∫σ:dε_p dV the elements with plasticity accumulate in their committed history
/// (also trapezoidal per integration point); kinetic energy from M v. The remainder external −
/// kinetic − strain − gap − damping − plastic is the time integrator's numerical dissipation
/// (Houbolt damps high modes; Bathe §9.4) when positive, and energy created by the integration
/// when negative. Energy is a check, not only a report: creation() measures, after every
/// accepted step, the energy created by the integration (a negative remainder) and by the
/// gap/contact elements (a negative gap work: they gave back more than they took) against the
/// energy put in.
#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assembly/assembler.h"
#include "elements/element.h"

namespace impactfe {

class EnergyBalance {
 public:
  explicit EnergyBalance(const std::vector<std::unique_ptr<Element>>& elements);

  /// Forces at the start and the end of one converged step (over all active DOFs).
  struct StepForces {
    const VectorXd& external_old;
    const VectorXd& external_new;
    const VectorXd& internal_old;
    const VectorXd& internal_new;
    const VectorXd& damping_old;
    const VectorXd& damping_new;
  };
  /// Adds the work of a converged step from u_old to u_new (same DOF numbering).
  void add_step(const Assembler& assembler, const VectorXd& u_old, const VectorXd& u_new,
                const StepForces& f);

  /// Work of the support reactions on prescribed motion (D with a value) over a step: external
  /// work, as that of the applied loads.
  void add_support_work(double work) {
    external_work_ += work;
    peak_input_ = std::max(peak_input_, initial_kinetic_ + initial_strain_ + external_work_);
  }
  /// Kinetic energy of the initial velocities (IC): energy put in before the first step.
  void set_initial_kinetic(double energy) { initial_kinetic_ = energy; }
  /// Strain energy of the initial displacements (IC), ½ u₀·f_int(u₀): energy put in for the
  /// check's reference only (the strain column counts the change from u₀).
  void set_initial_strain(double energy) { initial_strain_ = energy; }
  /// The status elements' forces at the initial state u₀ (all active DOFs): the first step's
  /// trapezoid starts from them (a slider or gap loaded by IC displacements), not from zero.
  void start(const Assembler& assembler, const VectorXd& u0);
  double external_work() const { return external_work_; }
  double gap_work() const { return gap_work_; }
  double damping_work() const { return damping_work_; }
  /// Plastic work of the committed element histories (0 without plasticity).
  double plastic_work() const;
  /// Internal work minus the work on status elements and the plastic work: the elastic strain
  /// energy (plus the energy stored by kinematic hardening).
  double strain_energy() const { return internal_work_ - gap_work_ - plastic_work(); }
  /// The results-file energy columns ("kinetic", "strain", "external_work", "gap_work",
  /// "dissipation", and "plastic_work" when elements have a history) for the given kinetic
  /// energy.
  std::map<std::string, double> columns(double kinetic) const;
  /// What was not accounted for: initial kinetic + external − kinetic − strain − gap − damping.
  double numerical_dissipation(double kinetic) const;
  /// A warning when the time integrator lost more than 5 % of the energy put in (external work
  /// plus initial kinetic energy: numerical dissipation) or the balance is off the other way by
  /// more than 1 % (energy created), or the gap/contact elements gave back more than 1 % of it
  /// (negative gap work: contact chatter inside unresolved steps), with the remedy; nothing
  /// otherwise.
  std::optional<std::string> balance_warning(double kinetic) const;
  /// Energy created beyond the bound of the check: more than kCreationBound of the energy put
  /// in (the largest initial kinetic + initial strain + external work reached so far; the
  /// floor: nothing is checked while nothing was put in).
  static constexpr double kCreationBound = 0.10;
  struct Creation {
    std::string term;   // what grew: "gap/contact work" or "kinetic + strain energy"
    double created;     // energy created by it
    double reference;   // energy put in
    std::string cause;  // the likely cause and the remedy
  };
  std::optional<Creation> creation(double kinetic) const;
  /// One line for the run summary.
  std::string summary(double time, double kinetic) const;

  /// The accumulated works and the last step's status-element forces, flattened (restart
  /// files); `restore` takes what `state` gave for the same elements.
  std::vector<double> state() const;
  void restore(const std::vector<double>& state);

 private:
  const std::vector<std::unique_ptr<Element>>& elements_;
  std::vector<std::size_t> status_elements_;
  std::vector<std::size_t> history_elements_;
  std::vector<VectorXd> status_force_old_;  // element forces of the status elements, last step
  double initial_kinetic_ = 0.0;
  double initial_strain_ = 0.0;
  double peak_input_ = 0.0;  // the largest energy put in so far (the check's reference)
  double external_work_ = 0.0, internal_work_ = 0.0, gap_work_ = 0.0, damping_work_ = 0.0;
  VectorXd du_;  // scratch of add_step: the step's displacement increment
};

}  // namespace impactfe
