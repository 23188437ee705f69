#pragma once
/// Elements whose DOF list follows the deformation (elements/connectivity.h: contact nodes on a
/// deformable target with large sliding): after an accepted step they re-find their DOFs, and
/// when a list changed the driver renumbers before the next step.
///
/// Why a renumbering between steps and not a fixed superset: the facets a sliding node may meet
/// are not known when the model is built (the whole target, in general), and a superset that
/// large would couple every contact node to every target node. Within a step the lists are
/// fixed, so Newton iterates on a static pattern; a contact node keeps a margin of candidates
/// (1.5 × its pinball, target_surface.h) and changes its list once per half pinball of travel.
/// The renumbering is the one a change of the constraint set makes at a load step
/// (discretisation.h), except that the integrator continues: its history is remapped by DOF
/// key, so the time scheme (Houbolt's past displacements included) carries on as if nothing
/// happened; the linear part of a condensed transient is factorized again for the new contact
/// DOF set (its cost is the price of a change, not of a step).
#include <optional>
#include <string>
#include <vector>

#include "analysis/discretisation.h"

namespace impactfe {

class LargeSliding {
 public:
  explicit LargeSliding(const Structure& structure) : structure_(structure) {}

  /// The elements re-find their DOFs at the displacements u (over `disc`'s active DOFs); true
  /// when a list changed (the DOFs must be renumbered).
  bool refresh(const Discretisation& disc, const VectorXd& u);
  /// The run summary's line (empty when no list changed).
  std::string summary() const;

 private:
  const Structure& structure_;
  std::optional<std::vector<std::size_t>> members_;  // found on the first refresh
  long long passes_ = 0;                             // refresh passes made
  int renumberings_ = 0;                             // passes that changed a list
};

}  // namespace impactfe
