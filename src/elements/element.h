#pragma once
/// The element interface. Elements work in global (Cartesian) axes and never know the time
/// scheme or the analysis driver; drivers never know element internals.
#include <Eigen/Core>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/dof.h"
#include "core/model.h"

namespace impactfe {

/// Analysis-wide switches an element needs when it evaluates its matrices.
struct ElementContext {
  bool large_deflection = false;   // co-rotational / total-Lagrangian kinematics (NLGEOM, KAY(6))
  bool stress_stiffening = false;  // add the geometric (stress) stiffness (SSTIF, KAY(8))
  bool lumped_mass = false;        // diagonal mass (LUMPM, KAY(1))
};

/// Named scalar results of one element at one time point (e.g. SAXL, FORC, STAT).
/// The names are fixed per element family and given by Element::result_names().
using ElementResultValues = std::vector<double>;

/// Gap / slider status of a status element (COMBIN40).
enum class GapStatus { Open = 0, Closed = 1, Sliding = 2 };

class Element {
 public:
  explicit Element(int id) : id_(id) {}
  virtual ~Element() = default;
  Element(const Element&) = delete;
  Element& operator=(const Element&) = delete;

  /// User element number.
  int id() const { return id_; }
  /// Descriptive family name: "Spar", "SpringDamper", "PointMass", "CombinationGap", ...
  virtual const char* family() const = 0;
  /// Element DOFs in element order (node, dof). Repeated nodes of degenerate shapes appear once.
  virtual const std::vector<DofKey>& dofs() const = 0;
  int n_dofs() const { return static_cast<int>(dofs().size()); }

  /// True when stiffness or internal force depend on the displacement for this context
  /// (large deflection, status elements). Linear elements are evaluated once per factorization.
  virtual bool is_nonlinear(const ElementContext& ctx) const = 0;

