// Copying and numbering of solid-model entities and meshes (APDL_MODELING §3.1, §3.5-§3.7):
// KGEN, LGEN, AGEN, VGEN, their reflections KSYMM, LSYMM, ARSYM, VSYMM, VGLUE and AGLUE
// (coincident boundaries only), NUMMRG, NUMCMP.
#include <fmt/format.h>

#include <set>

#include "deck/modeling_helpers.h"
#include "geometry/numbering.h"
#include "geometry/solid_copy.h"

namespace impactfe::deck {

namespace {

using geometry::SolidKind;

/// Pattern of a generation command: NUM1..NUM2 step NINC; ALL = selected; a negative NUM1 =
/// the |NUM1| highest-numbered entities.
template <class Map>
std::vector<int> pattern(DeckReader& r, const Command& c, int f1, const Map& map,
                         const Selection& sel, const char* what) {
  const auto first = r.opt_int(c, f1);
  if (first && *first < 0) {
    std::vector<int> out;
    for (auto it = map.rbegin(); it != map.rend() && static_cast<int>(out.size()) < -*first; ++it)
      out.insert(out.begin(), it->first);
    if (out.empty()) r.fail(c, fmt::format("no {} is defined", what));
    return out;
  }
  return entity_list(r, c, f1, f1 + 1, f1 + 2, map, sel, what);
}

/// The kind and pattern (fields 2-4) of a copy or reflection, by the command's first letter:
/// KGEN/KSYMM keypoints, LGEN/LSYMM lines, AGEN/ARSYM areas, VGEN/VSYMM volumes.
void set_pattern(DeckReader& r, const Command& c, geometry::CopyRequest& q) {
  const SolidModel& s = r.model.solid;
  const ModelSelection& sel = r.model.selection;
  switch (c.name.front()) {
    case 'K':
      q.kind = SolidKind::Keypoint;
      q.pattern = pattern(r, c, 2, s.keypoints, sel.keypoints, "keypoint");
      break;
    case 'L':
      q.kind = SolidKind::Line;
      q.pattern = pattern(r, c, 2, s.lines, sel.lines, "line");
      break;
    case 'A':
      q.kind = SolidKind::Area;
      q.pattern = pattern(r, c, 2, s.areas, sel.areas, "area");
      break;
    default:
      q.kind = SolidKind::Volume;
      q.pattern = pattern(r, c, 2, s.volumes, sel.volumes, "volume");
  }
}

void run_copy(DeckReader& r, const Command& c, const geometry::CopyRequest& q) {
  geometry::Mesher mesher(r.model, mesh_pointers(r), c.where);
  geometry::copy_solid(r.model, q, mesher, c.where);
  record_created_elements(r, mesher);
}

void cmd_generate(DeckReader& r, const Command& c) {
  // xGEN,ITIME,N1,N2,NINC,DX,DY,DZ,KINC,NOELEM,IMOVE
  geometry::CopyRequest q;
  set_pattern(r, c, q);
  const int itime = r.integer(c, 1, 2);
  q.move = r.integer(c, 10, 0) == 1;
  if (!q.move && itime < 2) r.fail(c, fmt::format("ITIME {} must be greater than 1", itime));
  q.copies = q.move ? 1 : itime - 1;
  q.system = r.model.coordinate_systems.active_system();
  q.increment = Vec3(r.real(c, 5, 0.0), r.real(c, 6, 0.0), r.real(c, 7, 0.0));
  q.kinc = r.integer(c, 8, 0);
  if (q.kinc < 0) r.fail(c, fmt::format("KINC {} must not be negative", q.kinc));
  q.copy_mesh = r.integer(c, 9, 0) == 0;
  run_copy(r, c, q);
}

// KSYMM / LSYMM / ARSYM / VSYMM,Ncomp,N1,N2,NINC,KINC,NOELEM,IMOVE: one reflected copy of the
// pattern (or the pattern moved onto its image with IMOVE = 1) about the plane through the
// origin of the active Cartesian system normal to its axis Ncomp. The copy runs through the
// reflected keypoints in the original order, so a reflected area's normal is the mirror image of
// the original's, reversed.
void cmd_symmetry(DeckReader& r, const Command& c) {
  geometry::CopyRequest q;
  // X by default; 1, 2, 3 are the legacy numbers of X, Y, Z (Verification Manual decks).
  const std::string axis = c.blank(1) ? "X" : r.label(c, 1);
  if (axis == "X" || axis == "1")
    q.mirror = 0;
  else if (axis == "Y" || axis == "2")
    q.mirror = 1;
  else if (axis == "Z" || axis == "3")
    q.mirror = 2;
  else
    r.fail(c, fmt::format("Ncomp '{}': X, Y or Z (the axis normal to the reflection plane)",
                          c.text(1)));
  set_pattern(r, c, q);
  q.copies = 1;
  q.move = r.integer(c, 7, 0) == 1;
  q.system = r.model.coordinate_systems.active_system();
  q.kinc = r.integer(c, 5, 0);
  if (q.kinc < 0) r.fail(c, fmt::format("KINC {} must not be negative", q.kinc));
  q.copy_mesh = r.integer(c, 6, 0) == 0;
  run_copy(r, c, q);
}

/// The deck's own node and element lists follow a renumbering.
void remap_deck_lists(DeckReader& r, const std::map<int, int>& nodes,
                      const std::map<int, int>& elements) {
  auto remap = [](std::vector<int>& list, const std::map<int, int>& map, const auto& exists) {
    std::vector<int> out;
    for (int id : list) {
      const auto it = map.find(id);
      const int to = it == map.end() ? id : it->second;
      if (exists(to) && std::find(out.begin(), out.end(), to) == out.end()) out.push_back(to);
    }
    list = std::move(out);
  };
  remap(r.modeling.defined_by_n, nodes, [&](int id) { return r.model.nodes.count(id) != 0; });
  remap(r.modeling.element_order, elements,
        [&](int id) { return r.model.elements.count(id) != 0; });
}

/// Merges coincident keypoints (restricted to `only` when non-empty) and the lines, areas and
/// volumes that become duplicates. Returns the number of areas merged.
int merge_keypoints(DeckReader& r, const Command& c, double toler, const std::set<int>& only) {
  Model& m = r.model;
  std::map<int, int> kps = geometry::coincident_keypoints(m, toler);
  if (!only.empty())
    for (auto it = kps.begin(); it != kps.end();)
      it =
          only.count(it->first) != 0 && only.count(it->second) != 0 ? std::next(it) : kps.erase(it);
  geometry::renumber_keypoints(m, kps);
  const auto lines = geometry::duplicate_lines(m);
  const auto areas_before = m.solid.areas;
  geometry::renumber_lines(m, lines);
  const auto areas = geometry::duplicate_areas(m);
  geometry::renumber_areas(m, areas);
  const auto volumes = geometry::duplicate_volumes(m);
  geometry::renumber_volumes(m, volumes);
  for (const auto& [from, to] : areas)
    if (!areas_before.at(from).grid.empty())
      r.warn(c, fmt::format("merged area {} was meshed: merge its nodes with NUMMRG,NODE", from));
  Log::info("{}:{}: {}: merged {} keypoints, {} lines, {} areas, {} volumes", c.where.file,
            c.where.line, c.name, kps.size(), lines.size(), areas.size(), volumes.size());
  return static_cast<int>(areas.size() + lines.size());
}

void merge_nodes(DeckReader& r, const Command& c, double toler, bool keep_high, bool select_only) {
  const auto map = geometry::coincident_nodes(r.model, toler, keep_high);
  if (select_only) {
    std::set<int> coincident;
    for (const auto& [from, to] : map) coincident.insert({from, to});
    r.model.selection.nodes.apply(SelectType::Select, all_ids(r.model.nodes),
                                  [&](int id) { return coincident.count(id) != 0; });
    return;
  }
  geometry::renumber_nodes(r.model, map);
  remap_deck_lists(r, map, {});
  Log::info("{}:{}: NUMMRG: {} nodes merged", c.where.file, c.where.line, map.size());
}

void merge_elements(DeckReader& r, const Command& c) {
  const auto map = geometry::duplicate_elements(r.model);
  geometry::renumber_elements(r.model, map);
  remap_deck_lists(r, {}, map);
  Log::info("{}:{}: NUMMRG: {} duplicate elements removed", c.where.file, c.where.line, map.size());
}

void cmd_nummrg(DeckReader& r, const Command& c) {
  // NUMMRG,Label,TOLER,GTOLER,Action,Switch; MAPDL reads the label's first four characters
  // (VM178 writes NUMMRG,NODES).
  std::string label = r.label(c, 1);
  if (label.size() > 4) {
    const std::string four = label.substr(0, 4);
    if (four == "NODE" || four == "ELEM" || four == "TYPE" || four == "REAL" || four == "SECT")
      label = four;
  }
  if (label == "KPOI" || label.rfind("KPOINT", 0) == 0) label = "KP";  // VM62: NUMMRG,KPOI
  const std::string action = r.label(c, 4);
  const std::string sw = r.label(c, 5);
  if (!action.empty() && action != "SELE")
    r.fail(c, fmt::format("bad Action '{}' (SELE)", c.text(4)));
  if (!sw.empty() && sw != "LOW" && sw != "HIGH")
    r.fail(c, fmt::format("bad Switch '{}' (LOW, HIGH)", c.text(5)));
  if (!action.empty() && label != "NODE") r.fail(c, "Action SELE applies to NODE only");
  const bool geometric = label == "NODE" || label == "KP" || label == "ALL";
  const double toler = r.real(c, 2, geometric ? 1e-4 : 1e-7);
  if (toler < 0.0) r.fail(c, fmt::format("TOLER {} must not be negative", toler));
  const double value_toler = label == "ALL" && c.blank(2) ? 1e-7 : toler;
  if (label == "NODE") {
    merge_nodes(r, c, toler, sw == "HIGH", action == "SELE");
  } else if (label == "KP") {
    merge_keypoints(r, c, toler, {});
  } else if (label == "ELEM") {
    merge_elements(r, c);
  } else if (label == "MAT") {
    geometry::merge_materials(r.model, toler);
  } else if (label == "TYPE") {
    geometry::merge_element_types(r.model);
  } else if (label == "REAL") {
    geometry::merge_real_sets(r.model, toler);
  } else if (label == "SECT") {
    geometry::merge_sections(r.model, toler);
  } else if (label == "ALL") {
    merge_keypoints(r, c, toler, {});
    merge_nodes(r, c, toler, sw == "HIGH", false);
    merge_elements(r, c);
    geometry::merge_materials(r.model, value_toler);
    geometry::merge_element_types(r.model);
    geometry::merge_real_sets(r.model, value_toler);
    geometry::merge_sections(r.model, value_toler);
  } else if (label == "CP" || label == "CE") {
    r.fail(c, fmt::format("{}: coupled sets and constraint equations are not supported", label));
  } else {
    r.fail(c,
           fmt::format("bad label '{}' (NODE, ELEM, KP, MAT, TYPE, REAL, SECT, ALL)", c.text(1)));
  }
}

void cmd_numcmp(DeckReader& r, const Command& c) {
  const std::string label = r.label(c, 1);
  Model& m = r.model;
  const bool all = label == "ALL";
  if (label == "NODE" || all) {
    const auto map = geometry::compress_map(m.nodes);
    geometry::renumber_nodes(m, map);
    remap_deck_lists(r, map, {});
  }
  if (label == "ELEM" || all) {
    const auto map = geometry::compress_map(m.elements);
    geometry::renumber_elements(m, map);
    remap_deck_lists(r, {}, map);
  }
  if (label == "KP" || all)
    geometry::renumber_keypoints(m, geometry::compress_map(m.solid.keypoints));
  if (label == "LINE" || all) geometry::renumber_lines(m, geometry::compress_map(m.solid.lines));
  if (label == "AREA" || all) geometry::renumber_areas(m, geometry::compress_map(m.solid.areas));
  if (label == "VOLU" || all)
    geometry::renumber_volumes(m, geometry::compress_map(m.solid.volumes));
  if (!all && label != "NODE" && label != "ELEM" && label != "KP" && label != "LINE" &&
      label != "AREA" && label != "VOLU")
    r.fail(c, fmt::format("NUMCMP,{} is not supported (NODE, ELEM, KP, LINE, AREA, VOLU, ALL)",
                          c.text(1)));
}

void cmd_glue(DeckReader& r, const Command& c) {
  // VGLUE,NV1,...,NV9 / AGLUE,NA1,...,NA9: only coincident boundaries.
  const bool volumes = c.name == "VGLUE";
  const SolidModel& s = r.model.solid;
  std::vector<int> ids;
  if (r.label(c, 1) == "ALL") {
    ids = volumes ? selected_ids(s.volumes, r.model.selection.volumes)
                  : selected_ids(s.areas, r.model.selection.areas);
  } else {
    for (int f = 1; f <= std::min(9, c.last_given()); ++f) {
      const int id = r.integer(c, f, 0);
      if (volumes ? s.volumes.count(id) == 0 : s.areas.count(id) == 0)
        r.fail(c, fmt::format("{} {} is not defined", volumes ? "volume" : "area", id));
      ids.push_back(id);
    }
  }
  if (ids.size() < 2) r.fail(c, "at least two entities are needed");
  std::set<int> kps;
  for (int id : ids) {
    const std::vector<int> areas = volumes ? s.volumes.at(id).areas : std::vector<int>{id};
    for (int a : areas)
      for (int k : s.areas.at(a).keypoints) kps.insert(k);
  }
  if (merge_keypoints(r, c, 1e-4, kps) == 0)
    r.fail(c, fmt::format("{}: general boolean not supported: the {} share no coincident {} "
                          "(only exactly coincident boundaries can be glued)",
                          c.name, volumes ? "volumes" : "areas", volumes ? "faces" : "edges"));
}

}  // namespace

void register_solid_edit_commands(std::vector<CommandSpec>& t) {
  for (const char* name : {"KGEN", "LGEN", "AGEN", "VGEN"})
    t.push_back({name, cmd_generate, kPrep7});
  for (const char* name : {"KSYMM", "LSYMM", "ARSYM", "VSYMM"})
    t.push_back({name, cmd_symmetry, kPrep7});
  t.push_back({"NUMMRG", cmd_nummrg, kPrep7});
  t.push_back({"NUMCMP", cmd_numcmp, kPrep7});
  t.push_back({"VGLUE", cmd_glue, kPrep7});
  t.push_back({"AGLUE", cmd_glue, kPrep7});
}

}  // namespace impactfe::deck
