// Solid-model entities (APDL_MODELING §3): keypoints K, KFILL, KDELE; lines L, LSTR, LARC;
// areas A, AL; volumes V, VA; working-plane primitives RECTNG, BLC4, BLC5, BLOCK, CYL4, CYLIND;
// NUMSTR; listings KLIST, LLIST, ALIST, VLIST; IGESIN (CAD files, /AUX15); and the clear refusals
// of what is not supported (booleans, splines, other primitives).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/log.h"
#include "deck/modeling_helpers.h"
#include "geometry/cad_import.h"
#include "geometry/line_geometry.h"
#include "geometry/solid_builder.h"
#include "geometry/spacing.h"

namespace impactfe::deck {

namespace {

SolidModel& solid(DeckReader& r) {
  return r.model.solid;
}

geometry::SolidBuilder builder(DeckReader& r, const Command& c) {
  return geometry::SolidBuilder(r.model.solid, c.where);
}

CoordinateSystem active(DeckReader& r) {
  return r.model.coordinate_systems.active_system();
}

/// The working plane as a Cartesian system (primitives are built in its x-y coordinates).
CoordinateSystem working_plane(DeckReader& r) {
  const WorkingPlane& wp = r.model.coordinate_systems.working_plane;
  return CoordinateSystem{CsysKind::Cartesian, wp.origin, wp.axes};
}

void cmd_k(DeckReader& r, const Command& c) {
  const int id = r.integer(c, 1, 0);
  if (id < 0) r.fail(c, fmt::format("keypoint number {} must be positive", id));
  builder(r, c).keypoint(id, active_point(r, c, 2));
}

void cmd_kfill(DeckReader& r, const Command& c) {
  // KFILL,NP1,NP2,NFILL,NSTRT,NINC,SPACE
  const auto& kps = solid(r).keypoints;
  int np1 = 0, np2 = 0;
  if (c.blank(1) || c.blank(2)) {
    if (kps.size() < 2) r.fail(c, "KFILL needs two keypoints: fewer than two are defined");
    np2 = kps.rbegin()->first;
    np1 = std::next(kps.rbegin())->first;
  }
  np1 = r.integer(c, 1, np1);
  np2 = r.integer(c, 2, np2);
  for (int k : {np1, np2})
    if (kps.count(k) == 0) r.fail(c, fmt::format("keypoint {} is not defined", k));
  const int nfill = r.integer(c, 3, std::abs(np2 - np1) - 1);
  if (nfill <= 0)
    r.fail(c, fmt::format("no keypoint to fill between {} and {} (NFILL {})", np1, np2, nfill));
  int ninc_default = (np2 - np1) / (nfill + 1);
  if (ninc_default == 0) ninc_default = 1;
  const int ninc = r.integer(c, 5, ninc_default);
  const int nstrt = r.integer(c, 4, np1 + ninc);
  const double space = r.real(c, 6, 1.0);
  const Vec3 a = kps.at(np1).x, b = kps.at(np2).x;
  const CoordinateSystem cs = active(r);
  const std::vector<double> f = geometry::division_fractions(nfill + 1, space);
  for (int k = 0; k < nfill; ++k) {
    const int id = nstrt + k * ninc;
    if (id <= 0) r.fail(c, fmt::format("generated keypoint number {} is not positive", id));
    builder(r, c).keypoint(
        id, geometry::interpolate_in_system(cs, a, b, f[static_cast<std::size_t>(k + 1)]));
  }
}

void cmd_kdele(DeckReader& r, const Command& c) {
  for (int id :
       entity_list(r, c, 1, 2, 3, solid(r).keypoints, r.model.selection.keypoints, "keypoint")) {
    for (const auto& [lid, line] : solid(r).lines)
      if (line.kp1 == id || line.kp2 == id)
        r.fail(c, fmt::format("keypoint {} is used by line {} and cannot be deleted", id, lid));
    if (solid(r).keypoints.at(id).node != 0)
      r.fail(c, fmt::format("keypoint {} is meshed (KCLEAR first)", id));
    solid(r).keypoints.erase(id);
    r.model.selection.keypoints.forget(id);
  }
}

void cmd_l(DeckReader& r, const Command& c) {
  // L,P1,P2,NDIV,SPACE,XV1,YV1,ZV1,XV2,YV2,ZV2
  for (int f = 5; f <= 11; ++f)
    if (!c.blank(f)) r.fail(c, "slope vectors (XV1..ZV2) are not supported");
  const int p1 = r.integer(c, 1, 0), p2 = r.integer(c, 2, 0);
  const int id = builder(r, c).line(p1, p2, active(r));
  Line& line = solid(r).lines.at(id);
  const int ndiv = r.integer(c, 3, 0);
  if (ndiv < 0) r.fail(c, fmt::format("NDIV {} must not be negative", ndiv));
  line.ndiv = ndiv;
  line.space = r.real(c, 4, 1.0);
  if (line.space == 0.0) line.space = 1.0;
}

void cmd_lstr(DeckReader& r, const Command& c) {
  builder(r, c).line(r.integer(c, 1, 0), r.integer(c, 2, 0), CoordinateSystem{});
}

void cmd_larc(DeckReader& r, const Command& c) {
  // LARC,P1,P2,PC,RAD
  const auto& kps = solid(r).keypoints;
  const int p1 = r.integer(c, 1, 0), p2 = r.integer(c, 2, 0), pc = r.integer(c, 3, 0);
  for (int k : {p1, p2, pc})
    if (kps.count(k) == 0) r.fail(c, fmt::format("keypoint {} is not defined", k));
  const Vec3 a = kps.at(p1).x, b = kps.at(p2).x, x = kps.at(pc).x;
  Vec3 normal = (b - a).cross(x - a);
  const double chord = (b - a).norm();
  if (normal.norm() <= 1e-12 * chord * chord)
    r.fail(c, fmt::format("keypoints {}, {} and {} are collinear: the arc plane is undefined", p1,
                          p2, pc));
  normal.normalize();
  Vec3 centre;
  double sweep = 0.0;
  const auto rad = r.opt_real(c, 4);
  if (!rad || *rad == 0.0) {
    // Circle through P1, PC, P2 (circumcentre); the arc runs from P1 through PC to P2.
    const Vec3 u = x - a, v = b - a;
    const Vec3 w = u.cross(v);
    centre =
        a + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w.squaredNorm());
  } else {
    // Centre on PC's side of the chord (RAD > 0) or the other side (RAD < 0); minor arc.
    if (std::fabs(*rad) < 0.5 * chord * (1 - 1e-12))
      r.fail(c, fmt::format("radius {} is smaller than half the chord {}", *rad, 0.5 * chord));
    const Vec3 mid = 0.5 * (a + b);
    Vec3 side = normal.cross(b - a).normalized();
    if (side.dot(x - mid) < 0.0) side = -side;
    const double h = std::sqrt(std::max(0.0, *rad * *rad - 0.25 * chord * chord));
    centre = mid + (*rad > 0 ? h : -h) * side;
  }
  // Sweep angle about `normal` from P1 to P2, choosing the way through PC (3-point form) or the
  // minor arc (radius form).
  auto angle_of = [&](const Vec3& p) {
    const Vec3 e1 = (a - centre).normalized();
    const Vec3 e2 = normal.cross(e1);
    double t = std::atan2((p - centre).dot(e2), (p - centre).dot(e1)) * 180.0 / M_PI;
    if (t < 0.0) t += 360.0;
    return t;
  };
  const double tb = angle_of(b);
  if (!rad || *rad == 0.0) {
    const double tc = angle_of(x);
    sweep = tc < tb ? tb : tb - 360.0;
  } else {
    sweep = tb <= 180.0 ? tb : tb - 360.0;
  }
  builder(r, c).arc(p1, p2, centre, normal, sweep);
}

std::vector<int> integer_fields(DeckReader& r, const Command& c, int first, int last) {
  std::vector<int> out;
  for (int f = first; f <= std::min(last, c.last_given()); ++f)
    if (!c.blank(f)) out.push_back(r.integer(c, f, 0));
  return out;
}

void cmd_a(DeckReader& r, const Command& c) {
  const std::vector<int> kps = integer_fields(r, c, 1, 18);
  builder(r, c).area_from_keypoints(kps, active(r));
}

void cmd_al(DeckReader& r, const Command& c) {
  std::vector<int> lines;
  if (r.label(c, 1) == "ALL") {
    lines = selected_ids(solid(r).lines, r.model.selection.lines);
    if (lines.empty()) r.fail(c, "ALL: no line is selected");
    if (!c.blank(2)) {
      const int first = r.integer(c, 2, 0);
      const auto it = std::find(lines.begin(), lines.end(), std::abs(first));
      if (it == lines.end()) r.fail(c, fmt::format("line {} is not selected", std::abs(first)));
      lines.erase(it);
      lines.insert(lines.begin(), first);
    }
  } else {
    lines = integer_fields(r, c, 1, 10);
  }
  builder(r, c).area_from_lines(lines);
}

void cmd_v(DeckReader& r, const Command& c) {
  std::vector<int> kps = integer_fields(r, c, 1, 8);
  if (kps.size() < 4) r.fail(c, fmt::format("V needs at least 4 keypoints, {} given", kps.size()));
  // Fewer than 8: degenerate forms (4: tetrahedron P1 P2 P3 P3 P4 P4 P4 P4, 6: prism).
  if (kps.size() == 4) kps = {kps[0], kps[1], kps[2], kps[2], kps[3], kps[3], kps[3], kps[3]};
  if (kps.size() == 6) kps = {kps[0], kps[1], kps[2], kps[2], kps[3], kps[4], kps[5], kps[5]};
  if (kps.size() != 8) r.fail(c, "V takes 4, 6 or 8 keypoints");
  builder(r, c).volume_from_keypoints(kps, active(r));
}

void cmd_va(DeckReader& r, const Command& c) {
  std::vector<int> areas;
  if (r.label(c, 1) == "ALL") {
    areas = selected_ids(solid(r).areas, r.model.selection.areas);
  } else {
    areas = integer_fields(r, c, 1, 10);
  }
  builder(r, c).volume_from_areas(areas);
}

void cmd_rectng(DeckReader& r, const Command& c) {
  builder(r, c).rectangle(working_plane(r), r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0),
                          r.real(c, 4, 0.0));
}

