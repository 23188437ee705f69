#pragma once
/// The model database built by the deck reader: the user's node and element numbers (sparse
/// ids), element types with KEYOPTs, real-constant sets, materials, sections, elements,
/// master DOFs, gap conditions, and the analyses requested with their load steps.
/// Nothing here solves anything.
#include <Eigen/Core>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "core/dof.h"
#include "core/errors.h"
#include "core/explicit_controls.h"
#include "core/load_values.h"
#include "core/material_table.h"
#include "core/output_control.h"
#include "core/rotating_frame.h"
#include "core/selection.h"
#include "core/solid_model.h"

namespace impactfe {

struct Node {
  int id = 0;
  Vec3 x = Vec3::Zero();
  /// Nodal-coordinate rotation angles THXY, THYZ, THZX in degrees relative to global Cartesian
  /// (N command, NROTAT). D, F, IC and the nodal results of a rotated node act in its nodal axes
  /// (APDL_MODELING §2.6).
  Vec3 angles_deg = Vec3::Zero();
  bool rotated() const { return angles_deg.squaredNorm() > 0.0; }
  /// Nodal axes (columns) in global components: rotation_from_angles(angles_deg).
  Mat3 axes() const { return rotation_from_angles(angles_deg); }
};

/// ET: local type number, ANSYS name (e.g. "LINK8", the name it is registered under in the
/// element registry), and KEYOPT(1..18) (index 0 unused).
struct ElementType {
  int id = 0;
  std::string ansys_name;
  std::array<int, 19> keyopt{};
  SourceLocation where;
  int key(int i) const { return keyopt.at(static_cast<std::size_t>(i)); }
};

/// R / RMORE: constants in input order; missing trailing values are zero.
struct RealSet {
  int id = 0;
  std::vector<double> values;
  /// Constant number i (1-based), 0 when absent.
  double get(int i) const {
    return (i >= 1 && i <= static_cast<int>(values.size()))
               ? values[static_cast<std::size_t>(i - 1)]
               : 0.0;
  }
  /// True when constant i (1-based) was given explicitly, even as blank→0.
  bool given(int i) const { return i >= 1 && i <= static_cast<int>(values.size()); }
};

/// Linear-elastic material: EX, EY, EZ, NUXY (=PRXY), ..., GXY, DENS, ALPX, DAMP by label.
struct Material {
  int id = 0;
  std::map<std::string, double> props;
  bool has(const std::string& label) const { return props.count(label) != 0; }
  double get(const std::string& label, double fallback) const {
    auto it = props.find(label);
    return it == props.end() ? fallback : it->second;
  }
};

/// SECTYPE/SECDATA: a section of one of the types elements/section_types.h describes (its
/// subtypes and what its SECDATA values mean; APDL_MODELING §7.2).
struct Section {
  int id = 0;
  std::string type;     // SECTYPE Type: "LINK", "SHELL", "BEAM"
  std::string subtype;  // SECTYPE Subtype ("RECT"), empty for a type without subtypes
  std::vector<double> data;
  /// SHELL: the values of every SECDATA (thickness, MAT, θ in degrees, NUMPT), one per layer,
  /// bottom layer first (APDL_MODELING §7.2); `data` is the first of them.
  std::vector<std::vector<double>> layers;
  /// SECOFFSET location (upper case), empty when not given.
  std::string offset;
  /// SECCONTROL values (blank: 0, the computed property). BEAM: TXZ, (unused), TXY transverse
  /// shear stiffnesses kGA of the x-z and x-y planes, ADDMAS added mass per length.
  std::vector<double> controls;
};

/// An element as defined in the deck. Node list may contain repeats (degenerate shapes).
/// For a MATRIX50 element `superelement_file` names the file (resolved only when solving).
struct ElementRecord {
  int id = 0;
  int type = 1;
  int real = 1;
  int mat = 1;
  int secnum = 0;
  /// ESYS: the local coordinate system (> 10) that orients the element axes; 0 the element's
  /// own (shells: x along I-J). Carried out by the types whose descriptor says so
  /// (ElementTypeDescriptor::esys_axes); a SOLVE refuses it on the others.
  int esys = 0;
  std::vector<int> nodes;
  std::string superelement_file;  // MATRIX50 only: "unit:8" (4x) or a file name (SE)
  SourceLocation where;
};

/// GP: gap condition between master DOFs (or to ground) for reduced / MSUP transients.
struct GapCondition {
  int node_i = 0;
  int node_j = 0;
  Dof dof = Dof::UX;
  double stiffness = 0.0;
  double gap = 0.0;
  double damping = 0.0;
  SourceLocation where;
};

/// Automatic time stepping of a load step (AUTOTS; NSUBST NSBMX/NSBMN, DELTIM DTMIN/DTMAX,
/// Carry; APDL_MODELING §9.1, docs/solution_control.md).
struct StepControl {
  std::optional<bool> automatic;         // AUTOTS ON/AUTO (true), OFF (false); unset: default
  std::optional<double> dt_min, dt_max;  // DELTIM DTMIN / DTMAX (time units)
  std::optional<int> n_max, n_min;       // NSUBST NSBMX (smallest step) / NSBMN (largest step)
  bool carry = false;                    // Carry ON: start with the last step of the previous
};

/// RESCONTROL,DEFINE (APDL_MODELING §9.5): the converged substeps that keep a restart point in
/// <jobname>.rst.h5 (none unless RESCONTROL was given, [A]).
/// Load steps: 0 LAST (default), n > 0 every n-th (ALL = 1), -1 NONE; substeps: 0 LAST
/// (default), n > 0 every n-th and the last, -1 NONE.
struct RestartControl {
  bool defined = false;  // RESCONTROL,DEFINE given: restart points are written
  int load_steps = 0;
  int frequency = 0;
};

/// ANTYPE,,RESTART,LDSTEP,SUBSTEP: continue from a restart point (blank: the last one saved).
struct RestartRequest {
  std::optional<int> load_step;
  std::optional<int> substep;
  SourceLocation where;  // the ANTYPE command
};

/// CP: a set of nodes whose DOF `dof` (in nodal axes) share one value (APDL_MODELING, coupled
/// DOF sets). The first node is the prime DOF: the others are eliminated onto it.
struct CoupledSet {
  int id = 0;
  Dof dof = Dof::UX;
  std::vector<int> nodes;  // input order, no repeats
  SourceLocation where;    // the CP command
};

/// One term C_i u_i of a linear constraint equation (DOF in nodal axes).
struct ConstraintTerm {
  DofKey dof;
  double coefficient = 0.0;
};

/// A linear constraint equation CONST = sum C_i u_i (CE; also what CERIG and the MPC184 rigid
/// link and beam write). The first term's DOF is the slave: it is eliminated (master-slave
/// elimination, assembly/constraint_equations.h); the constant applies to total displacements.
struct ConstraintEquation {
  int id = 0;
  double constant = 0.0;
  std::vector<ConstraintTerm> terms;  // input order, the slave first
  SourceLocation where;               // the command (or element record) that defined it
};

/// CERIG,MASTE,SLAVE,Ldof...: a rigid region of small rotations, written as constraint
/// equations when the structure is built (3-D or 2-D by the DOFs the master carries there).
struct RigidRegion {
  int master = 0;
  std::vector<int> slaves;
  bool translations = true;  // the slaves' UX, UY (UZ) follow the master's motion
  bool rotations = true;     // the slaves' rotations equal the master's
  /// Only these slave DOFs (CERIG Ldof = UX, UY, ...), empty: as translations/rotations say.
  std::vector<Dof> only;
  SourceLocation where;
};

/// One load step: the full load state at its end (not deltas) and its options.
/// Loads are cumulative: a step inherits everything from the previous step unless changed.
struct LoadStep {
  int number = 1;
  std::optional<double> time_end;        // TIME; blank = default (see analysis driver)
  std::optional<double> dt;              // DTIME / DELTIM
  std::optional<int> n_substeps;         // ITER NITTER / NSUBST
  OutputControl output;                  // ITER NPOST / OUTRES (core/output_control.h)
  bool stepped = false;                  // KBC: false = ramped, true = stepped
  int reformulation = 1;                 // KRF / NROPT: re-form tangent every n iterations
  bool time_integration = true;          // KAY(5) / TIMINT
  Vec3 acel = Vec3::Zero();              // ACEL: acceleration of the reference frame
  std::map<DofKey, double> constraints;  // D (value in nodal axes)
  std::map<DofKey, double> forces;       // F (nodal axes)
  std::map<DofKey, double> forces_imag;  // F VALUE2: imaginary part (harmonic analysis)
  // HARFRQ,FREQB,FREQE (Hz) of a harmonic analysis: the substeps' frequencies are evenly spaced
  // in (FREQB, FREQE] (NSUBST of them); unset: no frequency given (the SOLVE is refused).
  std::optional<std::pair<double, double>> frequency_range;
  std::map<DofKey, SourceLocation> force_where;  // the F command that set each force
  // Time-function loads (`%TABLE%`, APDL_MODELING §5.5): the table named here gives the value
  // at each time (KBC does not apply); the number in constraints/forces is then unused.
  std::map<DofKey, std::string> constraint_tables;
  std::map<DofKey, std::string> force_tables;
  std::array<std::string, 3> acel_tables;    // ACEL components
  RotationalLoads rotation;                  // OMEGA, DOMEGA, CGLOC, CGOMGA, DCGOMG
  std::map<FaceKey, SurfaceLoad> pressures;  // SF, SFE, SFA (face pressures)
  // Temperatures of the thermal strain (docs/thermal_loads.md). The reference temperature is
  // TREF (MP,REFT of a material overrides it); every node without BF,TEMP has the uniform
  // temperature (TUNIF / BFUNIF,TEMP; unset: TREF), applied stepped; BF,node,TEMP values ramp
  // per KBC from the previous step's temperature of the node.
  double reference_temperature = 0.0;               // TREF
  std::optional<double> uniform_temperature;        // TUNIF / BFUNIF,TEMP
  std::map<int, double> node_temperatures;          // BF,node,TEMP
  std::map<int, SourceLocation> temperature_where;  // the BF command of each node temperature
  /// The temperature of `node` at the end of the step.
  double temperature(int node) const {
    const auto it = node_temperatures.find(node);
    if (it != node_temperatures.end()) return it->second;
    return uniform_temperature.value_or(reference_temperature);
  }
  /// True when the step gives temperatures (TUNIF, BFUNIF or BF): a thermal strain load
  /// wherever they differ from the reference temperature.
  bool gives_temperatures() const {
    return uniform_temperature.has_value() || !node_temperatures.empty();
  }
  // LVSCALE (mode-superposition transient): the loads of the modal analysis's load step
  // `load_vector_step` (Model::modal_load_vectors) times `load_vector_scale`, added to this
  // step's loads and ramped or stepped like them (0: none).
  double load_vector_scale = 0.0;
  int load_vector_step = 1;
  StepControl control;        // AUTOTS and the DELTIM / NSUBST limits
  RestartControl rescontrol;  // RESCONTROL in force when the step is solved
  SourceLocation where;       // command that closed the step (LWRITE/SOLVE/...)
};

/// Initial condition on one DOF (IC).
struct InitialCondition {
  double displacement = 0.0;
  double velocity = 0.0;
  SourceLocation where;  // the IC command
};

enum class AnalysisType { Static, Modal, Transient, Substructure, Harmonic, Spectrum };
enum class TransientMethod { Full, Reduced, ModeSuperposition };
enum class IntegratorKind { Houbolt, Newmark, HHT };
enum class Dialect { Classic4x, Modern };

/// Newmark / HHT / generalized-alpha parameters (TINTP; ALPHA = textbook beta, DELTA = gamma).
struct TimeIntegrationParameters {
  std::optional<double> gamma;  // TINTP GAMMA (amplitude decay), default 0.005
  std::optional<double> alpha;  // Newmark beta
  std::optional<double> delta;  // Newmark gamma
  std::optional<double> alpha_f;
  std::optional<double> alpha_m;
  SourceLocation where;  // the TINTP command (blank when none was given)
};

/// Newton-Raphson and convergence options (NEQIT, CNVTOL, NROPT).
struct ConvergenceOptions {
  int max_iterations = 25;
  double force_tolerance = 0.005;
  double force_minref = 1e-2;
  std::optional<double> displacement_tolerance;  // CNVTOL,U (off unless given)
  bool full_newton = true;
  bool line_search = false;       // LNSRCH,ON
  bool line_search_auto = false;  // LNSRCH,AUTO
};

/// MODOPT: number of modes and frequency window (Hz).
struct ModalOptions {
  int n_modes = 10;
  std::optional<double> freq_begin;
  std::optional<double> freq_end;
  bool normalize_to_unity = false;  // Nrmkey ON: max component 1, else mass-normalised
  std::string method = "LANB";
  bool element_results = false;  // MXPAND Elcalc YES: the element results of each mode
};

/// One requested expansion of a reduced / MSUP transient: n solutions in (t_begin, t_end].
struct ExpansionRequest {
  int count = 1;
  double t_begin = 0.0;
  double t_end = 0.0;
  bool every_step = false;  // NUMEXP,ALL
};

/// HROPT / HROUT / DMPSTR: the harmonic response analysis (ANTYPE,HARMIC).
struct HarmonicOptions {
  bool mode_superposition = false;  // HROPT,MSUP (else FULL)
  int n_modes = 0;                  // HROPT MAXMODE (0: the MODOPT count)
  bool amplitude_phase = false;     // HROUT,OFF: printed as amplitude and phase (printout only)
  double structural_damping = 0.0;  // DMPSTR g: i g K
};

/// The single-point response spectrum analysis (ANTYPE,SPECTR + SPOPT,SPRS; docs/
/// spectrum_analysis.md): the excitation (SED, SVTYP, FREQ, SV), the mode combination (SRSS,
/// CQC, GRP, DSUM, NRLSUM) and the missing mass response (MMASS).
struct SpectrumOptions {
  bool single_point = false;      // SPOPT,SPRS given
  int n_modes = 0;                // SPOPT NMODE (0: every mode of the modal analysis)
  bool element_results = false;   // SPOPT Elcalc YES
  Vec3 direction = Vec3::Zero();  // SED: the excitation direction (normalised by the analysis)
  /// SVTYP KSV: 0 seismic velocity, 2 seismic acceleration, 3 seismic displacement.
  int spectrum_type = 0;
  double scale = 1.0;                                          // SVTYP FACT
  bool linear_interpolation = false;                           // SVTYP KeyInterp
  std::vector<double> frequencies;                             // FREQ (Hz)
  std::vector<std::pair<double, std::vector<double>>> curves;  // SV: damping -> values
  /// The mode combination: "" (none given), SRSS, CQC, GRP, DSUM, NRLSUM.
  std::string combination;
  double significance = 0.001;            // SIGNIF of the combination command
  std::string response = "DISP";          // Label: DISP, VELO, ACEL
  double duration = 10.0;                 // DSUM TD (s)
  bool missing_mass = false;              // MMASS,ON
  double zero_period_acceleration = 0.0;  // MMASS ZPA
  SourceLocation where;                   // the SPOPT command
};

/// ERESX: how elements give their integration-point results at their nodes. Default: MAPDL's
/// (extrapolated while elastic, the nearest point copied once a point is inelastic), Copy
/// (ERESX,YES: always the nearest point), Extrapolate (ERESX,NO: always extrapolated).
enum class NodalStressRule { Default = 0, Copy = 1, Extrapolate = 2 };

/// Analysis-wide options (first load step semantics).
struct AnalysisOptions {
  AnalysisType type = AnalysisType::Static;
  TransientMethod method = TransientMethod::Full;
  IntegratorKind integrator = IntegratorKind::Newmark;
  TimeIntegrationParameters tintp;
  bool large_deflection = false;                              // KAY(6) / NLGEOM
  bool stress_stiffening = false;                             // KAY(8) / SSTIF (NLGEOM implies it)
  bool lumped_mass = false;                                   // KAY(1) / LUMPM
  NodalStressRule nodal_stresses = NodalStressRule::Default;  // ERESX
  ConvergenceOptions convergence;
  ModalOptions modal;
  int msup_modes = 0;                   // TRNOPT MAXMODE (0 = all computed)
  double damping_ratio = 0.0;           // DMPRAT
  std::map<int, double> modal_damping;  // MDAMP: mode -> ratio
  double alpha_damping = 0.0;           // ALPHAD
  double beta_damping = 0.0;            // BETAD
  HarmonicOptions harmonic;             // ANTYPE,HARMIC
  SpectrumOptions spectrum;             // ANTYPE,SPECTR
  int superelement_matrices = 1;        // KAY(6) under KAN=7 / SEOPT SEMATR
  std::string superelement_name;        // SEOPT Sename
  std::optional<int> total_masters;     // TOTAL NTOT (automatic masters)
  bool total_masters_exclude_rotations = false;
  std::map<std::string, int> kay;  // raw KAY values as given (logged)
  /// ANTYPE,,RESTART: the analysis continues from this restart point. The deck hands it to the
  /// next analysis it opens and then forgets it (one analysis continues the run).
  std::optional<RestartRequest> restart;
};

/// One analysis the deck asks to run (4x: /INPUT,27; modern: the SOLVEs of one ANTYPE),
/// with a snapshot of the model taken when the analysis was frozen.
struct AnalysisRequest {
  AnalysisOptions options;
  std::vector<LoadStep> load_steps;
  SourceLocation where;  // the command that started the solution (/INPUT,27, SOLVE, ...)
  /// True when `load_steps` is the whole analysis (AFWRITE froze it); false when later SOLVEs
  /// may append load steps to it.
  bool complete = false;
};

/// SEEXP: the superelement to expand and the use pass whose master results drive it.
struct SuperelementExpansionSource {
  std::string name;      // Sename: the superelement file <Sename>.sub.h5 (or the name as given)
  std::string use_file;  // Usefil: the use pass results <Usefil>.h5 (or the name as given)
  SourceLocation where;  // the SEEXP command
};

/// Expansion ("stress") pass of the preceding reduced/MSUP analysis (/STRESS ... END, EXPASS), or
/// of a superelement's use pass (EXPASS + SEEXP).
struct ExpansionPassRequest {
  std::vector<ExpansionRequest> requests;
  bool static_correction = true;  // EXPASS KeyStat
  std::optional<SuperelementExpansionSource> superelement;
  SourceLocation where;
};

/// CM: a named, frozen list of entity numbers of one kind (APDL_MODELING §1.7). Later
/// selection changes do not alter it; entities deleted later drop out when it is used.
struct Component {
  std::string entity;    // "NODE", "ELEM" (solid-model kinds: "KP", "LINE", "AREA", "VOLU")
  std::vector<int> ids;  // ascending
  SourceLocation where;  // the CM command
};

/// The time of the substep being solved, as the implicit creep laws read it
/// (J2Plasticity::creep): creep acts over (time − dt, time) while `active`.
struct CreepClock {
  bool active = false;       // creep acts in the step being solved
  double time = 0.0;         // t_{n+1}: the load-step TIME at the end of the substep
  double dt = 0.0;           // t_{n+1} − t_n (0: no creep increment)
  double temperature = 0.0;  // absolute temperature of the creep laws
};

/// Everything the deck defines. Node and element maps are ordered by user id.
struct Model {
  std::string title;
  std::string jobname;
  std::string units;  // /UNITS system label (SI, BIN, ...); empty when the deck gives none
  Dialect dialect = Dialect::Modern;

