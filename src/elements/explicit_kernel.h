#pragma once
/// The explicit (central-difference) side of an element type (docs/explicit_dynamics.md): the
/// elements of one type are built together into an ExplicitElementSet that keeps their state as
/// structure of arrays and evaluates them in one loop per cycle. The explicit run (src/explicit)
/// knows only this interface; an element type offers it through the `explicit_set` factory of
/// its registration (element_registry.h).
///
/// Per cycle the run hands the set the configuration x_{n+1} and the half-step velocities
/// v_{n+1/2}; the set updates its stresses over dt_{n+1/2}, writes each element's nodal forces
/// into its own slots of a force buffer (the run sums them per node in a fixed order, so the
/// result does not depend on how the element loop is split over threads) and returns the
/// smallest stable time step of its elements at x_{n+1}.
#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// Nodal arrays of the run, indexed by the run's node index (structure of arrays).
struct ExplicitNodalView {
  const double* x = nullptr;  // current coordinates x_{n+1}
  const double* y = nullptr;
  const double* z = nullptr;
  const double* vx = nullptr;  // half-step velocities v_{n+1/2}
  const double* vy = nullptr;
  const double* vz = nullptr;
  /// Angular velocities ω_{n+1/2} (global axes) of the nodes that carry rotations (those of a set
  /// with has_rotations()); null when the run has none. Other nodes' entries are 0.
  const double* wx = nullptr;
  const double* wy = nullptr;
  const double* wz = nullptr;
  /// Lumped nodal masses (after mass scaling): the step of the discrete elements (COMBI165),
  /// which have none of their own, comes from their nodes' masses.
  const double* mass = nullptr;
};

/// What an element set is built from.
struct ExplicitBuildContext {
  const Model& model;
  /// The run's index of a node id (InputError at the element when the node is undefined).
  std::function<int(int node, const ElementRecord& record)> node_index;
  /// EDHGLS, EDBVIS and EDMP,HGLS: the hourglass control and bulk viscosity by material.
  const ExplicitControls& controls;
  ExplicitHourglass hourglass_of(int mat) const { return controls.hourglass_of(mat); }
};

/// The smallest stable time step of a set and the element (user id) that has it.
struct ExplicitStepLimit {
  double dt = std::numeric_limits<double>::infinity();
  int element = 0;
  void take(double step, int id) {
    if (step < dt) {
      dt = step;
      element = id;
    }
  }
};

/// Energies of a set, accumulated since the start.
struct ExplicitSetEnergies {
  double internal = 0.0;      // ∫σ:D dV dt + bulk viscosity work (includes plastic work)
  double hourglass = 0.0;     // work of the hourglass forces (viscous: dissipated)
  double plastic_work = 0.0;  // ∫σ:dε_p dV
};

/// A surface piece an element offers to contact (docs/explicit_dynamics.md, "Contact"): four
/// run node indices counterclockwise seen from outside (a triangle repeats its third node), the
/// element (user id), and what the penalty stiffness is made of (LS-DYNA Theory Manual,
/// "Penalty method"): k = f·K·A²/V for a solid's face (`volume` > 0, `thickness` 0) and
/// k = f·K·A/(largest diagonal) for a shell (`thickness` > 0: the surface lies ±thickness/2 off
/// the mid-surface).
struct ExplicitSegment {
  int nodes[4] = {0, 0, 0, 0};
  int element = 0;
  double bulk_modulus = 0.0;
  double volume = 0.0;
  double thickness = 0.0;
};

