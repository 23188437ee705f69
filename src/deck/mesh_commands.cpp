// Meshing commands (APDL_MODELING §4): size controls ESIZE, LESIZE, KESIZE, AESIZE, DESIZE
// (SMRTSIZE, MOPT accepted and ignored with a note), MSHAPE, MSHKEY, attributes KATT, LATT,
// AATT, VATT, ESYS, the mesh commands KMESH, LMESH, AMESH, VMESH, VSWEEP, EXTOPT, VEXT, VROTAT
// and KCLEAR, LCLEAR, ACLEAR, VCLEAR.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "deck/modeling_helpers.h"
#include "geometry/mesh_quality.h"
#include "geometry/solid_sweep.h"

namespace impactfe::deck {

namespace {

SolidModel& solid(DeckReader& r) {
  return r.model.solid;
}

/// A size field: blank → nullopt; zero → nullopt; negative → error.
std::optional<double> size_field(DeckReader& r, const Command& c, int f, const char* what) {
  const auto v = r.opt_real(c, f);
  if (!v || *v == 0.0) return std::nullopt;
  if (*v < 0.0) r.fail(c, fmt::format("{} {} must be positive", what, *v));
  return v;
}

void cmd_esize(DeckReader& r, const Command& c) {
  MeshControls& m = solid(r).mesh;
  const auto v = r.opt_real(c, 1);
  const auto ndiv = r.opt_int(c, 2);
  if (v && *v < 0.0) r.fail(c, fmt::format("element size {} must be positive", *v));
  if (ndiv && *ndiv < 0) r.fail(c, fmt::format("NDIV {} must not be negative", *ndiv));
  if ((!v || *v == 0.0) && (!ndiv || *ndiv == 0)) {
    // ESIZE alone, or with SIZE and NDIV blank (fields beyond NDIV are none of ESIZE's, as
    // ESIZ,,,2): back to the defaults. A zero given explicitly is a size of zero: refused.
    if (c.blank(1) && c.blank(2)) {
      if (c.last_given() > 2)
        r.warn(c, fmt::format("field {} is not a field of ESIZE (SIZE, NDIV): ignored",
                              c.last_given()));
      m.esize = 0.0;
      m.esize_ndiv = 0;
      return;
    }
    r.fail(c, "element size must be positive (or give NDIV > 0)");
  }
  m.esize = v.value_or(0.0);
  m.esize_ndiv = ndiv.value_or(0);
}

void cmd_lesize(DeckReader& r, const Command& c) {
  // LESIZE,NL1,SIZE,ANGSIZ,NDIV,SPACE,KFORC,LAYER1,LAYER2,KYNDIV
  const bool all = r.label(c, 1) == "ALL";
  const auto lines = entity_list(r, c, 1, 0, 0, solid(r).lines, r.model.selection.lines, "line");
  const auto size = size_field(r, c, 2, "SIZE");
  const auto angle = size_field(r, c, 3, "ANGSIZ");
  const auto ndiv = r.opt_int(c, 4);
  if (ndiv && *ndiv < 0) r.fail(c, fmt::format("NDIV {} must not be negative", *ndiv));
  const auto space = r.opt_real(c, 5);
  const int kforc = r.integer(c, 6, all ? 0 : 1);
  if (kforc < 0 || kforc > 4) r.fail(c, fmt::format("KFORC {} must be 0..4", kforc));
  for (int f = 7; f <= 9; ++f)
    if (!c.blank(f)) r.warn(c, "LAYER1/LAYER2/KYNDIV ignored (no layer meshing)");
  if (!size && !angle && (!ndiv || *ndiv == 0) && kforc != 4 && !space)
    r.fail(c, "give SIZE, ANGSIZ or NDIV (all are blank or zero)");
  for (int id : lines) {
    Line& l = solid(r).lines.at(id);
    const bool has = l.ndiv > 0 || l.size || l.angle;
    const int current = l.ndiv;
    const int wanted = ndiv.value_or(0);
    if (kforc == 0 && has) continue;
    if (kforc == 2 && !(wanted > 0 && current > 0 && current < wanted)) continue;
    if (kforc == 3 && !(wanted > 0 && current > wanted)) continue;
    if (!l.nodes.empty())
      r.warn(c, fmt::format("line {} is already meshed: the new size applies after it is cleared",
                            id));
    if (kforc == 4) {
      if (size) l.size = size, l.ndiv = 0;
      if (angle) l.angle = angle;
      if (ndiv && *ndiv > 0) l.ndiv = *ndiv;
      if (space && *space != 0.0) l.space = *space;
      continue;
    }
    l.ndiv = ndiv.value_or(0);
    l.size = size;
    l.angle = angle;
    l.space = space && *space != 0.0 ? *space : 1.0;
  }
}

void cmd_kesize(DeckReader& r, const Command& c) {
  const auto kps =
      entity_list(r, c, 1, 0, 0, solid(r).keypoints, r.model.selection.keypoints, "keypoint");
  const auto size = r.opt_real(c, 2);
  if (!size || *size <= 0.0) r.fail(c, "SIZE must be positive");
  if (!c.blank(3) || !c.blank(4)) r.fail(c, "FACT1/FACT2 (size factors) are not supported");
  for (int k : kps) solid(r).keypoints.at(k).size = *size;
}

void cmd_aesize(DeckReader& r, const Command& c) {
  const auto areas = entity_list(r, c, 1, 0, 0, solid(r).areas, r.model.selection.areas, "area");
  const auto size = r.opt_real(c, 2);
  if (!size || *size <= 0.0) r.fail(c, "SIZE must be positive");
  for (int a : areas) solid(r).areas.at(a).size = *size;
}

void cmd_desize(DeckReader& r, const Command& c) {
  MeshControls::Desize& d = solid(r).mesh.desize;
  const std::string l = r.label(c, 1);
  if (l == "DEFA") {
    d = MeshControls::Desize{};
    return;
  }
  if (l == "STAT" || l == "ON" || l == "OFF") {
    Log::info("{}:{}: DESIZE,{}: MINL {} MINH {} MXEL {} ANGL {} ANGH {}", c.where.file,
              c.where.line, l, d.minl, d.minh, d.mxel, d.angl, d.angh);
    return;
  }
  d.minl = r.integer(c, 1, d.minl);
  d.minh = r.integer(c, 2, d.minh);
  d.mxel = r.integer(c, 3, d.mxel);
  d.angl = r.real(c, 4, d.angl);
  d.angh = r.real(c, 5, d.angh);
  if (d.minl < 1 || d.mxel < d.minl || d.angl <= 0.0)
    r.fail(c, "bad DESIZE values (MINL ≥ 1, MXEL ≥ MINL, ANGL > 0)");
  for (int f = 6; f <= 9; ++f)
    if (!c.blank(f)) r.warn(c, "EDGMN/EDGMX/ADJF/ADJM ignored");
}

void cmd_smrtsize(DeckReader& r, const Command& c) {
  // OFF (the default state) is what impactfe always does; STAT only lists.
  const std::string l = r.label(c, 1);
  if (l == "OFF" || l == "STAT") return;
  r.warn(c, "SmartSizing is not implemented; the DESIZE defaults are used");
}

void cmd_mopt(DeckReader& r, const Command& c) {
  r.warn(c, "mesher options have no effect on impactfe's mapped mesher; ignored");
}

void cmd_mshape(DeckReader& r, const Command& c) {
  const int key = r.integer(c, 1, 0);
  if (key != 0 && key != 1)
    r.fail(c, fmt::format("KEY {} must be 0 (quad/hex) or 1 (tri/tet)", key));
  const std::string dim = r.label(c, 2);
  MeshControls& m = solid(r).mesh;
  if (dim.empty() || dim == "2D") m.shape_2d = key;
  if (dim.empty() || dim == "3D") m.shape_3d = key;
  if (!dim.empty() && dim != "2D" && dim != "3D")
    r.fail(c, fmt::format("bad dimension '{}' (2D, 3D)", c.text(2)));
}

void cmd_mshkey(DeckReader& r, const Command& c) {
  const int key = r.integer(c, 1, 0);
  if (key < 0 || key > 2) r.fail(c, fmt::format("KEY {} must be 0, 1 or 2", key));
  solid(r).mesh.key = key;
}

/// Attribute field: blank/0 → 0 (no association), −1 → unchanged, else the value.
void set_attribute(DeckReader& r, const Command& c, int f, int& target) {
  const int v = r.integer(c, f, 0);
  if (v == -1) return;
  if (v < -1) r.fail(c, fmt::format("field {}: attribute {} must not be negative", f, v));
  target = v;
}

template <class Map>
void assign_attributes(DeckReader& r, const Command& c, Map& map, const Selection& sel,
                       const char* what, const std::array<int, 5>& fields) {
  int skipped = 0;
  for (auto& [id, entity] : map) {
    if (!sel.selected(id)) continue;
    if (!entity.elements.empty()) {
      ++skipped;
      continue;
    }
    EntityAttributes& a = entity.attr;
    int* targets[5] = {&a.mat, &a.real, &a.type, &a.esys, &a.secnum};
    for (int k = 0; k < 5; ++k)
      if (fields[static_cast<std::size_t>(k)] > 0)
        set_attribute(r, c, fields[static_cast<std::size_t>(k)], *targets[k]);
  }
  if (skipped > 0)
    r.warn(c,
           fmt::format("{} meshed {}(s) keep their attributes (clear them first)", skipped, what));
}

}  // namespace

void check_esys_number(DeckReader& r, const Command& c, int kcn) {
  if (kcn != 0 && kcn <= 10)
    r.fail(c, fmt::format("ESYS {}: an element coordinate system is 0 (the element's own axes) "
                          "or a local system above 10 (LOCAL defines one parallel to a global "
                          "system)",
                          kcn));
}

namespace {

void check_esys_field(DeckReader& r, const Command& c, int f) {
  check_esys_number(r, c, r.integer(c, f, 0));
}

void cmd_katt(DeckReader& r, const Command& c) {
  check_esys_field(r, c, 4);
  assign_attributes(r, c, solid(r).keypoints, r.model.selection.keypoints, "keypoint",
                    {1, 2, 3, 4, 0});
}

void cmd_latt(DeckReader& r, const Command& c) {
  // LATT,MAT,REAL,TYPE,--,KB,KE,SECNUM
  assign_attributes(r, c, solid(r).lines, r.model.selection.lines, "line", {1, 2, 3, 0, 7});
  const int kb = r.integer(c, 5, 0), ke = r.integer(c, 6, 0);
  for (int k : {kb, ke})
    if (k > 0 && solid(r).keypoints.count(k) == 0)
      r.fail(c, fmt::format("orientation keypoint {} is not defined", k));
  for (auto& [id, line] : solid(r).lines)
    if (r.model.selection.lines.selected(id) && line.elements.empty()) {
      line.orientation_kb = kb;
      line.orientation_ke = ke;
    }
}

void cmd_aatt(DeckReader& r, const Command& c) {
  check_esys_field(r, c, 4);
  assign_attributes(r, c, solid(r).areas, r.model.selection.areas, "area", {1, 2, 3, 4, 5});
}

void cmd_vatt(DeckReader& r, const Command& c) {
  check_esys_field(r, c, 4);
  assign_attributes(r, c, solid(r).volumes, r.model.selection.volumes, "volume", {1, 2, 3, 4, 5});
}

void cmd_esys(DeckReader& r, const Command& c) {
  // ESYS,KCN: the element coordinate system of the elements defined next (E, meshing).
  const int kcn = r.integer(c, 1, 0);
  check_esys_number(r, c, kcn);
  r.modeling.esys = kcn;
}

template <class Map>
std::vector<int> mesh_targets(DeckReader& r, const Command& c, const Map& map, const Selection& sel,
                              const char* what) {
  return entity_list(r, c, 1, 2, 3, map, sel, what);
}

void cmd_kmesh(DeckReader& r, const Command& c) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  for (int id : mesh_targets(r, c, solid(r).keypoints, r.model.selection.keypoints, "keypoint"))
    mesher.mesh_keypoint(id);
  record_created_elements(r, mesher);
}

void cmd_lmesh(DeckReader& r, const Command& c) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  for (int id : mesh_targets(r, c, solid(r).lines, r.model.selection.lines, "line"))
    mesher.mesh_line(id);
  record_created_elements(r, mesher);
}