void cmd_blc(DeckReader& r, const Command& c) {
  // BLC4,XCORNER,YCORNER,WIDTH,HEIGHT,DEPTH / BLC5,XCENTER,YCENTER,WIDTH,HEIGHT,DEPTH
  double x = r.real(c, 1, 0.0), y = r.real(c, 2, 0.0);
  const double w = r.real(c, 3, 0.0), h = r.real(c, 4, 0.0), d = r.real(c, 5, 0.0);
  if (c.name == "BLC5") {
    x -= 0.5 * w;
    y -= 0.5 * h;
  }
  if (d == 0.0)
    builder(r, c).rectangle(working_plane(r), x, x + w, y, y + h);
  else
    builder(r, c).block(working_plane(r), x, x + w, y, y + h, 0.0, d);
}

void cmd_block(DeckReader& r, const Command& c) {
  builder(r, c).block(working_plane(r), r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0),
                      r.real(c, 4, 0.0), r.real(c, 5, 0.0), r.real(c, 6, 0.0));
}

void cmd_cyl4(DeckReader& r, const Command& c) {
  // CYL4,XCENTER,YCENTER,RAD1,THETA1,RAD2,THETA2,DEPTH
  const double t1 = r.real(c, 4, 0.0), t2 = r.real(c, 6, 360.0);
  const double depth = r.real(c, 7, 0.0);
  builder(r, c).cylinder(working_plane(r), r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0),
                         r.real(c, 5, 0.0), t1, t2, std::min(0.0, depth), std::max(0.0, depth));
}

