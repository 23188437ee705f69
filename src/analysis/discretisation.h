#pragma once
/// The discretised structure of a static or full transient run for one set of constrained DOFs:
/// the DOF numbering (free DOFs first, constraints eliminated, thesis eq. 2-8), the assembler,
/// the status loop, the linear solver with its factorization of the effective matrix
/// K + cC C + cM M, the condensation of the linear part (linear_part_condensation.h), the frame
/// acceleration load, the contact-frequency estimator and the contact elements that check their
/// penetration. A change of the constraint set, or of the DOF list of a contact that slides
/// (large_sliding.h), builds a new one: the renumbering (the state is remapped by DOF key,
/// motion_state.h).
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "analysis/linear_part_condensation.h"
#include "analysis/structure.h"
#include "analysis/time_step_advice.h"
#include "assembly/loads.h"
#include "elements/penetration_check.h"
#include "linalg/linear_solver.h"
#include "nonlinear/status_loop.h"

namespace impactfe {

class Discretisation {
 public:
  /// `constrained`: the DOFs held by D and the automatic constraints. `condense`: a transient
  /// whose linear part may be condensed onto its nonlinear elements (--no-condense: false).
  Discretisation(const Structure& structure, std::set<DofKey> constrained, bool condense);

  const std::set<DofKey>& constrained() const { return constrained_; }
  const DofMap& dofs() const { return *dofs_; }
  Assembler& assembler() { return *assembler_; }
  const Assembler& assembler() const { return *assembler_; }
  StatusLoop& status_loop() { return *status_loop_; }
  LinearSolver& solver() { return *solver_; }
  const LinearSolver& solver() const { return *solver_; }
  const FrameAccelerationLoad& frame_load() const { return frame_load_; }
  /// The contact frequencies of the status elements (nullptr: the model has none).
  const ContactFrequencyEstimator* contact_frequency() const { return contact_frequency_.get(); }

  /// The condensation of the linear part, or nullptr when it does not apply (or was dropped).
  LinearPartCondensation* condensation() { return condensation_.get(); }
  /// What the run summary says about the condensation of this numbering (nullopt: nothing new).
  const std::optional<std::string>& condensation_note() const { return condensation_note_; }
  /// The linear part alone is singular (a DOF held only by nonlinear elements): full Newton.
  void drop_condensation() { condensation_.reset(); }
  /// The linear solver's and the condensation's counters together.
  SolverCounters counters() const;

  /// Factorizes the effective matrix for `coeff` at (u, v). Throws SingularMatrixError.
  void factorize(const IntegrationCoefficients& coeff, const VectorXd& u, const VectorXd& v);
  /// Whether the factor holds the effective matrix for `coeff` (a status change, a step change
  /// or a new start invalidates it).
  bool factor_valid_for(const IntegrationCoefficients& coeff) const;
  bool factor_valid() const { return factor_valid_; }
  void invalidate_factor() { factor_valid_ = false; }

  /// The cut reason when a KEYOPT(7) contact penetrates more than FTOLN·depth at u and the
  /// substep from u_start added more than that (PenetrationCheck); empty if none.
  std::string excessive_penetration(const VectorXd& u_start, const VectorXd& u) const;
  /// "elements 3, 4" carrying active DOF `index` (for messages).
  std::string elements_at(int index) const;
  /// "node 12 UZ".
  std::string describe_dof(int index) const { return Structure::describe_dof(*dofs_, index); }

  /// ½ vᵀ M v from the assembler's global products (no copy of M is kept).
  double kinetic_energy(const VectorXd& v) const {
    return 0.5 * v.dot(assembler_->inertia_force(v));
  }

 private:
  const Structure& structure_;
  std::set<DofKey> constrained_;
  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::unique_ptr<StatusLoop> status_loop_;
  std::unique_ptr<LinearSolver> solver_;
  FrameAccelerationLoad frame_load_;  // -M r a, assembled once per DOF numbering
  SparseMatrix effective_;            // formed on the first full assembly
  bool factor_valid_ = false;
  IntegrationCoefficients factored_{};
  std::unique_ptr<ContactFrequencyEstimator> contact_frequency_;
  std::unique_ptr<LinearPartCondensation> condensation_;
  std::optional<std::string> condensation_note_;
  // Contact elements with KEYOPT(7) = 1 (elements/penetration_check.h): index and interface.
  std::vector<std::pair<std::size_t, const PenetrationCheck*>> penetration_checks_;
};

}  // namespace impactfe