/// The shapes of the elements a meshing command made (geometry/mesh_quality.h): one line in the
/// log, and a warning naming the first element past the limits (inverted ones first).
void report_mesh_quality(DeckReader& r, const Command& c, const geometry::Mesher& mesher) {
  const geometry::MeshQuality q = geometry::mesh_quality(r.model, mesher.created_elements());
  if (q.measured == 0) return;
  Log::info("{}:{}: {}: {}", c.where.file, c.where.line, c.name, geometry::describe(q));
  if (q.inverted > 0)
    r.warn(c, fmt::format("{} inverted or flat element(s) (scaled Jacobian <= 0 or a folded "
                          "quadratic map), the first element {}: an element refuses them or "
                          "computes them wrongly; check the geometry and the line divisions",
                          q.inverted, q.first_inverted));
  else if (q.past_limits > 0)
    r.warn(c,
           fmt::format("{} element(s) past the shape limits (edge ratio > {}, scaled Jacobian "
                       "< {} or Jacobian ratio > {}), the first element {}",
                       q.past_limits, geometry::kEdgeRatioWarning, geometry::kScaledJacobianWarning,
                       geometry::kJacobianRatioWarning, q.first_past_limits));
}

void cmd_amesh(DeckReader& r, const Command& c) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  for (int id : mesh_targets(r, c, solid(r).areas, r.model.selection.areas, "area"))
    mesher.mesh_area(id);
  record_created_elements(r, mesher);
  report_mesh_quality(r, c, mesher);
}

