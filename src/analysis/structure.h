#pragma once
/// The solvable form of a model snapshot: element objects built from the records (adapted for
/// rotated nodal axes and material damping, assembly/element_adapters.h), the element context of
/// the analysis, the node table of the results file, and the automatic constraints of DOFs that
/// carry neither stiffness nor mass (spec §10.1 item 5). Nodal tables of rotated nodes are in
/// their nodal axes, as MAPDL reports them.
/// A DOF that carries a load, an initial condition or a master designation is never constrained
/// automatically: the constructor throws ModelError at the command that put it there (the model
/// is a mechanism).
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "analysis/progress.h"
#include "assembly/assembler.h"
#include "assembly/constraint_equations.h"
#include "assembly/dof_map.h"
#include "elements/element.h"
#include "results/results_file.h"

namespace impactfe {

/// Run-time settings that do not come from the deck.
struct RunSettings {
  bool continue_on_nonconvergence = false;
  std::string superelement_file;         // --se
  ProgressObserver* progress = nullptr;  // told after every substep (the CLI's progress line)
  /// Condense the linear part of a full transient onto the nonlinear elements' DOFs when that
  /// applies (--no-condense turns it off).
  bool condense = true;
  /// A transient that creates energy (EnergyBalance::creation) stops with a solution error
  /// unless this is set (--accept-energy-error): then it warns once and goes on.
  bool accept_energy_error = false;
};

class Structure {
 public:
  /// `steps`: the load steps to be run (their forces must not act on an automatically
  /// constrained DOF; the automatic-constraint report omits the DOFs they hold themselves).
  Structure(const Model& model, const AnalysisOptions& options, const RunSettings& settings,
            const std::vector<LoadStep>* steps = nullptr);

  const Model& model() const { return model_; }
  const AnalysisOptions& options() const { return options_; }
  const ElementContext& context() const { return context_; }
  const std::vector<std::unique_ptr<Element>>& elements() const { return elements_; }
  const std::vector<int>& node_ids() const { return node_ids_; }

  /// Stiffness-proportional damping β of each element's material (MP,DAMP), element order;
  /// empty when no material has one.
  const std::vector<double>& material_stiffness_damping() const { return material_beta_; }

  /// DOFs with neither stiffness nor mass (listed in the log, constrained to zero).
  const std::set<DofKey>& automatic_constraints() const { return automatic_; }
  /// ModelError when a force of `step` acts on an automatically constrained DOF (a load step
  /// solved after the structure was built).
  void check_load_step(const LoadStep& step) const;
  /// The coupled DOF sets (CP), each in its nodes' order (the first is the prime DOF).
  std::vector<std::vector<DofKey>> coupled_dofs() const;
  /// The slaves of the constraint equations (CE, CERIG, MPC184) and what they depend on (null
  /// when the model has none); hand it to every DofMap of this structure.
  const std::shared_ptr<const DependentDofs>& dependent_dofs() const { return dependent_; }
  /// NotImplementedError at the first constraint equation when the structure has any: for the
  /// analyses that do not apply them (`analysis` names it), which refuse rather than ignore them.
  void refuse_constraint_equations(const std::string& analysis) const;
  /// Nodal table of total displacements: as nodal_table, with the constants of the constraint
  /// equations in their slaves' values (u_s = Σ a_j u_j + g).
  Eigen::MatrixXd displacement_table(const DofMap& dofs, const VectorXd& u) const;
  /// D of the load step plus the automatic constraints.
  std::set<DofKey> constraints_of(const LoadStep& step) const;

  /// Makes the nodal tables follow the node list of a results file (`ids`, ascending): rows of
  /// nodes this structure does not have stay NaN. InputError naming the node when the structure
  /// has a node the list lacks (the model grew after the results file was begun).
  void use_table_nodes(const std::vector<int>& ids);

  /// n_nodes x 6 table (ascending node id; NaN where the DOF does not exist) from values over
  /// the active DOFs of `dofs`.
  Eigen::MatrixXd nodal_table(const DofMap& dofs, const VectorXd& values) const;
  /// Same, with only the constrained DOFs filled (reactions).
  Eigen::MatrixXd reaction_table(const DofMap& dofs, const VectorXd& reactions) const;
  /// Element results grouped by family at (u, v) over the active DOFs.
  std::map<std::string, ElementResultTable> element_results(const Assembler& assembler,
                                                            const VectorXd& u,
                                                            const VectorXd& v) const;
  /// Names a DOF in messages: "node 12 UZ".
  static std::string describe_dof(const DofMap& dofs, int index) {
    return describe(dofs.key(index));
  }

 private:
  /// A node table (NaN where no DOF) of values(i) for the DOFs first .. end − 1 of `dofs`.
  Eigen::MatrixXd dof_table(const DofMap& dofs, const VectorXd& values, int first, int end,
                            bool with_constants = false) const;
  /// Builds dependent_ from the model's CE and CERIG and the elements' kinematic constraints.
  void eliminate_constraint_equations(const std::vector<LoadStep>* steps);
  /// InputError when a load step prescribes a slave with D.
  void check_slaves_free(const LoadStep& step) const;
  /// Row of node `id` in the nodal tables; std::out_of_range when it has none.
  int node_row(int id) const;
  /// Indexes node_ids_ for node_row.
  void index_node_rows();

  const Model& model_;
  AnalysisOptions options_;
  ElementContext context_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::vector<int> node_ids_;
  /// node_row's index: by id − node_id_base_ (−1: no row) when the ids span at most 4 × their
  /// number + 1024 values, as numbered decks do (a map lookup per node took ~3 ms per table of
  /// the 155 522-DOF dome's stored points); a map otherwise.
  std::vector<int> node_row_dense_;
  int node_id_base_ = 0;
  std::map<int, int> node_row_sparse_;
  std::set<DofKey> automatic_;
  std::shared_ptr<const DependentDofs> dependent_;
  std::vector<double> material_beta_;
  /// The elements with results, by family (ascending family name, as the tables of
  /// element_results): grouped once, not at every stored point.
  struct ResultFamily {
    std::string name;
    std::vector<std::size_t> members;  // element indices, element order
    std::vector<int> element_ids;
  };
  std::vector<ResultFamily> result_families_;
};

}  // namespace impactfe
