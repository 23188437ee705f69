// Coordinate systems, working plane and nodal rotations (APDL_MODELING §2): CSYS, LOCAL, CLOCAL,
// CSDELE, WPCSYS, WPOFFS, WPROTA, WPAVE, WPSTYL, NROTAT, and DSYM (a rotation and constraints).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "deck/modeling_helpers.h"
#include "deck/post_support.h"

namespace impactfe::deck {

namespace {

CoordinateSystems& systems(DeckReader& r) {
  return r.model.coordinate_systems;
}

/// Angles with round-off below 1e-10 degrees set to zero (an unrotated node stays unrotated).
Vec3 clean_angles(const Vec3& a) {
  Vec3 out = a;
  for (int i = 0; i < 3; ++i)
    if (std::fabs(out(i)) < 1e-10) out(i) = 0.0;
  return out;
}

CsysKind system_kind(DeckReader& r, const Command& c, int field) {
  const std::string l = r.label(c, field);
  if (l.empty() || l == "0" || l == "CART") return CsysKind::Cartesian;
  if (l == "1" || l == "CYLIN") return CsysKind::Cylindrical;
  if (l == "2" || l == "SPHE") return CsysKind::Spherical;
  if (l == "3" || l == "TORO") r.fail(c, "toroidal coordinate systems (KCS = 3) are not supported");
  r.fail(c, fmt::format("bad system type '{}' (0 CART, 1 CYLIN, 2 SPHE)", c.text(field)));
}

void check_elliptic(DeckReader& r, const Command& c, int first) {
  for (int f = first; f <= first + 1; ++f)
    if (!c.blank(f) && std::fabs(r.real(c, f, 1.0) - 1.0) > 1e-12)
      r.fail(c, "elliptical systems (PAR1/PAR2 ≠ 1) are not supported");
}

int user_system_number(DeckReader& r, const Command& c) {
  const auto kcn = r.opt_int(c, 1);
  if (!kcn) r.fail(c, "system number KCN missing");
  if (*kcn <= 10)
    r.fail(c, fmt::format("KCN {} must be greater than 10 (0..10 are reserved)", *kcn));
  return *kcn;
}

void cmd_csys(DeckReader& r, const Command& c) {
  const int kcn = r.integer(c, 1, 0);
  if (!systems(r).has(kcn))
    r.fail(c, fmt::format("coordinate system {} is not defined (LOCAL, CLOCAL)", kcn));
  systems(r).active = kcn;
}

/// The CDB archive form of LOCAL: `LOCAL,R5.0,LOC,KCN,KCS,XC,YC,ZC` defines the system (axes
/// along global), then `...,ANG,KCN,KCS,THXY,THYZ,THZX` turns it and `...,PRM,KCN,KCS,PAR1,PAR2`
/// gives its shape parameters. As LOCAL, it makes the system active.
void local_archive_form(DeckReader& r, const Command& c) {
  Command plain = c;
  plain.fields.erase(plain.fields.begin(), plain.fields.begin() + std::min(2, c.n_fields()));
  const std::string part = r.label(c, 2);
  const int kcn = user_system_number(r, plain);
  if (part == "LOC") {
    CoordinateSystem cs;
    cs.kind = system_kind(r, plain, 2);
    cs.origin = Vec3(r.real(plain, 3, 0.0), r.real(plain, 4, 0.0), r.real(plain, 5, 0.0));
    systems(r).define(kcn, cs);
  } else if (part == "ANG" || part == "PRM") {
    if (!systems(r).has(kcn))
      r.fail(c, fmt::format("LOCAL,R5.0,{} of system {} before its LOC record", part, kcn));
    CoordinateSystem cs = systems(r).get(kcn);
    if (part == "ANG")
      cs.axes = rotation_from_angles(
          Vec3(r.real(plain, 3, 0.0), r.real(plain, 4, 0.0), r.real(plain, 5, 0.0)));
    else
      check_elliptic(r, plain, 3);
    systems(r).define(kcn, cs);
  } else {
    r.fail(c, fmt::format("LOCAL,R5.0 record '{}': LOC, ANG or PRM", part));
  }
  systems(r).active = kcn;
}

void cmd_local(DeckReader& r, const Command& c) {
  if (r.label(c, 1) == "R5.0") return local_archive_form(r, c);
  const int kcn = user_system_number(r, c);
  CoordinateSystem cs;
  cs.kind = system_kind(r, c, 2);
  cs.origin = Vec3(r.real(c, 3, 0.0), r.real(c, 4, 0.0), r.real(c, 5, 0.0));
  cs.axes = rotation_from_angles(Vec3(r.real(c, 6, 0.0), r.real(c, 7, 0.0), r.real(c, 8, 0.0)));
  check_elliptic(r, c, 9);
  systems(r).define(kcn, cs);
  systems(r).active = kcn;
}

void cmd_clocal(DeckReader& r, const Command& c) {
  const int kcn = user_system_number(r, c);
  const CoordinateSystem active = systems(r).active_system();
  CoordinateSystem cs;
  cs.kind = system_kind(r, c, 2);
  // Origin in the active system; axes start aligned with the active system at that point
  // (radial, tangential, axial in a cylindrical one).
  cs.origin = active.to_global(Vec3(r.real(c, 3, 0.0), r.real(c, 4, 0.0), r.real(c, 5, 0.0)));
  Mat3 base;
  active.axes_at(cs.origin, base);
  cs.axes =
      base * rotation_from_angles(Vec3(r.real(c, 6, 0.0), r.real(c, 7, 0.0), r.real(c, 8, 0.0)));
  check_elliptic(r, c, 9);
  systems(r).define(kcn, cs);
  systems(r).active = kcn;
}

void cmd_csdele(DeckReader& r, const Command& c) {
  std::vector<int> ids;
  if (r.label(c, 1) == "ALL") {
    for (const auto& [id, cs] : systems(r).systems())
      if (id > 10) ids.push_back(id);
  } else {
    const int first = r.integer(c, 1, 0);
    const int last = r.integer(c, 2, first);
    const int inc = std::max(1, r.integer(c, 3, 1));
    if (first <= 10) r.fail(c, fmt::format("system {} is predefined and cannot be deleted", first));
    for (int k = first; k <= last; k += inc) ids.push_back(k);
  }
  for (int id : ids) {
    systems(r).remove(id);
    if (systems(r).active == id) systems(r).active = 0;
  }
}

void cmd_wpcsys(DeckReader& r, const Command& c) {
  const int kcn = r.integer(c, 2, systems(r).active);
  if (!systems(r).has(kcn)) r.fail(c, fmt::format("coordinate system {} is not defined", kcn));
  const CoordinateSystem cs = systems(r).get(kcn);
  WorkingPlane& wp = systems(r).working_plane;
  wp.origin = cs.origin;
  wp.axes = cs.axes;
  wp.polar = cs.curvilinear();
}

void cmd_wpoffs(DeckReader& r, const Command& c) {
  WorkingPlane& wp = systems(r).working_plane;
  wp.origin += wp.axes * Vec3(r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0));
}

void cmd_wprota(DeckReader& r, const Command& c) {
  WorkingPlane& wp = systems(r).working_plane;
  wp.axes =
      wp.axes * rotation_from_angles(Vec3(r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0)));
}