void cmd_vmesh(DeckReader& r, const Command& c) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  for (int id : mesh_targets(r, c, solid(r).volumes, r.model.selection.volumes, "volume"))
    mesher.mesh_volume(id);
  record_created_elements(r, mesher);
  report_mesh_quality(r, c, mesher);
}

void cmd_vsweep(DeckReader& r, const Command& c) {
  // VSWEEP,VNUM,SRCA,TRGA,LSMO
  const auto volumes =
      entity_list(r, c, 1, 0, 0, solid(r).volumes, r.model.selection.volumes, "volume");
  const int source = r.integer(c, 2, 0), target = r.integer(c, 3, 0);
  for (int a : {source, target})
    if (a != 0 && solid(r).areas.count(a) == 0) r.fail(c, fmt::format("area {} is not defined", a));
  if (!c.blank(4)) r.warn(c, "LSMO (line smoothing) ignored");
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  for (int id : volumes) mesher.mesh_volume(id, source, target);
  record_created_elements(r, mesher);
  report_mesh_quality(r, c, mesher);
}

void cmd_clear(DeckReader& r, const Command& c) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  const ModelSelection& sel = r.model.selection;
  if (c.name == "KCLEAR") {
    for (int id : entity_list(r, c, 1, 2, 3, solid(r).keypoints, sel.keypoints, "keypoint"))
      mesher.clear_keypoint(id);
  } else if (c.name == "LCLEAR") {
    for (int id : entity_list(r, c, 1, 2, 3, solid(r).lines, sel.lines, "line"))
      mesher.clear_line(id);
  } else if (c.name == "ACLEAR") {
    for (int id : entity_list(r, c, 1, 2, 3, solid(r).areas, sel.areas, "area"))
      mesher.clear_area(id);
  } else {
    for (int id : entity_list(r, c, 1, 2, 3, solid(r).volumes, sel.volumes, "volume"))
      mesher.clear_volume(id);
  }
}