class ExplicitElementSet {
 public:
  virtual ~ExplicitElementSet() = default;
  /// The family name of the results file's element table ("Solid164").
  virtual const std::string& family() const = 0;
  virtual std::size_t size() const = 0;
  virtual int element_id(std::size_t k) const = 0;
  /// Nodes per element: the element's slots in the force buffer are [k·3n, (k+1)·3n).
  virtual int nodes_per_element() const = 0;
  /// The run's node indices of element k (nodes_per_element of them).
  virtual const int* nodes(std::size_t k) const = 0;
  /// Adds element k's lumped (row-sum) mass to its nodes.
  virtual void add_element_mass(std::size_t k, std::vector<double>& mass) const = 0;
  /// Adds each element's lumped mass to its nodes.
  void add_lumped_mass(std::vector<double>& mass) const {
    for (std::size_t k = 0; k < size(); ++k) add_element_mass(k, mass);
  }
  /// ∫ρ x xᵀ dV of element k about the origin in the configuration `state`: the rotational
  /// inertia of a rigid body (EDMP,RIGID) made of such elements.
  virtual Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& state,
                                             std::size_t k) const = 0;
  /// The stable time step of element k at the given configuration (no bulk viscosity).
  virtual double element_step(const ExplicitNodalView& state, std::size_t k) const = 0;
  /// Scales the density of element k by `factor` (≥ 1, mass scaling) and adds the extra mass to
  /// its nodes; returns the mass added.
  virtual double scale_mass(std::size_t k, double factor, std::vector<double>& mass) = 0;
  /// One cycle: stresses updated over dt from v_{n+1/2}, nodal forces f_int (x, y, z of each node
  /// of each element, element-major) written to `element_forces`; the stable step at x_{n+1}.
  /// The element loop runs in chunks of kChunk elements on the thread pool: each element writes
  /// only its own slots and state, each chunk sums its energies, and the chunks' sums and step
  /// limits are taken in chunk order, so the results are bitwise equal for any thread count.
  ExplicitStepLimit internal_forces(const ExplicitNodalView& state, double dt,
                                    double* element_forces) {
    return internal_forces_and_moments(state, dt, element_forces, nullptr);
  }
  /// Sets whose nodes carry rotations (shells, beams): the run gives their nodes angular
  /// velocities and rotary inertia and passes `element_moments`.
  virtual bool has_rotations() const { return false; }
  /// Adds each element's lumped rotary inertia (one value per node, the same about every
  /// axis) to its nodes; called again after mass scaling.
  virtual void add_rotary_inertia(std::vector<double>& /*inertia*/) const {}
  /// internal_forces plus the nodal moments (x, y, z per slot, like the forces) of a set with
  /// rotations; `element_moments` may be null (the moments are then computed and dropped).
  ExplicitStepLimit internal_forces_and_moments(const ExplicitNodalView& state, double dt,
                                                double* element_forces, double* element_moments);
  /// Energies accumulated since the start.
  ExplicitSetEnergies energies() const { return energies_; }
  /// Each element's internal energy (with its plastic work) and hourglass energy since the
  /// start, 2 per element (empty before the first cycle): the part energies of the results.
  const std::vector<double>& element_energies() const { return element_energy_; }
  /// Elements per chunk of the threaded element loop.
  static constexpr std::size_t kChunk = 256;
  /// The contact segments of every element (all faces of a solid: the contact keeps the ones
  /// not shared by two elements); none by default (springs, masses).
  virtual void segments(std::vector<ExplicitSegment>& out) const { (void)out; }
  /// Stored results of every element (rows) in the order of the registration's result_names.
  virtual void results(Eigen::MatrixXd& out) const = 0;

 protected:
  /// The cycle of elements [begin, end): as internal_forces_and_moments, the energies of the
  /// chunk added to `energies` (not to the set's: the caller sums the chunks in order).
  /// `element_moments` is never null for a set with rotations.
  virtual ExplicitStepLimit chunk_forces(const ExplicitNodalView& state, double dt,
                                         double* element_forces, double* element_moments,
                                         std::size_t begin, std::size_t end,
                                         ExplicitSetEnergies& energies) = 0;
  /// Adds an element's internal (hourglass) energy increment to its own total and returns it
  /// for the chunk's sum: `energies.internal += internal_work(k, dW)`. Each element writes
  /// only its own entries, so the element loop may run on several threads.
  double internal_work(std::size_t k, double work) {
    element_energy_[2 * k] += work;
    return work;
  }
  double hourglass_work(std::size_t k, double work) {
    element_energy_[2 * k + 1] += work;
    return work;
  }
  ExplicitSetEnergies energies_;
  std::vector<double> element_energy_;

 private:
  std::vector<ExplicitSetEnergies> chunk_energies_;
  std::vector<ExplicitStepLimit> chunk_limits_;
  std::vector<double> dropped_moments_;
};

class Element;

/// The implicit factory of an explicit (16x) element type: refuses the element, named `name`,
/// at its definition; `alternative` ends the message ("; use SOLID185 in an implicit one").
[[noreturn]] std::unique_ptr<Element> refuse_in_implicit_analysis(const ElementRecord& record,
                                                                  const char* name,
                                                                  const char* alternative = "");

using ExplicitSetFactory = std::function<std::unique_ptr<ExplicitElementSet>(
    const ExplicitBuildContext&, const std::vector<const ElementRecord*>&)>;

}  // namespace impactfe
