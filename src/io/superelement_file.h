#pragma once
/// The superelement file <jobname>.sub.h5 (HDF5) written by the generation pass (KAN,7 /
/// ANTYPE,SUBSTR) and read by the MATRIX50 element and the superelement expansion
/// (spec §10.6, §11.7). Layout: docs/substructuring.md.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "core/dof.h"
#include "core/model.h"

namespace impactfe {

/// One master DOF of a superelement: the user node id, its coordinates and nodal angles at
/// generation, and the DOF label.
struct SuperelementMaster {
  DofKey key;
  Vec3 x = Vec3::Zero();
  Vec3 angles_deg = Vec3::Zero();
};

/// Everything a superelement file holds. Matrices are in master order (the element DOF order).
struct SuperelementData {
  std::string name;   // SEOPT Sename, else the generation jobname
  std::string title;  // /TITLE of the generation run
  int matrices = 1;   // SEMATR: 1 = K, 2 = K + M, 3 = K + M + C
  std::vector<SuperelementMaster> masters;
  Eigen::MatrixXd stiffness;               // K_r = TᵀKT
  std::optional<Eigen::MatrixXd> mass;     // M_r = TᵀMT
  std::optional<Eigen::MatrixXd> damping;  // C_r = TᵀCT
  /// Reduced load vectors Tᵀf, one column per generation load step.
  Eigen::MatrixXd load_vectors;
  /// Reduced unit-acceleration vectors g_d = Tᵀ M r_d, one column per direction X, Y, Z: a
  /// frame acceleration a loads the masters with −Σ_d a_d g_d (spec §10.6, U25).
  Eigen::MatrixXd unit_acceleration;

  // ---- expansion data ---------------------------------------------------------------------
  std::vector<DofKey> slaves;       // free DOFs condensed out
  std::vector<DofKey> constrained;  // DOFs held at zero during generation
  /// T_sm = −K_ss⁻¹ K_sm (n_slaves x n_masters): u_s = T_sm u_m (+ static corrections).
  Eigen::MatrixXd transformation;
  /// K_ss⁻¹ f_s of each generation load step (n_slaves x n_load_vectors).
  Eigen::MatrixXd load_correction;
  /// K_ss⁻¹ (M r_d)_s (n_slaves x 3): a frame acceleration a adds −Σ_d a_d of these columns.
  Eigen::MatrixXd acceleration_correction;
  /// Generation model (nodes, types, real sets, materials, sections, elements), element context
  /// flags; serialised as text so the expansion can rebuild the elements (format in the docs).
  std::string model_text;

  int n_masters() const { return static_cast<int>(masters.size()); }
  int n_slaves() const { return static_cast<int>(slaves.size()); }
  std::vector<DofKey> master_keys() const;
};

/// Writes `data` to `path` (truncates). Throws std::runtime_error on an HDF5 failure.
void write_superelement(const std::string& path, const SuperelementData& data);
/// Reads a superelement file. Throws InputError(where, ...) when the file is missing or is not a
/// superelement file.
SuperelementData read_superelement(const std::string& path, const SourceLocation& where = {});

/// Text form of the element-building part of a model (and the context flags) for the file.
std::string serialize_generation_model(const Model& model, bool lumped_mass,
                                       bool stress_stiffening);
/// Rebuilds that model; `lumped_mass` / `stress_stiffening` receive the stored flags.
Model deserialize_generation_model(const std::string& text, bool& lumped_mass,
                                   bool& stress_stiffening);

}  // namespace impactfe