void cmd_pcirc(DeckReader& r, const Command& c) {
  // PCIRC,RAD1,RAD2,THETA1,THETA2: a circular area (a sector, an annular sector) about the
  // working plane origin, as CYL4 without depth; RAD1, RAD2 in either order, blank or equal
  // radii a solid circle.
  builder(r, c).cylinder(working_plane(r), 0.0, 0.0, r.real(c, 1, 0.0), r.real(c, 2, 0.0),
                         r.real(c, 3, 0.0), r.real(c, 4, 360.0), 0.0, 0.0);
}

void cmd_cylind(DeckReader& r, const Command& c) {
  // CYLIND,RAD1,RAD2,Z1,Z2,THETA1,THETA2
  const double z1 = r.real(c, 3, 0.0), z2 = r.real(c, 4, 0.0);
  if (z1 == z2) r.fail(c, "Z1 = Z2: zero-height cylinder");
  builder(r, c).cylinder(working_plane(r), 0.0, 0.0, r.real(c, 1, 0.0), r.real(c, 2, 0.0),
                         r.real(c, 5, 0.0), r.real(c, 6, 360.0), z1, z2);
}

void cmd_numstr(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  NumberingStart& n = solid(r).numstr;
  if (l == "DEFA") {
    n = NumberingStart{};
    return;
  }
  const int value = r.integer(c, 2, 0);
  if (value < 0) r.fail(c, fmt::format("VALUE {} must not be negative", value));
  if (l == "NODE")
    n.node = value;
  else if (l == "ELEM")
    n.elem = value;
  else if (l == "KP")
    n.kp = std::max(1, value);
  else if (l == "LINE")
    n.line = std::max(1, value);
  else if (l == "AREA")
    n.area = std::max(1, value);
  else if (l == "VOLU")
    n.volu = std::max(1, value);
  else
    r.fail(c, fmt::format("bad label '{}' (NODE, ELEM, KP, LINE, AREA, VOLU, DEFA)", c.text(1)));
}

