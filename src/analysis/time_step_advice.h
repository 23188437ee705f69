#pragma once
/// Time-step advice for impacts (thesis §III.C, eq. 5-3-1): the highest frequency that matters
/// is that of a contact while it is closed, acting between the bodies it joins, taken as rigid:
/// ω = √(k (1/m_I + 1/m_J)), with k the element's contact stiffness and m the mass (in the
/// contact direction) of the body each end belongs to — the nodes connected through elements
/// without a status — and a constrained end as ground. Δt = T/30 resolves it; Δt > T/10 does not.
#include <memory>
#include <optional>
#include <vector>

#include "assembly/dof_map.h"
#include "elements/element.h"
#include "linalg/sparse.h"

namespace impactfe {

struct ContactFrequency {
  double omega = 0.0;  // rad per unit time
  int element = 0;     // user id of the element that sets it
  double period() const;
};

/// The bodies and their masses, found once per DOF numbering, so that the frequency of the
/// contacts closed now costs a loop over the status elements (automatic time stepping asks
/// after every substep). `elements`, `dofs` outlive it.
class ContactFrequencyEstimator {
 public:
  /// `mass_row_sums`: M·1 over the active DOFs of `dofs` (Assembler::inertia_force of ones).
  ContactFrequencyEstimator(const std::vector<std::unique_ptr<Element>>& elements,
                            const DofMap& dofs, const VectorXd& mass_row_sums);
  /// The highest contact frequency (`closed_only`: of the contacts not open now), or nullopt.
  std::optional<ContactFrequency> highest(bool closed_only) const;

 private:
  const std::vector<std::unique_ptr<Element>>& elements_;
  struct Member {
    std::size_t element;
    double flexibility;  // 1/m_I + 1/m_J of the bodies its free DOFs belong to
  };
  std::vector<Member> members_;  // the status elements
};

}  // namespace impactfe