void cmd_wpave(DeckReader& r, const Command& c) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int p = 0; p < 3; ++p) {
    const int f = 1 + 3 * p;
    if (c.blank(f) && c.blank(f + 1) && c.blank(f + 2)) continue;
    sum += active_point(r, c, f);
    ++n;
  }
  if (n == 0) r.fail(c, "at least one point is needed");
  systems(r).working_plane.origin = sum / n;
}

/// Rotates the nodal coordinate systems of `ids` into system `kcn` (NROTAT, DSYM).
void rotate_nodes(DeckReader& r, const Command& c, const std::vector<int>& ids, int kcn) {
  const CoordinateSystem system = systems(r).get(kcn);
  // A node on the axis (R = 0) has no radial direction: MAPDL rotates it as at θ = 0 (its
  // NROTAT note only advises against rotating such nodes; vmr049-cr5-185 rotates them and back),
  // so its nodal axes are the system's own axes (axes_at returns them), with a warning.
  std::vector<int> on_axis;
  for (int id : ids) {
    Node& node = r.model.nodes.at(id);
    Mat3 axes;
    if (!system.axes_at(node.x, axes)) on_axis.push_back(id);
    node.angles_deg = clean_angles(angles_from_rotation(axes));
  }
  if (!on_axis.empty())
    r.warn(c, fmt::format("{} node{} on the axis of coordinate system {} (R = 0, first: node {}) "
                          "rotated as at θ = 0: nodal x along the system's X axis",
                          on_axis.size(), on_axis.size() == 1 ? "" : "s", kcn, on_axis.front()));
}