void cmd_extopt(DeckReader& r, const Command& c) {
  MeshControls::Extopt& e = solid(r).mesh.extopt;
  const std::string l = r.label(c, 1);
  if (l == "ON") {
    e.on = true;
  } else if (l == "OFF" || l == "DEFA") {
    e = MeshControls::Extopt{};
  } else if (l == "STAT") {
    Log::info("{}:{}: EXTOPT: {} NDIV {} SPACE {} ACLEAR {}", c.where.file, c.where.line,
              e.on ? "ON" : "OFF", e.ndiv, e.space, e.aclear ? 1 : 0);
  } else if (l == "ATTR") {
    for (int k = 0; k < 3; ++k) {
      const int v = r.integer(c, 2 + k, 0);
      if (v != 0 && v != 1) r.fail(c, fmt::format("ATTR value {} must be 0 or 1", v));
      e.attr[static_cast<std::size_t>(k)] = v;
    }
  } else if (l == "ESIZE") {
    const int n = r.integer(c, 2, 0);
    if (n < 0) r.fail(c, fmt::format("NDIV {} must not be negative", n));
    e.ndiv = n;
    e.space = r.real(c, 3, 1.0);
    if (e.space == 0.0) e.space = 1.0;
  } else if (l == "ACLEAR") {
    e.aclear = r.integer(c, 2, 0) == 1;
  } else if (l == "VSWE") {
    r.warn(c, "VSWE options ignored (the sweep mesher has no options)");
  } else {
    r.fail(c, fmt::format("bad label '{}' (ON, OFF, STAT, DEFA, ATTR, ESIZE, ACLEAR, VSWE)",
                          c.text(1)));
  }
}