  std::map<int, Node> nodes;
  std::map<int, ElementType> element_types;
  std::map<int, RealSet> real_sets;
  std::map<int, Material> materials;
  std::map<int, Section> sections;
  std::map<int, ElementRecord> elements;

  std::vector<DofKey> masters;                             // M, in input order, no duplicates
  std::map<DofKey, SourceLocation> master_where;           // the M command of each master
  std::vector<GapCondition> gap_conditions;                // GP, in input order
  std::map<DofKey, InitialCondition> initial_conditions;   // IC
  std::map<std::string, Component> components;             // CM, by upper-case name
  std::map<int, CoupledSet> coupled_sets;                  // CP, by set number
  std::map<int, ConstraintEquation> constraint_equations;  // CE, by equation number
  std::vector<RigidRegion> rigid_regions;                  // CERIG, in input order

  // Model building the MAPDL way (APDL_MODELING §1-§6).
  SolidModel solid;                      // keypoints, lines, areas, volumes, mesh controls
  CoordinateSystems coordinate_systems;  // CSYS, LOCAL, CLOCAL, working plane
  ModelSelection selection;              // selected flags of every entity kind
  std::map<std::string, TimeFunction> time_functions;  // TABLE loads by name (upper case)
  std::map<std::pair<int, std::string>, MaterialTable> material_tables;  // TB by (MAT, Lab)
  ExplicitControls explicit_dynamics;  // the ED* settings (docs/explicit_dynamics.md)
  /// Shared by the creep laws of the elements built from this model (and its snapshots).
  std::shared_ptr<CreepClock> creep_clock = std::make_shared<CreepClock>();

