#pragma once
/// The discrete system of an explicit run (docs/explicit_dynamics.md): the nodes of the
/// explicit elements (ascending id), their lumped (row-sum) masses, the element sets built
/// through the registry, and for each node the slots of the element force buffer that belong to
/// it, summed in a fixed order (element order) so that the internal force vector is bitwise the
/// same however the element loop is split.
#include <memory>
#include <string>
#include <vector>

#include "core/model.h"
#include "elements/explicit_kernel.h"
#include "explicit/rigid_body.h"

namespace impactfe {

/// Whether a model runs explicit: it has elements and each of their types has an explicit set
/// and no other kernel is needed (a type without one is named in `why_not`).
bool runs_explicit(const Model& model, std::string* why_not = nullptr);
/// True when some element type of the model is explicit-only (SOLID164, ...).
bool has_explicit_elements(const Model& model);

struct ExplicitSystem {
  std::vector<int> node_ids;  // ascending
  std::vector<double> x0, y0, z0;
  std::vector<double> mass;  // lumped nodal mass (mass-scaled)
  std::vector<std::unique_ptr<ExplicitElementSet>> sets;
  std::vector<std::size_t> set_offset;  // first force-buffer slot (node of an element) of each set
  std::size_t n_slots = 0;              // force-buffer slots (3 doubles each)
  /// Node → its force-buffer slots, CSR (slot_start has n_nodes + 1 entries), slots ascending.
  std::vector<std::size_t> slot_start;
  std::vector<std::size_t> slots;
  double physical_mass = 0.0;  // before mass scaling
  /// Nodes with rotational DOFs (those of a set with has_rotations()), ascending; empty when
  /// no set has rotations, and then `inertia` is empty too (translational runs stay as cheap).
  std::vector<std::size_t> rotational_nodes;
  std::vector<double> inertia;  // lumped rotary inertia per node (0 at nodes without rotations)
  /// The elements of rigid materials (EDMP,RIGID): built for their mass and their contact
  /// faces only; they take no part in the force loop or the time step.
  std::vector<std::unique_ptr<ExplicitElementSet>> rigid_sets;
  std::vector<RigidBody> rigid_bodies;  // one per rigid material, ascending material
  std::vector<int> rigid_body_of;       // per node: its body, −1 for none (empty: no bodies)
  bool is_rigid(std::size_t n) const { return !rigid_body_of.empty() && rigid_body_of[n] >= 0; }
  bool has_rotations() const { return !rotational_nodes.empty(); }
  /// Recomputes `inertia` from the sets (after mass scaling changed their densities).
  void update_inertia();

  std::size_t n_nodes() const { return node_ids.size(); }
  std::size_t n_elements() const;
  /// Index of a node id; -1 when the node carries no explicit element.
  int index_of(int node_id) const;
};

/// Builds the system of `model`'s elements with the ED settings of the model.
ExplicitSystem build_explicit_system(const Model& model);

}  // namespace impactfe
