#pragma once
/// External loads of a load step at a fraction of its time span: nodal forces (F), the inertia
/// load of the frame acceleration (ACEL: f = -M r a, spec §3.19), face pressures (SF/SFE/SFA,
/// APDL_MODELING §5.1-§5.3) and prescribed displacements (D), ramped or stepped per KBC (spec
/// §3.20), or given by time functions (`%TABLE%` loads, APDL_MODELING §5.5).
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "assembly/dof_map.h"
#include "core/model.h"
#include "linalg/sparse.h"

namespace impactfe {

/// Interpolation of one load step: `previous` is the step before (nullptr for the first step)
/// and `fraction` in [0, 1] the position within the step (1 = end of step).
struct LoadPoint {
  const LoadStep* current = nullptr;
  const LoadStep* previous = nullptr;
  double fraction = 1.0;
  /// Time of the point and the model's time functions (Model::time_functions): a load given as
  /// a table takes the table's value at this time, whatever KBC says.
  double time = 0.0;
  const std::map<std::string, TimeFunction>* tables = nullptr;
};

/// Value of a DOF entry of a load table at a load point (KBC ramp from the previous value).
double interpolate(const LoadPoint& at, double previous_value, double current_value);
/// Value of the time function `name` at the load point's time. Precondition: the table exists
/// (the deck reader checks it when the load is given).
double table_value(const LoadPoint& at, const std::string& name);
/// True when the load step has loads given by time functions.
bool has_tabular_loads(const LoadStep& step);

/// The F or D entries of a load step resolved to active DOF indices once per load step, so that
/// a substep evaluates them without a map lookup (issue 11: a step costs a solve plus O(n)
/// vector work). F entries on constrained DOFs are dropped (the constraint wins); D entries on
/// free or inactive DOFs too.
class ResolvedDofLoads {
 public:
  enum class Kind { Forces, Constraints };
  ResolvedDofLoads() = default;
  ResolvedDofLoads(const DofMap& dofs, const LoadStep& current, const LoadStep* previous,
                   Kind kind);
  /// Adds the loads at `at` to v (over all active DOFs).
  void add_to(const LoadPoint& at, VectorXd& v) const;

 private:
  struct Entry {
    int index = 0;
    double previous = 0.0;  // value at the end of the previous load step (KBC ramp start)
    double value = 0.0;
    std::string table;    // time function, when the load is given by one
    double weight = 1.0;  // the table's factor (a force on a slave acts as a_j F on master j)
  };
  std::vector<Entry> entries_;
};

/// Nodal forces F over all active DOFs (entries on constrained DOFs are dropped: the constraint
/// wins).
VectorXd nodal_forces(const DofMap& dofs, const LoadPoint& at);
/// Frame acceleration (ACEL) at a load point.
Vec3 frame_acceleration(const LoadPoint& at);
/// Inertia load of a frame acceleration over all active DOFs, summed from each element's
/// Element::frame_acceleration_load (−M r a, or −Σ a_d g_d exactly for a superelement).
VectorXd inertia_load(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                      const ElementContext& ctx, const Vec3& acel);
/// The inertia loads of several frame accelerations (the columns of `accelerations`) in one
/// pass over the elements: each element's mass is formed once (issue 11).
Eigen::MatrixXd inertia_loads(const std::vector<std::unique_ptr<Element>>& elements,
                              const DofMap& dofs, const ElementContext& ctx,
                              const Eigen::Matrix3Xd& accelerations);
/// The frame-acceleration load is linear in a: f(a) = Σ_d a_d f(e_d). The three unit loads are
/// assembled once per DOF numbering (through the element hook, so superelements are exact) and
/// each time step costs three vector updates.
class FrameAccelerationLoad {
 public:
  FrameAccelerationLoad() = default;
  FrameAccelerationLoad(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                        const ElementContext& ctx);
  /// −M r a over all active DOFs.
  VectorXd operator()(const Vec3& acel) const;
  /// The same into `f` (resized; its storage reused); a zero vector of `n` when there is no
  /// frame acceleration load (no mass).
  void assign(const Vec3& acel, Eigen::Index n, VectorXd& f) const;

 private:
  std::array<VectorXd, 3> unit_;
};

/// The rotational inertia loads (OMEGA, DOMEGA, CGLOC, CGOMGA, DCGOMG) at a load point: each
/// component ramped per KBC from the previous step's value (the angular velocity is ramped, so
/// the centrifugal load grows with its square), or stepped.
RotationalLoads rotational_loads(const LoadPoint& at);
/// Inertia load over all active DOFs of the acceleration field of `loads`
/// (rotational_acceleration, MAPDL Theory Reference "Acceleration Effect"), summed from each
/// element's Element::acceleration_field_load (−M ā); `position(node)` gives the node's
/// coordinates. An element's refusal names the command that gave the loads (loads.where).
VectorXd rotational_inertia_load(const std::vector<std::unique_ptr<Element>>& elements,
                                 const DofMap& dofs, const ElementContext& ctx,
                                 const std::function<Vec3(int)>& position,
                                 const RotationalLoads& loads);

/// Consistent nodal loads of the face pressures over all active DOFs, at displacement u (over
/// all active DOFs; under large deflection the pressures follow the deformed faces), from each
/// element's Element::pressure_load. Pressures on elements that no longer exist are skipped.
VectorXd pressure_forces(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                         const ElementContext& ctx, const LoadPoint& at, const VectorXd& u);

/// Prescribed displacements: values on constrained DOFs (index >= n_free), zero elsewhere.
VectorXd prescribed_displacements(const DofMap& dofs, const LoadPoint& at);
/// Constrained DOF set of a load step (D entries).
std::set<DofKey> constrained_set(const LoadStep& step);

}  // namespace impactfe