  /// Current (not yet written) load state and options; LWRITE/LSWRITE/SOLVE snapshot it.
  AnalysisOptions options;
  LoadStep current;
  /// The load steps of the last modal analysis solved (its F, ACEL, SF): the load vectors a
  /// mode-superposition transient scales with LVSCALE.
  std::vector<LoadStep> modal_load_vectors;

  const Node& node(int id) const;
  const ElementType& element_type(int id) const;
};

/// The parsed deck: the final model and the ordered solution and expansion requests.
struct Job {
  Model model;
  /// In execution order; each entry is either an analysis or an expansion pass.
  struct Step {
    std::optional<AnalysisRequest> analysis;
    std::optional<ExpansionPassRequest> expansion;
    /// The model (geometry, elements, masters, gaps) as of this request. Shared, not copied,
    /// by the session that solves it (issue 11: one model copy less on large runs); not changed
    /// after the request is made.
    std::shared_ptr<Model> model_snapshot = std::make_shared<Model>();
  };
  std::vector<Step> steps;
  std::vector<std::string> ignored_commands;  // graphics / print-only commands, listed in the log
  /// --skip-unknown: each unknown command skipped, how often, and where it first appeared.
  struct Skipped {
    std::string name;
    int count = 0;
    SourceLocation first;
  };
  std::vector<Skipped> skipped_unknown;
};

}  // namespace impactfe