std::string attributes_text(const EntityAttributes& a) {
  return fmt::format("MAT {} REAL {} TYPE {} ESYS {} SECN {}", a.mat, a.real, a.type, a.esys,
                     a.secnum);
}

void cmd_list(DeckReader& r, const Command& c) {
  const SolidModel& s = r.model.solid;
  const ModelSelection& sel = r.model.selection;
  std::string out = fmt::format("{} listing (selected entities):", c.name);
  if (c.name == "KLIST") {
    for (const auto& [id, k] : s.keypoints)
      if (sel.keypoints.selected(id))
        out += fmt::format("\n  KP {:6d}  X {:14.6g} Y {:14.6g} Z {:14.6g}  node {}  {}", id,
                           k.x(0), k.x(1), k.x(2), k.node, attributes_text(k.attr));
  } else if (c.name == "LLIST") {
    for (const auto& [id, l] : s.lines)
      if (sel.lines.selected(id))
        out += fmt::format(
            "\n  LINE {:6d}  KP {} → {}  length {:.6g}  NDIV {}  nodes {}  elements "
            "{}  {}",
            id, l.kp1, l.kp2, geometry::line_length(l), l.ndiv, l.nodes.size(), l.elements.size(),
            attributes_text(l.attr));
  } else if (c.name == "ALIST") {
    for (const auto& [id, a] : s.areas)
      if (sel.areas.selected(id))
        out += fmt::format("\n  AREA {:6d}  lines {}  nodes {}  elements {}  {}", id,
                           fmt::join(a.lines, " "), a.grid.nodes.size(), a.elements.size(),
                           attributes_text(a.attr));
  } else {
    for (const auto& [id, v] : s.volumes)
      if (sel.volumes.selected(id))
        out += fmt::format("\n  VOLU {:6d}  areas {}  elements {}  {}", id, fmt::join(v.areas, " "),
                           v.elements.size(), attributes_text(v.attr));
  }
  Log::info("{}:{}: {}", c.where.file, c.where.line, out);
}

/// Commands recognised but not supported, with the reason given in the error.
const std::map<std::string, std::string>& refusal_reasons() {
  static const std::map<std::string, std::string> reasons = {
      {"VOVLAP", "boolean operations are not supported"},
      {"AOVLAP", "boolean operations are not supported"},
      {"VADD", "boolean operations are not supported"},
      {"AADD", "boolean operations are not supported"},
      {"VSBV", "boolean operations are not supported"},
      {"VSBA", "boolean operations are not supported"},
      {"ASBA", "boolean operations are not supported"},
      {"ASBV", "boolean operations are not supported"},
      {"VDELE", "deleting volumes is not supported"},
      {"ADELE", "deleting areas is not supported"},
      {"LDELE", "deleting lines is not supported"},
      {"VDIV", "boolean operations are not supported"},
      {"ADIV", "boolean operations are not supported"},
      {"LDIV", "dividing lines is not supported"},
      {"LCOMB", "combining lines is not supported"},
      {"LFILLT", "fillets are not supported"},
      {"CIRCLE", "CIRCLE is not supported; use LARC or CYL4"},
      {"BSPLIN", "splines are not supported"},
      {"SPLINE", "splines are not supported"},
      {"CON4", "cones are not supported (not a primitive here)"},
      {"CONE", "cones are not supported (not a primitive here)"},
      {"TORUS", "tori are not supported"},
      {"POLYGON", "polygons are not supported (not a primitive here)"},
      {"RPRISM", "regular prisms are not supported (not a primitive here)"},
      {"PRISM", "PRISM is not supported (not a primitive here)"},
      {"SPHERE", "spheres are not supported (their surface has no edges to bound areas)"},
      {"LCCAT", "concatenated lines (LCCAT) are not supported"},
      {"AMAP", "AMAP is not supported; mapped meshing needs 3- or 4-sided areas"},
      {"CS", "CS (system by three nodes) is not supported; use LOCAL or CLOCAL"},
      {"CSKP", "CSKP (system by three keypoints) is not supported; use LOCAL or CLOCAL"},
      {"KWPAVE", "KWPAVE is not supported; use WPAVE"},
      {"NWPAVE", "NWPAVE is not supported; use WPAVE"},
  };
  return reasons;
}

