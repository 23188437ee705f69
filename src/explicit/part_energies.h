#pragma once
/// The energies of each part of an explicit run (LS-DYNA's MATSUM; docs/explicit_dynamics.md,
/// "Results and the energy check"): parts as EDPART numbers them (the elements grouped by type,
/// material and real set, in ascending order), each with its kinetic, internal (with plastic
/// work) and hourglass energy.
#include <Eigen/Core>

#include <map>
#include <vector>

#include "core/model.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_system.h"

namespace impactfe {

/// The EDPART number of every element of `model` (by element id).
std::map<int, int> explicit_part_numbers(const Model& model);

class ExplicitPartEnergies {
 public:
  ExplicitPartEnergies(const Model& model, const ExplicitSystem& system);
  std::size_t size() const { return n_parts_; }
  /// Kinetic, internal and hourglass energy of each part, 3 per part, part 1 first. A node's
  /// kinetic energy (½mv² + ½Iω², rigid nodes too) goes to the parts of the elements around it
  /// in proportion to the mass each lumped there; internal and hourglass energies are the sums
  /// of the parts' elements' (ExplicitElementSet::element_energies).
  Eigen::VectorXd at(const ExplicitSystem& system, const CentralDifference& cd) const;

 private:
  std::size_t n_parts_ = 0;
  /// Per element set (system.sets), per element: its part (0-based).
  std::vector<std::vector<int>> part_of_;
  /// Node → (part, fraction of the node's mass), CSR.
  std::vector<std::size_t> share_start_;
  std::vector<int> share_part_;
  std::vector<double> share_fraction_;
};

}  // namespace impactfe
