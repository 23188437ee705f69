#pragma once
/// The settings of an explicit dynamics analysis (the ED* commands of MAPDL's ANSYS LS-DYNA
/// interface, docs/explicit_dynamics.md): time-step control (EDCTS), hourglass and bulk viscosity
/// (EDHGLS, EDBVIS), output intervals (EDRST, EDHTIME) and initial velocities (EDVEL). Stored
/// by the deck reader, read by src/explicit; nothing here solves anything.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "core/errors.h"

namespace impactfe {

/// EDVEL,VGEN / VELO: a translational initial velocity of the nodes of a component.
struct ExplicitInitialVelocity {
  std::string component;   // the node component named by Cname (upper case)
  std::vector<int> nodes;  // its nodes when EDVEL was given (ascending)
  Vec3 velocity = Vec3::Zero();
  SourceLocation where;  // the EDVEL command
};

/// An output interval: NSTEP points over the analysis (TIME / NSTEP apart) or a time interval.
struct ExplicitOutputInterval {
  std::optional<int> steps;
  std::optional<double> interval;
  /// The interval for an analysis ending at `end_time`: `default_steps` points when none given.
  double for_end_time(double end_time, int default_steps) const {
    if (steps) return end_time / *steps;  // NSTEP wins over DT when both are given (EDRST notes)
    if (interval) return *interval;
    return end_time / default_steps;
  }
};

/// EDCURVE: a data curve (abscissa, ordinate), the shorter of the two arrays' length.
struct ExplicitCurve {
  std::vector<double> x, y;
  SourceLocation where;
};

/// EDLOAD,ADD: a load by curve (forces, prescribed motion, base accelerations, PRESS, RBF..).
/// The value at time t is SCALE · curve(t − BTIME) between BTIME and DTIME (0: no death),
/// linear between the points and held beyond the last (docs/explicit_dynamics.md).
struct ExplicitCurveLoad {
  std::string label;       // FX FY FZ UX.. VX.. ACLX.. PRESS RBFX..
  std::string component;   // node or element component (upper case), part number as text
  std::vector<int> nodes;  // ascending nodes; PRESS: 4 per face, the pressure's normal order
  std::vector<double> times, values;
  double scale = 1.0, birth = 0.0, death = 0.0;
  int part_material = 0;  // RBFX ..: the material of the part (EDPART) the load names
  SourceLocation where;
};

/// EDCGEN: a contact definition (penalty formulation, docs/explicit_dynamics.md). `contact` and
/// `target` name a part number (EDPART) or a component; blank for single surface contact.
struct ExplicitContact {
  std::string option;  // NTS, ANTS, OSTS, STS, ASTS, ASSC, SS, AG
  std::string contact, target;
  double static_friction = 0.0, dynamic_friction = 0.0, decay = 0.0;  // FS, FD, DC
  double viscous_damping = 0.0;                                       // VDC, % of critical
  double slave_scale = 1.0, master_scale = 1.0;                       // EDCMORE SFS, SFM
  double birth = 0.0, death = 0.0;                                    // BTIME, DTIME (0: never)
  SourceLocation where;
};

/// EDMP,RIGID: the elements of a material move as one rigid body. The constraint codes are
/// those of the command (and of LS-DYNA's *MAT_RIGID CON1/CON2), in global axes: 0 free,
/// 1 x, 2 y, 3 z, 4 x and y, 5 y and z, 6 z and x, 7 all three.
struct ExplicitRigidMaterial {
  int translation = 0;  // VAL1: the fixed translations of the centre of mass
  int rotation = 0;     // VAL2: the fixed rotations
  SourceLocation where;
};

/// Hourglass control and bulk viscosity of the reduced-integration elements (SOLID164,
/// SHELL163) of one material (EDMP,HGLS, LS-DYNA's *HOURGLASS), or of every material without
/// EDMP,HGLS (EDHGLS, EDBVIS: the viscous form).
struct ExplicitHourglass {
  /// VAL1: 0 to 3 the viscous forms, 4 and 5 the stiffness forms (docs/explicit_dynamics.md).
  int type = 0;
  double membrane = 0.1;        // VAL2 QM: the solid's coefficient, the shell's membrane one
  double bulk_quadratic = 1.5;  // VAL3 (solids)
  double bulk_linear = 0.06;    // VAL4 (solids)
  double bending = 0.1;         // VAL5: the shell's rotational modes (default VAL2)
  double warping = 0.1;         // VAL6: the shell's transverse mode (default VAL2)
  bool stiffness() const { return type >= 4; }
  SourceLocation where;  // the EDMP command (unknown for the global settings)
};

/// EDCRB,ADD,NEQN,PARTM,PARTS: the rigid body of the slave part moves with that of the master
/// part as one body (LS-DYNA *CONSTRAINED_RIGID_BODIES): mass, centre and inertia from the
/// elements of every member, the master's constraint codes (EDMP,RIGID). The parts are stored
/// by their materials, whose rigid bodies they are.
struct ExplicitRigidMerge {
  int master_part = 0, slave_part = 0;
  int master_material = 0, slave_material = 0;
  SourceLocation where;
};

/// EDDAMP,ALL,LCID,VALDMP: mass-weighted (alpha) damping of the whole model, the force −α m v
/// on every deformable node (and the moment −α I ω on a node with rotations) and on the centre
/// of mass of every rigid body (LS-DYNA *DAMPING_GLOBAL). α is VALDMP, or the curve LCID's
/// value at the time.
struct ExplicitMassDamping {
  double alpha = 0.0;
  int curve = 0;  // LCID (EDCURVE), 0: the constant alpha
  SourceLocation where;
};

struct ExplicitControls {
  /// EDCTS TSSFAC: the fraction of the stable time step taken (default 0.9).
  double time_step_factor = 0.9;
  /// EDCTS DTMS: the time step of mass-scaled solutions (0: no mass scaling). Positive: every
  /// element whose stable step falls below it gets mass until it reaches it, throughout the
  /// run; negative: mass is added at the start only, to the elements below |DTMS|.
  double mass_scaling_step = 0.0;
  /// EDHGLS HGCO: the Flanagan–Belytschko viscous hourglass coefficient (default 0.1).
  double hourglass_coefficient = 0.1;
  /// EDBVIS QVCO, LVCO: quadratic and linear bulk viscosity coefficients (1.5, 0.06).
  double bulk_quadratic = 1.5;
  double bulk_linear = 0.06;
  std::map<int, ExplicitHourglass> hourglass_materials;  // EDMP,HGLS, by material
  /// The hourglass control and bulk viscosity of the elements of material `mat`.
  ExplicitHourglass hourglass_of(int mat) const {
    if (const auto it = hourglass_materials.find(mat); it != hourglass_materials.end())
      return it->second;
    return ExplicitHourglass{.membrane = hourglass_coefficient,
                             .bulk_quadratic = bulk_quadratic,
                             .bulk_linear = bulk_linear,
                             .bending = hourglass_coefficient,
                             .warping = hourglass_coefficient};
  }
  ExplicitOutputInterval results;                           // EDRST (default 100 intervals)
  ExplicitOutputInterval history;                           // EDHTIME (default 1000 intervals)
  std::vector<ExplicitInitialVelocity> initial_velocities;  // EDVEL, in input order
  std::map<int, ExplicitCurve> curves;                      // EDCURVE, by LCID
  std::vector<ExplicitCurveLoad> loads;                     // EDLOAD, in input order
  std::vector<ExplicitContact> contacts;                    // EDCGEN, entity number = index + 1
  std::map<int, ExplicitRigidMaterial> rigid_materials;     // EDMP,RIGID, by material
  std::map<int, ExplicitRigidMerge> rigid_merges;           // EDCRB, by equation number NEQN
  std::optional<ExplicitMassDamping> mass_damping;          // EDDAMP,ALL
  /// EDHIST: the node components whose nodes the stored history points (EDHTIME) hold; empty:
  /// all nodes.
  std::vector<std::string> history_components;
  /// SLSFAC: LS-DYNA's penalty scale factor of every contact (0.1; EDCONTACT, which sets it,
  /// is refused).
  double penalty_factor = 0.1;
  SourceLocation where;  // the last ED command that changed a setting
};

}  // namespace impactfe