void cmd_nrotat(DeckReader& r, const Command& c) {
  rotate_nodes(r, c, r.node_range(c, 1, 2, 3), systems(r).active);
}

void cmd_dsym(DeckReader& r, const Command& c) {
  // DSYM,Lab,Normal,KCN (MAPDL DSYM): the selected nodes are rotated into system KCN (any earlier
  // rotation redefined), then the displacement DOFs of a symmetry (SYMM) or antisymmetry (ASYM)
  // plane normal to X, Y or Z of KCN (R, θ, Φ in a curvilinear system) are set to zero:
  // SYMM X: UX ROTY ROTZ; Y: UY ROTZ ROTX; Z: UZ ROTX ROTY. ASYM X: UY UZ ROTX; Y: UX UZ ROTY;
  // Z: UX UY ROTZ. DOFs a node does not have are skipped by the solver, as for D.
  const std::string lab = c.blank(1) ? "SYMM" : r.label(c, 1);
  const bool symmetric = lab == "SYMM";
  if (!symmetric && lab != "ASYM" && lab != "ASYMM")
    r.fail(c, fmt::format("Lab '{}': SYMM or ASYM", c.text(1)));
  const std::string normal = c.blank(2) ? "X" : r.label(c, 2);
  if (normal != "X" && normal != "Y" && normal != "Z")
    r.fail(c, fmt::format("Normal '{}': X, Y or Z", c.text(2)));
  const int kcn = r.integer(c, 3, 0);
  if (!systems(r).has(kcn) || kcn == 4)
    r.fail(c, fmt::format("coordinate system {} is not defined", kcn));
  const int axis = normal[0] - 'X';  // 0, 1, 2
  const Dof u[3] = {Dof::UX, Dof::UY, Dof::UZ};
  const Dof rot[3] = {Dof::ROTX, Dof::ROTY, Dof::ROTZ};
  std::vector<Dof> dofs;
  if (symmetric)
    dofs = {u[axis], rot[(axis + 1) % 3], rot[(axis + 2) % 3]};
  else
    dofs = {u[(axis + 1) % 3], u[(axis + 2) % 3], rot[axis]};
  const std::vector<int> ids = require_selected_nodes(r, c);
  rotate_nodes(r, c, ids, kcn);
  LoadStep& s = r.model.current;
  for (int id : ids)
    for (Dof d : dofs) {
      s.constraints[DofKey{id, d}] = 0.0;
      s.constraint_tables.erase(DofKey{id, d});
    }
}

}  // namespace

Vec3 active_point(DeckReader& r, const Command& c, int f) {
  return r.model.coordinate_systems.active_system().to_global(
      Vec3(r.real(c, f, 0.0), r.real(c, f + 1, 0.0), r.real(c, f + 2, 0.0)));
}

void register_csys_commands(std::vector<CommandSpec>& t) {
  t.push_back({"CSYS", cmd_csys, kPrep7 | kSolu | kPost});
  t.push_back({"LOCAL", cmd_local, kPrep7 | kSolu | kPost});
  t.push_back({"CLOCAL", cmd_clocal, kPrep7 | kSolu | kPost});
  t.push_back({"CSDELE", cmd_csdele, kPrep7 | kSolu | kPost});
  t.push_back({"WPCSYS", cmd_wpcsys, kAnywhere});
  t.push_back({"WPOFFS", cmd_wpoffs, kAnywhere});
  t.push_back({"WPROTA", cmd_wprota, kAnywhere});
  t.push_back({"WPAVE", cmd_wpave, kAnywhere});
  t.push_back({"WPSTYL", [](DeckReader& r, const Command& c) { r.ignore(c); }, kAnywhere,
               "working-plane display style: graphics only"});
  t.push_back({"NROTAT", cmd_nrotat, kPrep7 | kSolu});
  t.push_back({"DSYM", cmd_dsym, kPrep7 | kSolu});
}

}  // namespace impactfe::deck
