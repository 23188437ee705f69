#pragma once
/// Element nodal forces of the current POST1 set for FSUM, NFORCE and PRESOL,F
/// (APDL_SCRIPTING §D.9): each element of the model evaluated at the stored displacement,
/// velocity and acceleration of its nodes. The deck layer builds the element objects from the
/// model (element layer), it does not solve anything.
#include <array>
#include <map>
#include <vector>

#include "deck/deck_context.h"

namespace impactfe::deck {

/// FX FY FZ MX MY MZ at one node (global axes): the element's internal force vector there.
using NodalForce = std::array<double, 6>;

/// Element nodal forces of element `element` at the current set, by node, for the FORCE kind
/// (TOTAL = static + damping + inertia, STATIC = f_int(u), DAMP = C v, INERT = M a).
std::map<int, NodalForce> element_nodal_forces(DeckReader& r, const Command& c, int element);

/// The element's result values extrapolated to its nodes at the current set (by node id, in
/// the type's result_names() order); empty when the element has no nodal values (then its
/// centroid values stand for the nodes) or cannot be built.
std::map<int, std::vector<double>> element_nodal_results(DeckReader& r, const Command& c,
                                                         int element);

/// The axes of the element's stress and strain components at the current set (columns: the
/// result x, y, z axes in global coordinates; Element::result_axes at the stored displacement),
/// cached for the set. The identity when the element cannot be built (its values then stay as
/// stored).
const Mat3& element_result_axes(DeckReader& r, const Command& c, int element);

/// Sum over `elements` of their nodal forces at each node.
std::map<int, NodalForce> nodal_force_sums(DeckReader& r, const Command& c,
                                           const std::vector<int>& elements);

}  // namespace impactfe::deck
