#pragma once
/// Superelement expansion (spec §10.6 "Expansion", §10.5): from the master DOF values of a use
/// pass, the full substructure displacements u = [u_m; T_sm u_m + static corrections], its
/// velocities and accelerations (T only), and the element results of the generation model.
#include <memory>
#include <string>
#include <vector>

#include "analysis/structure.h"
#include "io/superelement_file.h"
#include "results/results_file.h"

namespace impactfe {

class SuperelementExpansion {
 public:
  /// Rebuilds the generation model and its elements from the file content.
  explicit SuperelementExpansion(SuperelementData data);
  ~SuperelementExpansion();

  const SuperelementData& data() const { return data_; }
  /// The generation model (nodes, elements) the expanded results refer to.
  const Model& model() const { return *model_; }
  /// Node ids of the expanded nodal tables (ascending).
  const std::vector<int>& node_ids() const { return structure_->node_ids(); }
  /// Numbering of the expanded vectors (the generation pass's active DOFs).
  const DofMap& dofs() const { return *dofs_; }

  /// Full displacement over dofs() from the master displacements u_m (file master order).
  /// Static corrections (KeyStat): `acel` — frame acceleration of the use pass, adds
  /// −Σ_d a_d K_ss⁻¹(M r_d)_s; `load_scales` — factors of the generation load vectors, adds
  /// Σ_i s_i K_ss⁻¹ f_s,i (empty: none).
  VectorXd expand_displacement(const VectorXd& um, const Vec3& acel = Vec3::Zero(),
                               const std::vector<double>& load_scales = {}) const;
  /// Velocity or acceleration over dofs() from master values: T x_m (no static term).
  VectorXd expand_motion(const VectorXd& xm) const;
  /// A results time point of the substructure: nodal U, V, A tables and element results.
  TimePoint time_point(double time, const VectorXd& um, const VectorXd& vm, const VectorXd& am,
                       const Vec3& acel = Vec3::Zero()) const;

 private:
  SuperelementData data_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Structure> structure_;
  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::vector<int> master_index_, slave_index_;
};

/// Where the files of a superelement expansion pass are: SEEXP Sename → <Sename>.sub.h5 (or the
/// name as given), Usefil → <Usefil>.h5 (or the name as given), in the working directory.
/// InputError at the SEEXP command when one is missing.
std::string superelement_file_of(const SuperelementExpansionSource& source);
std::string use_results_file_of(const SuperelementExpansionSource& source);

/// The superelement expansion pass (EXPASS + SEEXP; spec §10.6 "Expansion"): reads the master
/// histories (U, V, A) of the use pass's static and transient analyses, selects the time points
/// the requests ask for (NUMEXP / EXPSOL), and appends one Expansion analysis of the generation
/// model to `writer` (whose model section must be the generation model: see results_model()).
/// The static correction (KeyStat) adds the slave response to the frame acceleration the use
/// pass recorded. Returns the number of time points written.
int expand_superelement_use_pass(const SuperelementExpansion& expansion, const ResultsReader& use,
                                 const ExpansionPassRequest& request, ResultsWriter& writer);

}  // namespace impactfe
