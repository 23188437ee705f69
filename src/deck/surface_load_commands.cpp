// Surface loads and loads on solid-model entities (APDL_MODELING §5.1-§5.6): SF, SFE, SFBEAM,
// SFA and their deletion (SFDELE, SFEDELE, SFADELE), DK, DL, DA, FK and their deletion, SBCTRAN
// (and the automatic transfer at SOLVE), the `%TABLE%` load-value field, and the refusals of
// SFL, SFGRAD and FL.
#include <fmt/format.h>

#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include "core/text.h"
#include "deck/lexer.h"
#include "deck/modeling_helpers.h"
#include "deck/post_support.h"
#include "geometry/element_faces.h"
#include "geometry/load_transfer.h"

namespace impactfe::deck {

namespace {

SolidLoads& solid_loads(DeckReader& r) {
  return r.model.solid.loads;
}

void require_pressure(DeckReader& r, const Command& c, int field) {
  // MAPDL reads the label's first four letters: PRESS (vmr031) is PRES.
  const std::string lab = r.label(c, field);
  if (lab != "PRES" && lab != "PRESS")
    r.fail(c, fmt::format("surface load '{}' not supported in a structural analysis (PRES)",
                          c.text(field)));
}

void refuse_component(DeckReader& r, const Command& c, int field) {
  const std::string l = r.label(c, field);
  if (!l.empty() && l != "ALL" && !r.opt_real(c, field))
    r.fail(c, fmt::format("'{}': component names are not available (use ALL with a selection)",
                          c.text(field)));
}

SurfaceLoad uniform(const LoadField& v) {
  SurfaceLoad s;
  s.values.fill(v.value);
  s.table = v.table;
  return s;
}

void cmd_sf(DeckReader& r, const Command& c) {
  // SF,Nlist,Lab,VALUE,VALUE2,MESHFLAG
  // Nlist: ALL (the selected nodes) or a node component (APDL_MODELING §1.9, §5.1).
  const std::string nlist = r.label(c, 1);
  std::optional<std::set<int>> component;
  if (!nlist.empty() && nlist != "ALL") {
    const auto members = component_members(r, c, nlist, "NODE");
    if (!members)
      r.fail(c,
             "Nlist must be ALL (the selected nodes) or a node component: single node numbers "
             "are not allowed");
    component.emplace(members->begin(), members->end());
  }
  require_pressure(r, c, 2);
  const LoadField v = load_field(r, c, 3);
  if (r.real(c, 4, 0.0) != 0.0) r.fail(c, "VALUE2 (imaginary part) is not supported");
  const ModelSelection& sel = r.model.selection;
  // Pressures on shells whose surface is not selected go to their selected edges (MAPDL's
  // in-plane edge pressure).
  const auto faces = geometry::faces_on_nodes(
      r.model, [&](int n) { return component ? component->count(n) != 0 : sel.nodes.selected(n); },
      [&](int e) { return sel.elements.selected(e); }, true);
  if (faces.empty())
    r.fail(c,
           "no element face has all its nodes selected (select the nodes of the loaded "
           "surface and the elements under it)");
  for (const FaceKey& f : faces) r.model.current.pressures[f] = uniform(v);
}

std::vector<int> element_list(DeckReader& r, const Command& c, int field) {
  if (const auto members = component_members(r, c, r.label(c, field), "ELEM")) {
    if (members->empty())
      r.fail(c, fmt::format("component {} has no existing elements", c.text(field)));
    return *members;
  }
  refuse_component(r, c, field);
  return entity_list(r, c, field, 0, 0, r.model.elements, r.model.selection.elements, "element");
}

/// The values line of the CDB archive form `SFE,ELEM,LKEY,Lab,KVAL,R5.0` (the lexer attaches it
/// as the command's block): VALUE1 to VALUE4 at the face's corners, separated by blanks; one
/// value alone loads every corner.
SurfaceLoad archive_face_values(DeckReader& r, const Command& c) {
  Command at_values = c;
  at_values.where.line = c.block_line;
  if (!c.block) r.fail(c, "R5.0: the line of values that follows the command is missing");
  std::string_view line = *c.block;
  if (const std::size_t end = line.find('\n'); end != std::string_view::npos)
    line = line.substr(0, end);
  std::vector<double> values;
  for (std::size_t pos = 0; pos < line.size();) {
    while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t')) ++pos;
    std::size_t end = pos;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
    if (end == pos) break;
    const std::string_view token = line.substr(pos, end - pos);
    const auto v = parse_fortran_number(token);
    if (!v) r.fail(at_values, fmt::format("SFE values line: '{}' is not a number", token));
    if (values.size() == 4) r.fail(at_values, "SFE values line: more than 4 values");
    values.push_back(*v);
    pos = end;
  }
  if (values.empty()) r.fail(at_values, "SFE values line: no value");
  SurfaceLoad load;
  load.values.fill(values.front());
  for (std::size_t k = 1; k < values.size(); ++k) load.values[k] = values[k];
  return load;
}

void cmd_sfe(DeckReader& r, const Command& c) {
  // SFE,ELEM,LKEY,Lab,KVAL,VALUE1,VALUE2,VALUE3,VALUE4,MESHFLAG; in a CDB archive
  // SFE,ELEM,LKEY,Lab,KVAL,R5.0 with the values on the next line (archive_face_values).
  const auto elements = element_list(r, c, 1);
  const int lkey = r.integer(c, 2, 1);
  require_pressure(r, c, 3);
  const int kval = r.integer(c, 4, 0);
  if (kval == 2) r.fail(c, "KVAL = 2 (imaginary part) is not supported");
  if (kval != 0 && kval != 1) r.fail(c, fmt::format("KVAL {} must be 0 or 1", kval));
  const bool archive = r.label(c, 5) == "R5.0";
  if (archive && c.last_given() > 5)
    r.fail(c, "R5.0: the values are on the next line, not after R5.0");
  const LoadField v1 = archive ? LoadField{} : load_field(r, c, 5);
  SurfaceLoad load = archive ? archive_face_values(r, c) : uniform(v1);
  const bool tapered = !archive && (!c.blank(6) || !c.blank(7) || !c.blank(8));
  if (tapered && v1.table.empty())
    for (int k = 1; k < 4; ++k) load.values[static_cast<std::size_t>(k)] = r.real(c, 5 + k, 0.0);
  for (int e : elements) {
    const ElementRecord& rec = r.model.elements.at(e);
    if (geometry::element_face_nodes(r.model, rec, lkey).empty())
      r.fail(c, fmt::format("element {} ({}) has no face {}", e,
                            r.model.element_types.count(rec.type) != 0
                                ? r.model.element_types.at(rec.type).ansys_name
                                : "undefined type",
                            lkey));
    r.model.current.pressures[FaceKey{e, lkey}] = load;
  }
}

void cmd_sfbeam(DeckReader& r, const Command& c) {
  // SFBEAM,Elem,LKEY,Lab,VALI,VALJ,VAL2I,VAL2J,IOFFST,JOFFST,LENRAT: a force per length on face
  // LKEY of beam elements, VALI at node I and VALJ (default VALI) at J, linear between; the
  // faces are the elements' own (Beam::pressure_load, QuadraticBeam::pressure_load).
  const auto elements = element_list(r, c, 1);
  const int lkey = r.integer(c, 2, 1);
  require_pressure(r, c, 3);
  const LoadField vi = load_field(r, c, 4);
  SurfaceLoad load = uniform(vi);
  if (!c.blank(5)) {
    if (!vi.table.empty()) r.fail(c, "VALJ with a table VALI: the table gives the whole load");
    load.values[1] = r.real(c, 5, 0.0);
  }
  if (r.real(c, 6, 0.0) != 0.0 || r.real(c, 7, 0.0) != 0.0)
    r.fail(c, "VAL2I, VAL2J (imaginary parts of a harmonic load) are not supported");
  if (r.real(c, 8, 0.0) != 0.0 || r.real(c, 9, 0.0) != 0.0)
    r.fail(c,
           "IOFFST, JOFFST: a load over part of the element is not implemented (the whole "
           "length from I to J is)");
  const double lenrat = r.real(c, 10, 0.0);
  if (lenrat != 0.0 && lenrat != 1.0) r.fail(c, fmt::format("LENRAT {:g}: 0 or 1", lenrat));
  for (int e : elements) {
    const ElementRecord& rec = r.model.elements.at(e);
    const auto type = r.model.element_types.find(rec.type);
    const std::string name = type != r.model.element_types.end() ? type->second.ansys_name : "";
    if (name != "BEAM188" && name != "BEAM189" && name != "BEAM3" && name != "BEAM4")
      r.fail(c, fmt::format("element {} is a {}: SFBEAM loads the beams BEAM188, BEAM189, BEAM3 "
                            "and BEAM4",
                            e, name.empty() ? "element of no type" : name));
    if (geometry::element_face_nodes(r.model, rec, lkey).empty())
      r.fail(c, fmt::format("LKEY {}: {} has faces 1 to {}", lkey, name, name == "BEAM3" ? 4 : 5));
    r.model.current.pressures[FaceKey{e, lkey}] = load;
  }
}

void cmd_sfdele(DeckReader& r, const Command& c) {
  // SFDELE,Nlist,Lab
  const std::string nlist = r.label(c, 1);
  if (!nlist.empty() && nlist != "ALL") refuse_component(r, c, 1);
  const std::string lab = r.label(c, 2);
  if (!lab.empty() && lab != "ALL" && lab != "PRES")
    r.fail(c, fmt::format("bad label '{}' (PRES, ALL)", c.text(2)));
  auto& pressures = r.model.current.pressures;
  const ModelSelection& sel = r.model.selection;
  for (auto it = pressures.begin(); it != pressures.end();) {
    const auto e = r.model.elements.find(it->first.element);
    bool all = e != r.model.elements.end();
    if (all)
      for (int n : geometry::element_face_nodes(r.model, e->second, it->first.face))
        all = all && sel.nodes.selected(n);
    it = all ? pressures.erase(it) : std::next(it);
  }
}

void cmd_sfedele(DeckReader& r, const Command& c) {
  // SFEDELE,ELEM,LKEY,Lab
  const auto elements = element_list(r, c, 1);
  const auto lkey = r.opt_int(c, 2);
  auto& pressures = r.model.current.pressures;
  for (int e : elements)
    for (auto it = pressures.lower_bound(FaceKey{e, 0});
         it != pressures.end() && it->first.element == e;)
      it = (!lkey || it->first.face == *lkey) ? pressures.erase(it) : std::next(it);
}

void cmd_sfa(DeckReader& r, const Command& c) {
  // SFA,AREA,LKEY,Lab,VALUE,VALUE2
  const auto areas =
      entity_list(r, c, 1, 0, 0, r.model.solid.areas, r.model.selection.areas, "area");
  const int lkey = r.integer(c, 2, 1);
  require_pressure(r, c, 3);
  const LoadField v = load_field(r, c, 4);
  if (r.real(c, 5, 0.0) != 0.0) r.fail(c, "VALUE2 (imaginary part) is not supported");
  for (int a : areas) solid_loads(r).area_pressures[{a, lkey}] = uniform(v);
}

void cmd_sfadele(DeckReader& r, const Command& c) {
  const auto areas =
      entity_list(r, c, 1, 0, 0, r.model.solid.areas, r.model.selection.areas, "area");
  const auto lkey = r.opt_int(c, 2);
  auto& p = solid_loads(r).area_pressures;
  for (int a : areas)
    for (auto it = p.begin(); it != p.end();)
      it = it->first.first == a && (!lkey || it->first.second == *lkey) ? p.erase(it)
                                                                        : std::next(it);
}

/// DOF labels of a solid-entity constraint or force: one label (ALL = six DOFs) plus extras.
std::vector<Dof> dof_labels(DeckReader& r, const Command& c, int first, int extra_first,
                            int extra_last, bool force) {
  std::vector<std::string> labels{r.label(c, first)};
  for (int f = extra_first; f > 0 && f <= extra_last; ++f)
    if (!c.blank(f)) labels.push_back(r.label(c, f));
  std::vector<Dof> out;
  for (const auto& l : labels) {
    if (l == "ALL" && !force) return {kAllDofs.begin(), kAllDofs.end()};
    const auto d = force ? parse_force_label(l) : parse_dof_label(l);
    if (!d)
      r.fail(c, fmt::format("bad {} label '{}' ({})", force ? "force" : "DOF", l,
                            force ? "FX FY FZ MX MY MZ" : "UX UY UZ ROTX ROTY ROTZ ALL"));
    out.push_back(*d);
  }
  return out;
}

SolidDofLoad solid_value(DeckReader& r, const Command& c, int field) {
  const LoadField v = load_field(r, c, field);
  return SolidDofLoad{v.value, v.table};
}

void cmd_dk(DeckReader& r, const Command& c) {
  // DK,KPOI,Lab,VALUE,VALUE2,KEXPND,Lab2..Lab6
  const auto kps =
      entity_list(r, c, 1, 0, 0, r.model.solid.keypoints, r.model.selection.keypoints, "keypoint");
  if (r.integer(c, 5, 0) == 1)
    r.fail(c, "KEXPND = 1 (expansion between keypoints) is not supported");
  const auto dofs = dof_labels(r, c, 2, 6, 10, false);
  const SolidDofLoad v = solid_value(r, c, 3);
  for (int k : kps)
    for (Dof d : dofs) solid_loads(r).keypoint_constraints[{k, d}] = v;
}

void cmd_fk(DeckReader& r, const Command& c) {
  const auto kps =
      entity_list(r, c, 1, 0, 0, r.model.solid.keypoints, r.model.selection.keypoints, "keypoint");
  const auto dofs = dof_labels(r, c, 2, 0, 0, true);
  const SolidDofLoad v = solid_value(r, c, 3);
  for (int k : kps)
    for (Dof d : dofs) solid_loads(r).keypoint_forces[{k, d}] = v;
}

void cmd_dl(DeckReader& r, const Command& c) {
  // DL,LINE,AREA,Lab,Value1,Value2
  const auto lines =
      entity_list(r, c, 1, 0, 0, r.model.solid.lines, r.model.selection.lines, "line");
  const std::string lab = r.label(c, 3);
  if (!c.blank(2)) r.warn(c, "AREA field: the lowest selected area containing the line is used");
  if (lab == "SYMM" || lab == "ASYM") {
    for (int l : lines)
      solid_loads(r).line_symmetry[l] =
          lab == "SYMM" ? SymmetryKind::Symmetric : SymmetryKind::Antisymmetric;
    return;
  }
  const auto dofs = dof_labels(r, c, 3, 0, 0, false);
  const SolidDofLoad v = solid_value(r, c, 4);
  for (int l : lines)
    for (Dof d : dofs) solid_loads(r).line_constraints[{l, d}] = v;
}

void cmd_da(DeckReader& r, const Command& c) {
  // DA,AREA,Lab,Value1,Value2
  const auto areas =
      entity_list(r, c, 1, 0, 0, r.model.solid.areas, r.model.selection.areas, "area");
  const std::string lab = r.label(c, 2);
  if (lab == "SYMM" || lab == "ASYM") {
    for (int a : areas)
      solid_loads(r).area_symmetry[a] =
          lab == "SYMM" ? SymmetryKind::Symmetric : SymmetryKind::Antisymmetric;
    return;
  }
  const auto dofs = dof_labels(r, c, 2, 0, 0, false);
  const SolidDofLoad v = solid_value(r, c, 3);
  for (int a : areas)
    for (Dof d : dofs) solid_loads(r).area_constraints[{a, d}] = v;
}

template <class Map>
void delete_dof_loads(DeckReader& r, const Command& c, Map& loads, const std::vector<int>& ids,
                      bool force) {
  const std::string lab = r.label(c, 2);
  std::vector<Dof> dofs(kAllDofs.begin(), kAllDofs.end());
  if (!lab.empty() && lab != "ALL") dofs = dof_labels(r, c, 2, 0, 0, force);
  for (int id : ids)
    for (Dof d : dofs) loads.erase({id, d});
}

void cmd_dkdele(DeckReader& r, const Command& c) {
  const auto ids =
      entity_list(r, c, 1, 0, 0, r.model.solid.keypoints, r.model.selection.keypoints, "keypoint");
  delete_dof_loads(r, c, solid_loads(r).keypoint_constraints, ids, false);
}
void cmd_fkdele(DeckReader& r, const Command& c) {
  const auto ids =
      entity_list(r, c, 1, 0, 0, r.model.solid.keypoints, r.model.selection.keypoints, "keypoint");
  delete_dof_loads(r, c, solid_loads(r).keypoint_forces, ids, true);
}
void cmd_dldele(DeckReader& r, const Command& c) {
  const auto ids = entity_list(r, c, 1, 0, 0, r.model.solid.lines, r.model.selection.lines, "line");
  delete_dof_loads(r, c, solid_loads(r).line_constraints, ids, false);
  const std::string lab = r.label(c, 2);
  if (lab.empty() || lab == "ALL" || lab == "SYMM" || lab == "ASYM")
    for (int id : ids) solid_loads(r).line_symmetry.erase(id);
}
void cmd_dadele(DeckReader& r, const Command& c) {
  const auto ids = entity_list(r, c, 1, 0, 0, r.model.solid.areas, r.model.selection.areas, "area");
  delete_dof_loads(r, c, solid_loads(r).area_constraints, ids, false);
  const std::string lab = r.label(c, 2);
  if (lab.empty() || lab == "ALL" || lab == "SYMM" || lab == "ASYM")
    for (int id : ids) solid_loads(r).area_symmetry.erase(id);
}

void cmd_sbctran(DeckReader& r, const Command& c) {
  for (const auto& note : geometry::transfer_solid_loads(r.model, c.where)) r.warn(c, note);
}

void cmd_surface_refused(DeckReader& r, const Command& c) {
  if (c.name == "FL") r.fail(c, "fatigue commands are not supported (FL is not a line force)");
  r.fail(c, fmt::format("{} is not supported (use SF, SFE or SFA with PRES)", c.name));
}

}  // namespace

LoadField load_field(DeckReader& r, const Command& c, int i) {
  const std::string text = trim(c.text(i));
  if (text.size() >= 2 && text.front() == '%' && text.back() == '%') {
    const std::string name = to_upper(text.substr(1, text.size() - 2));
    if (name == "_FIX") r.fail(c, "%_FIX% (hold the current value) is not supported");
    // A TABLE parameter whose primary variable is TIME becomes Model::time_functions[NAME]:
    // its index column T(i,0) are the times, column 1 the values (APDL_SCRIPTING §A.7). The
    // table is taken as it stands at this command, like every other load value.
    const Param* table = r.params.find(name);
    if (table == nullptr || table->type != ParamType::Table)
      r.fail(c, fmt::format("table %{}% is not defined (a TABLE array with primary variable TIME "
                            "is needed: *DIM,{},TABLE,n,1,1,TIME)",
                            name, name));
    if (to_upper(trim(table->variables[0])) != "TIME")
      r.fail(c, fmt::format("table %{}% has primary variable '{}': only TIME (a load history) is "
                            "supported, not spatial tables",
                            name, table->variables[0]));
    if (table->jmax != 1 || table->kmax != 1)
      r.fail(c, fmt::format("table %{}% has {}x{}x{} entries: a load history has one column of "
                            "values (*DIM,{},TABLE,n,1,1,TIME)",
                            name, table->imax, table->jmax, table->kmax, name));
    TimeFunction history;
    for (int i = 1; i <= table->imax; ++i) {
      const double t = table->values[table->offset(i, 0, 1)];
      if (!history.time.empty() && !(t > history.time.back()))
        r.fail(c, fmt::format("table %{}%: its times must increase ({}({},0) = {} after {})", name,
                              name, i, t, history.time.back()));
      history.time.push_back(t);
      history.value.push_back(table->values[table->offset(i, 1, 1)]);
    }
    r.model.time_functions[name] = std::move(history);
    return LoadField{0.0, name};
  }
  return LoadField{r.real(c, i, 0.0), {}};
}

std::vector<FaceKey> faces_on_selected_nodes(const DeckReader& r, const Command&) {
  const ModelSelection& sel = r.model.selection;
  return geometry::faces_on_nodes(
      r.model, [&](int n) { return sel.nodes.selected(n); },
      [&](int e) { return sel.elements.selected(e); });
}

void transfer_solid_loads(DeckReader& r, const Command& c) {
  if (r.model.solid.loads.empty() && r.model.solid.loads.transferred_constraints.empty() &&
      r.model.solid.loads.transferred_forces.empty() &&
      r.model.solid.loads.transferred_pressures.empty())
    return;
  for (const auto& note : geometry::transfer_solid_loads(r.model, c.where)) r.warn(c, note);
}

void prepare_model_for_solution(DeckReader& r, const Command& c) {
  transfer_solid_loads(r, c);
  check_material_tables(r, c);
}

void register_surface_load_commands(std::vector<CommandSpec>& t) {
  t.push_back({"SF", cmd_sf, kPrepSolu});
  t.push_back({"SFE", cmd_sfe, kPrepSolu});
  t.push_back({"SFBEAM", cmd_sfbeam, kPrepSolu});
  t.push_back({"SFA", cmd_sfa, kPrepSolu});
  t.push_back({"SFDELE", cmd_sfdele, kPrepSolu});
  t.push_back({"SFEDELE", cmd_sfedele, kPrepSolu});
  t.push_back({"SFADELE", cmd_sfadele, kPrepSolu});
  t.push_back({"DK", cmd_dk, kPrepSolu});
  t.push_back({"FK", cmd_fk, kPrepSolu});
  t.push_back({"DL", cmd_dl, kPrepSolu});
  t.push_back({"DA", cmd_da, kPrepSolu});
  t.push_back({"DKDELE", cmd_dkdele, kPrepSolu});
  t.push_back({"FKDELE", cmd_fkdele, kPrepSolu});
  t.push_back({"DLDELE", cmd_dldele, kPrepSolu});
  t.push_back({"DADELE", cmd_dadele, kPrepSolu});
  for (const char* name : {"SBCTRAN", "DTRAN", "FTRAN", "SFTRAN"})
    t.push_back({name, cmd_sbctran, kPrepSolu});
  for (const char* name : {"SFL", "SFGRAD", "FL"})
    t.push_back({name, cmd_surface_refused, kAnywhere});
}

}  // namespace impactfe::deck