  /// Tangent stiffness K_T (material + stress stiffness when ctx asks for it) and internal
  /// force f_int at total displacement u (element DOF order). For a linear element f_int = K u.
  virtual void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                       Eigen::VectorXd& f_int) const = 0;
  /// Internal force f_int at u alone, bitwise the f_int of tangent(): for a residual that
  /// needs no tangent (the evaluation that finds a Newton iterate converged; issue 11). The
  /// default runs tangent() and drops K.
  virtual void internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                              Eigen::VectorXd& f_int) const;
  /// True when internal_force() costs much less than tangent() here (co-rotational shell,
  /// total-Lagrangian brick): a residual then evaluates the force alone and the tangent only
  /// when a factorization asks for it. False (default): one tangent() serves both.
  virtual bool separate_internal_force(const ElementContext& ctx) const { return false; }
  /// Mass matrix (consistent, or lumped when ctx.lumped_mass or the element is inherently lumped).
  virtual void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const = 0;
  /// Viscous damping matrix at u (COMBIN40: only while closed). Default: none.
  virtual bool has_damping() const { return false; }
  virtual void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
                       Eigen::MatrixXd& C) const;
  /// Loads of frame accelerations (ACEL, spec §3.19) on the element DOFs: column k of f for
  /// the acceleration in column k of `a`. Default: f = −M r a with the element mass and r the
  /// rigid translation of each translational DOF (the mass formed once for all the columns). A
  /// superelement overrides it with the exact reduced vectors −Σ_d a_d g_d (spec §10.6, U25).
  virtual void frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                                       Eigen::MatrixXd& f) const;
  /// Inertia loads of acceleration fields linear in position (the rotational loads OMEGA,
  /// DOMEGA, CGOMGA, DCGOMG: core/rotating_frame.h), column k of f for fields[k]: f = −M ā with
  /// ā the field at each node on the translational DOFs and the material's angular acceleration
  /// on the rotational ones (the mass formed once for all fields). With the consistent mass of
  /// an isoparametric element this is ∫ρ Nᵀ a(x) dV exactly, since a linear field is interpolated
  /// exactly. `position(node)` gives a node's coordinates. Throws ModelError when a field has a
  /// component along a translation the element has no DOF for (a plane element in Z): that part
  /// of the load could not act. A superelement refuses (its file has no such load vectors).
  virtual void acceleration_field_load(const ElementContext& ctx,
                                       const std::vector<LinearAccelerationField>& fields,
                                       const std::function<Vec3(int)>& position,
                                       Eigen::MatrixXd& f) const;
  /// Consistent nodal load of a pressure on face `face` (1-based, the face numbering of the
  /// element type's registration) with values `p` at the face's nodes (face-node order), over the
  /// element DOFs in global axes (APDL_MODELING §5.1-§5.3). Positive pressure acts into the face.
  /// Under large deflection (ctx.large_deflection) the pressure follows the face deformed by u
  /// (follower load); otherwise it acts on the initial face. Default: the element takes no
  /// surface loads (ModelError naming it).
  virtual void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                             const Eigen::VectorXd& u, Eigen::VectorXd& f) const;

  // ---- history (plasticity) -----------------------------------------------------------------
  /// True when the element carries a material history (plastic strain per integration point).
  /// tangent() and results() stay pure functions of (committed history, u): they compute the
  /// trial state by return mapping from the committed one. The drivers call commit_history on
  /// every element with a history when a step has converged (StatusLoop::commit), and revert()
  /// when a step is restarted. Such an element must also report is_nonlinear() == true.
  virtual bool has_history() const { return false; }
  /// Accepts the converged step at u: the material state at u becomes the committed one.
  virtual void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {}
  /// Plastic work ∫σ:dε_p dV of the committed history (energy balance); 0 without plasticity.
  virtual double plastic_work() const { return 0.0; }

  // ---- committed state for restart files (RESCONTROL / ANTYPE,,RESTART) ---------------------
  /// Everything the element has committed beyond the displacements (material history of
  /// every integration point or fibre, slider slip, gap / contact status) as a flat vector;
  /// empty for an element without one. A restart file keeps it so that a continued run equals
  /// the uninterrupted one to round-off.
  virtual std::vector<double> history_state() const { return {}; }
  /// Makes `state` (from history_state() of the same element of the same model) the committed
  /// and the trial state. Throws (internal error) when the length does not fit.
  virtual void restore_history_state(const std::vector<double>& state);

  // ---- status elements (gap open/closed, slider stick/slide) --------------------------------
  virtual bool has_status() const { return false; }
  /// Re-evaluates the status from the latest iterate u; returns true when it changed (the
  /// iteration is then not converged). Called once per equilibrium iteration.
  virtual bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) { return false; }
  /// Accepts the converged step at u: the trial status/slip become the committed ones.
  virtual void commit(const Eigen::VectorXd& u) {}
  /// Returns to the committed state (a step is restarted).
  virtual void revert() {}
  /// Freezes the current status for the rest of the step (chatter guard).
  virtual void freeze_status(bool frozen) {}
  virtual GapStatus status() const { return GapStatus::Closed; }
  /// Stiffness of the closed contact (COMBIN40: K1 + K2), for time-step advice; 0 otherwise.
  virtual double contact_stiffness() const { return 0.0; }

  // ---- results ------------------------------------------------------------------------------
  /// Names of the element results, e.g. {"FORC", "SAXL", "EPEL"} for a spar.
  virtual const std::vector<std::string>& result_names() const = 0;
  /// Values in result_names() order at displacement u and velocity v.
  virtual void results(const ElementContext& ctx, const Eigen::VectorXd& u,
                       const Eigen::VectorXd& v, ElementResultValues& out) const = 0;
  /// Values in result_names() order at each of the element's nodes (key: node id), for nodal
  /// averages (PRNSOL, PLNSOL, *GET NODE S): the integration-point values extrapolated to the
  /// nodes. false: the element has only its results() values (averaged at the nodes as they are).
  virtual bool nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                             std::map<int, ElementResultValues>& at_node) const {
    return false;
  }
  /// The axes of the element's stress and strain components (S, EPEL, EPPL ... X..XZ) at
  /// displacement u: columns = the result x, y, z axes in global coordinates. POST1 rotates the
  /// components through them into the results system (MAPDL RSYS: "rotates the results data to
  /// the specified coordinate system during printout, display, or element table operations").
  /// Global axes (the identity) unless the element reports in its own axes (shells).
  virtual Eigen::Matrix3d result_axes(const ElementContext& ctx, const Eigen::VectorXd& u) const {
    return Eigen::Matrix3d::Identity();
  }
  /// Undeformed volume (length × area of a spar, ∫t dA of a shell, ∫dV of a brick) for
  /// *GET ELEM VOLU and ETABLE VOLU; nullopt for elements without one (springs, masses, gaps).
  virtual std::optional<double> volume() const { return std::nullopt; }

  // ---- thermal strain (docs/thermal_loads.md) ---------------------------------------------------
  /// The thermal expansion of the element's material: secant coefficients ALPX/ALPY/ALPZ (MP;
  /// ALPY and ALPZ default to ALPX), its own reference temperature MP,REFT when given, and the
  /// element's nodes (ElementRecord order) whose temperatures drive it. Data, set when the model's
  /// elements are built (assembly/element_adapters.h).
  struct ThermalExpansion {
    Vec3 alpha = Vec3::Zero();
    std::optional<double> reference_temperature;  // MP,REFT (else TREF)
    std::vector<int> nodes;
    bool expands() const { return alpha.squaredNorm() > 0.0; }
  };
  const ThermalExpansion& thermal_expansion() const { return thermal_expansion_; }
  void set_thermal_expansion(ThermalExpansion t) { thermal_expansion_ = std::move(t); }
  /// The temperature change T − T_ref at the element's nodes (ThermalExpansion::nodes order) at
  /// the load point being solved; empty when there is none. The loads set it before they ask
  /// thermal_load() and before results are taken, so that the stresses subtract the thermal
  /// strain of the same temperatures.
  virtual void set_temperature_change(std::vector<double> dT) {
    temperature_change_ = std::move(dT);
  }
  const std::vector<double>& temperature_change() const { return temperature_change_; }
  /// Equivalent nodal forces of the thermal strain ε_th = α (T − T_ref) at the temperature
  /// change set last: f = ∫ Bᵀ D ε_th dV over the element DOFs in global axes (linear kinematics).
  /// Default: NotImplementedError naming the element (an element that does not take thermal
  /// strain never ignores it).
  virtual void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const;

  // ---- damping of the element's material -----------------------------------------------------
  /// MP,ALPD / MP,BETD of the element's material (APDL_MODELING §6.1): C_e += α M_e + β K_e.
  /// Data, not behaviour: set when the model's elements are built (assembly/element_adapters.h)
  /// and applied by the assembly where it scatters the element's matrices, so that no wrapper
  /// stands between the drivers and what the element is.
  struct MaterialDamping {
    double alpha = 0.0;
    double beta = 0.0;
  };
  const MaterialDamping& material_damping() const { return material_damping_; }
  void set_material_damping(const MaterialDamping& d) { material_damping_ = d; }

 private:
  int id_;
  MaterialDamping material_damping_;
  ThermalExpansion thermal_expansion_;
  std::vector<double> temperature_change_;
};