void mesh_swept(DeckReader& r, const Command& c, const std::vector<geometry::SweptVolume>& made) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  geometry::mesh_swept_volumes(mesher, r.model.solid, made);
  record_created_elements(r, mesher);
}

void cmd_vext(DeckReader& r, const Command& c) {
  // VEXT,NA1,NA2,NINC,DX,DY,DZ,RX,RY,RZ
  const auto areas = entity_list(r, c, 1, 2, 3, solid(r).areas, r.model.selection.areas, "area");
  for (int f = 7; f <= 9; ++f) {
    const double v = r.real(c, f, 1.0);
    if (v != 0.0 && v != 1.0) r.fail(c, "scale factors RX, RY, RZ are not supported");
  }
  const CoordinateSystem active = r.model.coordinate_systems.active_system();
  if (active.curvilinear())
    r.fail(c, "VEXT in a curvilinear coordinate system is not supported (use CSYS,0 or VROTAT)");
  const Vec3 d = active.axes * Vec3(r.real(c, 4, 0.0), r.real(c, 5, 0.0), r.real(c, 6, 0.0));
  if (d.norm() == 0.0) r.fail(c, "zero extrusion (DX = DY = DZ = 0)");
  mesh_swept(r, c, geometry::extrude_areas(r.model.solid, areas, d, c.where));
}