// IGESIN,Fname,Ext: the IGES (or STEP) file's geometry into the solid model through Gmsh's
// OpenCASCADE importer (geometry/cad_import.h); Fname defaults to the jobname, Ext to "iges".
// MAPDL reads IGES in /AUX15; here IGESIN is a /PREP7 command and /AUX15 enters /PREP7.
void cmd_igesin(DeckReader& r, const Command& c) {
  std::string name = r.text_field(c, 1), ext = r.text_field(c, 2);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "iges";
  if (!c.blank(3)) r.warn(c, "field 3 of IGESIN is not used; ignored");
  const std::string path = resolve_input(c.where.file, name, ext);
  const auto n = geometry::import_cad(r.model, path, c.where);
  Log::info("{}:{}: IGESIN: {} keypoints, {} lines, {} areas, {} volumes from {}", c.where.file,
            c.where.line, n.keypoints, n.lines, n.areas, n.volumes, path);
}

void cmd_aux15(DeckReader& r, const Command&) {
  r.processor = kPrep7;
}

void cmd_ioptn(DeckReader& r, const Command& c) {
  r.warn(c, "IOPTN: import options have no effect (the file's geometry is read as it is)");
}

/// A command recognised but not supported: a clear error naming the command.
void cmd_refused_solid_model(DeckReader& r, const Command& c) {
  r.fail(c, refusal_reasons().at(c.name));
}

}  // namespace

void register_solid_model_commands(std::vector<CommandSpec>& t) {
  t.push_back({"/AUX15", cmd_aux15, kBegin | kPrep7 | kSolu | kPost});
  t.push_back({"IGESIN", cmd_igesin, kPrep7});
  t.push_back({"IOPTN", cmd_ioptn, kPrep7});
  t.push_back({"K", cmd_k, kPrep7});
  t.push_back({"KFILL", cmd_kfill, kPrep7});
  t.push_back({"KDELE", cmd_kdele, kPrep7});
  t.push_back({"L", cmd_l, kPrep7});
  t.push_back({"LSTR", cmd_lstr, kPrep7});
  t.push_back({"LARC", cmd_larc, kPrep7});
  t.push_back({"A", cmd_a, kPrep7});
  t.push_back({"AL", cmd_al, kPrep7});
  t.push_back({"V", cmd_v, kPrep7});
  t.push_back({"VA", cmd_va, kPrep7});
  t.push_back({"RECTNG", cmd_rectng, kPrep7});
  t.push_back({"BLC4", cmd_blc, kPrep7});
  t.push_back({"BLC5", cmd_blc, kPrep7});
  t.push_back({"BLOCK", cmd_block, kPrep7});
  t.push_back({"CYL4", cmd_cyl4, kPrep7});
  t.push_back({"PCIRC", cmd_pcirc, kPrep7});
  t.push_back({"CYLIND", cmd_cylind, kPrep7});
  t.push_back({"NUMSTR", cmd_numstr, kPrep7});
  for (const char* name : {"KLIST", "LLIST", "ALIST", "VLIST"})
    t.push_back({name, cmd_list, kAnywhere});
  for (const auto& entry : refusal_reasons())
    t.push_back({entry.first.c_str(), cmd_refused_solid_model, kAnywhere});
}

}  // namespace impactfe::deck