struct ElementBuildCache;  // elements/element_build_cache.h

/// What an element constructor gets: the model, its record, and a resolver for superelement
/// files (MATRIX50), which are found only when the model is solved.
struct ElementBuildContext {
  const Model& model;
  std::function<std::string(const ElementRecord&)> resolve_superelement_file;
  /// What the elements of one build pass share, made on first use (element_build_cache.h):
  /// the elements at each node and the contact targets. Without it every contact element
  /// would scan the whole model, and setting up n contact nodes would cost O(n × elements).
  mutable std::shared_ptr<ElementBuildCache> cache = nullptr;
  /// The elements are built for large-deflection kinematics (NLGEOM): an element may keep what
  /// its co-rotational tangent reads at every iteration. Without it such matrices are formed
  /// when asked (a linear model asks once per element; the assembler keeps the global sums).
  bool large_deflection = false;
};

/// Builds the element of a record. Throws InputError (with the element's source location) for
/// bad data: missing material property, zero length/area/volume, wrong node count.
std::unique_ptr<Element> create_element(const ElementBuildContext& ctx,
                                        const ElementRecord& record);

/// Throws ModelError (naming `element`) unless each field is unchanged by a rotation about the
/// global Y axis: the load of an axisymmetric element (X radial, Y the axis) must be
/// axisymmetric itself (rotations about Y only, CGLOC on the Y axis).
void require_axisymmetric_fields(const Element& element,
                                 const std::vector<LinearAccelerationField>& fields);

}  // namespace impactfe