void cmd_vrotat(DeckReader& r, const Command& c) {
  // VROTAT,NA1,NA2,NA3,NA4,NA5,NA6,PAX1,PAX2,ARC,NSEG
  std::vector<int> areas;
  if (r.label(c, 1) == "ALL") {
    areas = selected_ids(solid(r).areas, r.model.selection.areas);
  } else {
    for (int f = 1; f <= 6; ++f)
      if (!c.blank(f)) {
        const int a = r.integer(c, f, 0);
        if (solid(r).areas.count(a) == 0) r.fail(c, fmt::format("area {} is not defined", a));
        areas.push_back(a);
      }
  }
  if (areas.empty()) r.fail(c, "no area to rotate");
  const int p1 = r.integer(c, 7, 0), p2 = r.integer(c, 8, 0);
  for (int k : {p1, p2})
    if (solid(r).keypoints.count(k) == 0)
      r.fail(c, fmt::format("axis keypoint {} is not defined", k));
  double arc = r.real(c, 9, 360.0);
  if (arc == 0.0) arc = 360.0;
  if (std::fabs(arc) > 360.0) r.fail(c, fmt::format("ARC {} exceeds 360 degrees", arc));
  int nseg = r.integer(c, 10, 0);
  if (nseg <= 0) nseg = std::max(1, static_cast<int>(std::ceil(std::fabs(arc) / 90.0 - 1e-9)));
  if (nseg > 8) r.fail(c, fmt::format("NSEG {} exceeds 8", nseg));
  mesh_swept(r, c,
             geometry::revolve_areas(r.model.solid, areas, solid(r).keypoints.at(p1).x,
                                     solid(r).keypoints.at(p2).x, arc, nseg, c.where));
}

}  // namespace

geometry::MeshPointers mesh_pointers(const DeckReader& r) {
  geometry::MeshPointers p;
  p.type = r.modeling.current_type;
  p.mat = r.modeling.current_mat;
  p.real = r.modeling.current_real;
  p.secnum = r.modeling.current_secnum;
  p.esys = r.modeling.esys;
  p.max_nodes = r.options.max_nodes;
  p.max_elements = r.options.max_elements;
  return p;
}

void record_created_elements(DeckReader& r, const geometry::Mesher& mesher) {
  for (int e : mesher.created_elements()) r.modeling.element_order.push_back(e);
}

void register_mesh_commands(std::vector<CommandSpec>& t) {
  t.push_back({"ESIZE", cmd_esize, kPrep7});
  t.push_back({"LESIZE", cmd_lesize, kPrep7});
  t.push_back({"KESIZE", cmd_kesize, kPrep7});
  t.push_back({"AESIZE", cmd_aesize, kPrep7});
  t.push_back({"DESIZE", cmd_desize, kPrep7});
  t.push_back({"SMRTSIZE", cmd_smrtsize, kPrep7});
  t.push_back({"MOPT", cmd_mopt, kPrep7});
  t.push_back({"MSHAPE", cmd_mshape, kPrep7});
  t.push_back({"MSHKEY", cmd_mshkey, kPrep7});
  t.push_back({"KATT", cmd_katt, kPrep7});
  t.push_back({"LATT", cmd_latt, kPrep7});
  t.push_back({"AATT", cmd_aatt, kPrep7});
  t.push_back({"VATT", cmd_vatt, kPrep7});
  t.push_back({"ESYS", cmd_esys, kPrep7});
  t.push_back({"KMESH", cmd_kmesh, kPrep7});
  t.push_back({"LMESH", cmd_lmesh, kPrep7});
  t.push_back({"AMESH", cmd_amesh, kPrep7});
  t.push_back({"VMESH", cmd_vmesh, kPrep7});
  t.push_back({"VSWEEP", cmd_vsweep, kPrep7});
  t.push_back({"KCLEAR", cmd_clear, kPrep7});
  t.push_back({"LCLEAR", cmd_clear, kPrep7});
  t.push_back({"ACLEAR", cmd_clear, kPrep7});
  t.push_back({"VCLEAR", cmd_clear, kPrep7});
  t.push_back({"EXTOPT", cmd_extopt, kPrep7});
  t.push_back({"VEXT", cmd_vext, kPrep7});
  t.push_back({"VROTAT", cmd_vrotat, kPrep7});
}

}  // namespace impactfe::deck
