#include "elements/element_fields.h"

#include <fmt/format.h>

#include <algorithm>

namespace impactfe {

namespace {

std::vector<RealConstantField> named(std::initializer_list<const char*> names) {
  std::vector<RealConstantField> out;
  int position = 0;
  for (const char* name : names) out.push_back({++position, name, false});
  return out;
}

std::vector<int> range(int first, int last) {
  std::vector<int> out;
  for (int v = first; v <= last; ++v) out.push_back(v);
  return out;
}

std::vector<RealConstantField> shell63_constants() {
  auto r = named({"TK(I)", "TK(J)", "TK(K)", "TK(L)", "EFS", "THETA", "RMI"});
  r.push_back({8, "CTOP", true});
  r.push_back({9, "CBOT", true});
  r.push_back({19, "ADMSUA", false});
  return r;
}

std::vector<RealConstantField> surface_contact_constants() {
  // CONTA174 / CONTA175 (APDL_MODELING §8.4): the ones refused are read by MAPDL, not here.
  std::vector<RealConstantField> r;
  const char* names[] = {"R1",   "R2",     "FKN",  "FTOLN", "ICONT", "PINB", "PMAX",
                         "PMIN", "TAUMAX", "CNOF", "FKOP",  "FKT",   "COHE"};
  const bool refused[] = {true, true, false, false, true,  false, true,
                          true, true, false, true,  false, true};
  for (int i = 0; i < 13; ++i) r.push_back({i + 1, names[i], refused[i]});
  return r;
}

std::vector<KeyoptField> surface_contact_keyopts() {
  return {{2, {0, 1}, "algorithm: 0 augmented Lagrange, 1 penalty"},
          {4, range(0, 3), "detection points"},
          {7, {0, 1}, "1: bisection on penetration beyond FTOLN under AUTOTS"},
          {10, range(0, 2), "contact stiffness update"},
          {12, range(0, 6), "behaviour of the contact surface"},
          {18, {0, 1}, "sliding on a deformable target: 0 large, 1 small"}};
}

std::vector<ElementFields> make_table() {
  std::vector<ElementFields> t;
  // Spars (docs/spec/APDL_SUBSET.md §11.1; LINK180: R,n,AREA,ADDMAS,TENSKEY).
  t.push_back({"LINK1",
               named({"AREA", "ISTRN"}),
               {{1, {0, 1}, "written by the ANSYS 4 decks of the thesis; no effect on LINK1"}}});
  t.push_back({"LINK8", named({"AREA", "ISTRN"}), {}});
  // LINK180 keeps its cross-section area under NLGEOM: KEYOPT(2) = 1 (rigid section) is what
  // it computes; the default 0 (incompressible section) is approximated by it (the same to first
  // order in the strain).
  t.push_back({"LINK180",
               named({"AREA", "ADDMAS", "TENSKEY"}),
               {{2, {0, 1}, "1: rigid cross-section (constant area); 0 is computed so as well"}}});
  // Beams (APDL_MODELING §8.1, §8.2).
  t.push_back({"BEAM3",
               named({"AREA", "IZZ", "HEIGHT", "SHEARZ", "ISTRN", "ADDMAS"}),
               {{2, {0, 1}, "1: lumped mass"}}});
  {
    auto r = named({"AREA", "IZZ", "IYY", "TKZ", "TKY", "THETA", "ISTRN", "IXX", "SHEARZ", "SHEARY",
                    "SPIN", "ADDMAS"});
    r[10].refused = true;  // SPIN: rotating frame
    t.push_back({"BEAM4", r, {{2, {0, 1}, "1: lumped mass"}}});
  }
  t.push_back({"BEAM188",
               {},
               {{1, {0}, "1 (warping DOF) is not supported"},
                {3, {0, 2, 3}, "interpolation: 0 linear, 2 quadratic, 3 cubic"}}});
  t.push_back({"BEAM189", {}, {{1, {0}, "1 (warping DOF) is not supported"}}});
  // Springs, gaps, masses.
  {
    auto r = named({"K", "CV1", "CV2"});
    r[2].refused = true;  // nonlinear damping
    t.push_back({"COMBIN14",
                 r,
                 {{2, range(0, 6), "scalar spring on one DOF (1-6)"},
                  {3, {0, 1, 2}, "0 3-D longitudinal, 1 3-D torsional, 2 2-D longitudinal"}}});
  }
  t.push_back({"COMBIN40",
               named({"K1", "C", "M", "GAP", "FSLIDE", "K2"}),
               {{1, {0, 1}, "1: gap locks when closed"},
                {3, range(0, 6), "DOF: UX UX UY UZ ROTX ROTY ROTZ"},
                {6, {0, 1, 2}, "mass location: 0 half at each node, 1 node I, 2 node J"}}});
  // MPC184 (docs/elements/mpc184.md): the rigid link and the rigid beam, by elimination.
  t.push_back({"MPC184",
               {},
               {{1,
                 {0, 1},
                 "0 rigid link, 1 rigid beam; the joints, slider and other MPC184 forms "
                 "(KEYOPT(1) = 2..16) are not implemented"},
                {2,
                 {0, 1},
                 "0 direct elimination; 1 (Lagrange multipliers) is solved by elimination too"}}});
  t.push_back({"MASS21",
               named({"MASSX", "MASSY", "MASSZ", "IXX", "IYY", "IZZ"}),
               {{2, {0, 1}, "1: mass in nodal axes"},
                {3, {0, 2, 3, 4}, "0 3-D with inertias, 2 3-D mass, 3 2-D with IZZ, 4 2-D mass"}}});
  // Solids (docs/elements/solid45.md). SOLID185 KEYOPT(6) = 1 (mixed u-P) is not implemented.
  t.push_back({"SOLID45",
               {},
               {{1, {0, 1}, "1: no extra displacement shapes"},
                {2, {0, 1}, "1: reduced integration (approximated: full 2x2x2)"}}});
  t.push_back({"SOLID185",
               {},
               {{2, range(0, 3),
                 "0 B-bar (mean dilatation); 2 enhanced strain (incompatible modes + 4 "
                 "volumetric); 3 simplified enhanced strain (incompatible modes); 1 reduced: "
                 "full 2x2x2 (approximation, warned)"},
                {6, {0}, "1 (mixed u-P formulation) is not implemented"}}});
  // Quadratic solids (docs/elements/solid186.md). KEYOPT(6) = 1 (mixed u-P) is not implemented.
  t.push_back({"SOLID186",
               {},
               {{2, {0, 1}, "integration: 0 uniform reduced 2x2x2, 1 full 3x3x3"},
                {6, {0}, "1 (mixed u-P formulation) is not implemented"}}});
  t.push_back({"SOLID187", {}, {{6, {0}, "1 and 2 (mixed u-P formulations) are not implemented"}}});
  // Legacy quadratic solids, computed as SOLID186 / SOLID187 (docs/elements/solid186.md). Their
  // output KEYOPTs (SOLID95 4, 5, 6; SOLID92 5, 6) and SOLID95's 14-point rule are refused.
  t.push_back({"SOLID95",
               {},
               {{11,
                 {0},
                 "0 2x2x2 reduced integration; 1 (14-point integration) is not "
                 "implemented"}}});
  t.push_back({"SOLID92", {}, {}});
  // MESH200: mesh-only (no solution); KEYOPT(1) its cell.
  t.push_back({"MESH200",
               {},
               {{1, range(0, 11),
                 "cell: 0-3 lines (2 or 3 nodes), 4-5 triangles, 6-7 quadrilaterals, 8-9 "
                 "tetrahedra, 10-11 bricks (without or with midside nodes)"}}});
  // 2-D solids (docs/elements/plane182.md). THK is read with KEYOPT(3) = 3 only.
  t.push_back({"PLANE182",
               named({"THK"}),
               {{1, range(0, 3),
                 "0 full 2x2 (B-bar in plane strain and axisymmetry), 1 uniform reduced "
                 "(one point, hourglass control), 3 simplified enhanced strain (incompatible "
                 "modes), 2 enhanced strain in plane stress only; under NLGEOM 0 only"},
                {3, range(0, 3),
                 "0 plane stress, 1 axisymmetric, 2 plane strain, 3 plane stress with "
                 "thickness; 5 and 6 are not implemented"},
                {6, {0}, "1 (mixed u-P formulation) is not implemented"}}});
  // The legacy forms (computed as PLANE182 / PLANE183): KEYOPT(5) and (6) choose printout
  // (nodal stresses, surface solutions) and have no effect here.
  t.push_back({"PLANE42",
               named({"THK"}),
               {{2, {0, 1}, "0 extra displacement shapes (incompatible modes), 1 suppressed"},
                {3, range(0, 3),
                 "0 plane stress, 1 axisymmetric, 2 plane strain, 3 plane stress with "
                 "thickness"},
                {5, range(0, 2), "printout of extra element output (no effect here)"},
                {6, range(0, 4), "printout of surface solutions (no effect here)"}}});
  t.push_back({"PLANE82",
               named({"THK"}),
               {{3, range(0, 3),
                 "0 plane stress, 1 axisymmetric, 2 plane strain, 3 plane stress with "
                 "thickness"},
                {5, range(0, 2), "printout of extra element output (no effect here)"},
                {6, range(0, 4), "printout of surface solutions (no effect here)"}}});
  t.push_back({"PLANE183",
               named({"THK"}),
               {{1, {0, 1}, "0 8-node quadrilateral, 1 6-node triangle"},
                {3, range(0, 3),
                 "0 plane stress, 1 axisymmetric, 2 plane strain, 3 plane stress with "
                 "thickness; 5 and 6 are not implemented"},
                {6, {0}, "1 (mixed u-P formulation) is not implemented"}}});
  // Explicit elements (docs/explicit_dynamics.md): SOLID164 KEYOPT(1) 0 and 1 are both the
  // one-point constant-stress brick; 2 (full integration) and 5 (ALE) are not implemented.
  t.push_back({"SOLID164", {}, {{1, {0, 1}, "0 or 1: one-point constant stress (the same)"}}});
  t.push_back({"LINK160", named({"AREA"}), {}});
  t.push_back({"MASS166", named({"MASS"}), {}});
  // COMBI165: the dynamic magnification, clearance, failure and deflection limits are refused.
  {
    auto r = named({"KD", "V0", "CL", "FD", "CDL", "TDL"});
    for (auto& f : r) f.refused = true;
    t.push_back({"COMBI165", r, {{1, {1}, "1: translational spring or damper"}}});
  }
  // BEAM161: Hughes–Liu with cross-section integration (KEYOPT(1) 0 or 1), the default
  // quadrature, rectangular (KEYOPT(5) 0) or tubular (1) sections from the real constants; the
  // resultant, truss and tubular Belytschko formulations (KEYOPT(1) 2 to 5), the other
  // quadratures, the standard sections (KEYOPT(4), KEYOPT(5) = 2) and offset reference lines
  // (NSLOC, NTLOC) are not implemented.
  {
    auto r = named({"SHRF", "TS1", "TS2", "TT1", "TT2", "NSLOC", "NTLOC"});
    r[5].refused = r[6].refused = true;
    t.push_back({"BEAM161",
                 r,
                 {{1, {0, 1}, "0 or 1: Hughes-Liu with cross-section integration (the same)"},
                  {5, {0, 1}, "0 rectangular, 1 tubular (circular) section"}}});
  }
  // SHELL163: Belytschko–Tsay (KEYOPT(1) 0 or 2); the other formulations are not implemented.
  t.push_back({"SHELL163",
               named({"SHRF", "NIP", "T1", "T2", "T3", "T4"}),
               {{1, {0, 2}, "0 or 2: Belytschko-Tsay (the same)"}}});
  // Shells (docs/elements/shell63.md). SHELL181 is computed with the SHELL63 kernel; of its
  // real constants only the thicknesses are read (the others mean other things than SHELL63's).
  t.push_back({"SHELL63",
               shell63_constants(),
               {{1, {0, 1, 2}, "0 bending and membrane, 1 membrane only, 2 bending only"},
                {3, {0, 2}, "2: no extra displacement shapes"},
                {5, {0, 1}, "1: extra stress printout (a printout option: no effect here)"},
                {7, {0, 1}, "1: no rotary inertia"}}});
  t.push_back({"SHELL181",
               named({"TK(I)", "TK(J)", "TK(K)", "TK(L)"}),
               {{1, {0, 1}, "0 bending and membrane, 1 membrane only"},
                {3, {0, 2}, "integration: both computed with extra displacement shapes"},
                {8, {0, 1, 2}, "layer data storage (a printout option: no effect here)"},
                {9, {0}, "1 (user thickness routine) is not supported"}}});
  t.push_back({"SHELL281",
               named({"TK(I)", "TK(J)", "TK(K)", "TK(L)"}),
               {{1, {0, 1}, "0 bending and membrane, 1 membrane only"},
                {8, {0, 1, 2}, "layer data storage (a printout option: no effect here)"},
                {9, {0}, "1 (user thickness routine) is not supported"}}});
  t.push_back({"SHELL208",
               {},
               {{3,
                 {0, 2},
                 "0 one integration point along the length; 2 an extra internal node (quadratic, "
                 "condensed), two points"},
                {8, {0, 1, 2}, "layer data storage (a printout option: no effect here)"}}});
  t.push_back({"MATRIX50", {}, {}});
  // Contact (APDL_MODELING §8.4, docs/elements/conta174.md, conta175.md, conta178.md).
  t.push_back({"CONTA174", surface_contact_constants(), surface_contact_keyopts()});
  t.push_back({"CONTA175", surface_contact_constants(), surface_contact_keyopts()});
  // 2-D (docs/elements/targe169.md): the same law and fields, UX, UY per node.
  t.push_back({"CONTA171", surface_contact_constants(), surface_contact_keyopts()});
  t.push_back({"CONTA172", surface_contact_constants(), surface_contact_keyopts()});
  {
    auto r = named({"FKN", "GAP", "START", "FKS", "REDFACT", "NX", "NY", "NZ", "TOLN"});
    r[4].refused = true;
    t.push_back({"CONTA178",
                 r,
                 {{2, {0, 1}, "algorithm: 0 augmented Lagrange, 1 penalty"},
                  {12, range(0, 6), "behaviour of the contact"}}});
  }
  t.push_back({"TARGE170", {}, {{2, {0, 1}, "boundary conditions: 0 automatic, 1 given"}}, true});
  t.push_back(
      {"TARGE169",
       {},
       {{2,
         {0, 1},
         "boundary conditions: 0 automatic, 1 given (refused on a rigid target without a pilot)"}},
       true});
  std::sort(t.begin(), t.end(), [](const auto& a, const auto& b) { return a.type < b.type; });
  return t;
}

}  // namespace

const std::vector<ElementFields>& all_element_fields() {
  static const std::vector<ElementFields> table = make_table();
  return table;
}

const ElementFields* element_fields(const std::string& type) {
  for (const auto& f : all_element_fields())
    if (f.type == type) return &f;
  return nullptr;
}

std::string keyopt_refusal(const ElementType& type) {
  const ElementFields* fields = element_fields(type.ansys_name);
  if (fields == nullptr) return {};
  for (int k = 1; k < static_cast<int>(type.keyopt.size()); ++k) {
    const int v = type.key(k);
    if (v == 0) continue;
    const auto f = std::find_if(fields->keyopts.begin(), fields->keyopts.end(),
                                [k](const KeyoptField& x) { return x.number == k; });
    if (f == fields->keyopts.end())
      return fmt::format(
          "{} KEYOPT({}) = {} is not carried out (only KEYOPT(1..18) = 0 unless "
          "listed in docs/deck_reader.md, \"Element fields\")",
          type.ansys_name, k, v);
    if (std::find(f->values.begin(), f->values.end(), v) == f->values.end())
      return fmt::format("{} KEYOPT({}) = {} is not carried out ({})", type.ansys_name, k, v,
                         f->meaning);
  }
  return {};
}

std::string real_set_refusal(const ElementType& type, const RealSet& set) {
  const ElementFields* fields = element_fields(type.ansys_name);
  if (fields == nullptr || fields->real_set_of_pair) return {};
  for (int i = 1; i <= static_cast<int>(set.values.size()); ++i) {
    if (set.get(i) == 0.0) continue;
    const auto f = std::find_if(fields->real_constants.begin(), fields->real_constants.end(),
                                [i](const RealConstantField& x) { return x.position == i; });
    if (f == fields->real_constants.end()) {
      std::string read;
      for (const auto& c : fields->real_constants)
        if (!c.refused)
          read += fmt::format("{}{} {}", read.empty() ? "" : ", ", c.position, c.name);
      return fmt::format("real constant {} of set {} (= {}) is not read by {} ({})", i, set.id,
                         set.get(i), type.ansys_name,
                         read.empty() ? "it takes no real constants" : "it reads " + read);
    }
    if (f->refused)
      return fmt::format("{} (real constant {} of set {}) = {} is not supported by {}", f->name, i,
                         set.id, set.get(i), type.ansys_name);
  }
  return {};
}

}  // namespace impactfe
