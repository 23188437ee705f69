#pragma once
/// Helpers shared by the model-building command handlers (solid model, meshing, coordinate
/// systems, entity selection, surface and solid-entity loads, material tables).
#include <fmt/format.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/selection.h"
#include "deck/deck_context.h"
#include "geometry/mesher.h"

namespace impactfe::deck {

/// Numbers of the selected entities of `map`.
template <class Map>
std::vector<int> selected_ids(const Map& map, const Selection& selection) {
  std::vector<int> out;
  for (const auto& entry : map)
    if (selection.selected(entry.first)) out.push_back(entry.first);
  return out;
}

/// All numbers of `map`.
template <class Map>
std::vector<int> all_ids(const Map& map) {
  std::vector<int> out;
  for (const auto& entry : map) out.push_back(entry.first);
  return out;
}

/// Entities NUM1..NUM2 step NINC of `map` (fields f1, f2, f3; f2/f3 0 when the command has no
/// range). NUM1 = ALL (or blank when `blank_all`): the selected entities; P (picking): error.
/// A single missing number is an error; missing numbers inside a range are skipped, but the
/// range must hold at least one entity. `what` names the kind ("keypoint", "line", ...).
template <class Map>
std::vector<int> entity_list(DeckReader& r, const Command& c, int f1, int f2, int f3,
                             const Map& map, const Selection& selection, const char* what,
                             bool blank_all = false) {
  const std::string first_label = r.label(c, f1);
  if (first_label == "ALL" || (blank_all && first_label.empty())) {
    auto out = selected_ids(map, selection);
    if (out.empty()) r.fail(c, fmt::format("ALL: no {} is selected", what));
    return out;
  }
  if (first_label == "P") r.fail(c, "graphical picking (P) is not available in batch decks");
  const auto first = r.opt_int(c, f1);
  if (!first) r.fail(c, fmt::format("field {}: {} number missing", f1, what));
  const int last = f2 > 0 ? r.integer(c, f2, *first) : *first;
  int inc = f3 > 0 ? r.integer(c, f3, 1) : 1;
  if (inc == 0) inc = 1;
  if (last == *first) {
    if (map.count(*first) == 0) r.fail(c, fmt::format("{} {} is not defined", what, *first));
    return {*first};
  }
  if ((last - *first) * inc < 0)
    r.fail(c, fmt::format("empty {} range {} to {} step {}", what, *first, last, inc));
  std::vector<int> out;
  for (int n = *first; inc > 0 ? n <= last : n >= last; n += inc)
    if (map.count(n) != 0) out.push_back(n);
  if (out.empty())
    r.fail(c, fmt::format("no {} is defined in the range {} to {}", what, *first, last));
  return out;
}

/// Field `f` as the name of a component of `entity` ("NODE", "ELEM"): its members; otherwise
/// entity_list's number, range or ALL (fields f, f2, f3).
template <class Map>
std::vector<int> component_or_entity_list(DeckReader& r, const Command& c, int f, int f2, int f3,
                                          const char* entity, const Map& map,
                                          const Selection& selection, const char* what) {
  if (const auto cm = r.model.components.find(r.label(c, f));
      cm != r.model.components.end() && cm->second.entity == entity)
    return cm->second.ids;
  return entity_list(r, c, f, f2, f3, map, selection, what);
}

// ---- selection (APDL_MODELING §1.1) ------------------------------------------------------------

/// The Type field of a select command (blank = S). `associative`: only S, R, A, U are allowed.
SelectType select_type(DeckReader& r, const Command& c, int field, bool associative = false);
/// VMIN..VMAX (step VINC for integers) of fields f, f+1, f+2 as a test on a value. Integers:
/// VMAX defaults to VMIN, VINC to 1 (negative: error), VMIN > VMAX swapped. Reals: the MAPDL
/// tolerance (±0.005 |VMIN| when VMIN = VMAX ≠ 0, ±1e-6 when both are 0, ±1e-8 (VMAX − VMIN)
/// otherwise). `absolute` compares |value| (KABS = 1).
std::function<bool(double)> value_test(DeckReader& r, const Command& c, int f, bool integer,
                                       bool absolute = false);
/// ALLSEL,BELOW,<kind>: from the selected entities of `kind` (VOLU, AREA, LINE, KP, ELEM),
/// selects everything attached below them (additively).
void select_below(DeckReader& r, const std::string& kind);

/// Global position of the point given by fields f, f+1, f+2 in the active coordinate system.
Vec3 active_point(DeckReader& r, const Command& c, int f);

/// The current TYPE/MAT/REAL/SECNUM pointers for meshing.
geometry::MeshPointers mesh_pointers(const DeckReader& r);

/// Appends the elements a mesher created to the deck's creation order (EGEN with negative
/// IEL1 counts them).
void record_created_elements(DeckReader& r, const geometry::Mesher& mesher);

/// A load value field: a number, or `%NAME%` naming a time table (APDL_MODELING §5.5).
struct LoadField {
  double value = 0.0;
  std::string table;  // upper-case table name, empty for a number
};
/// Reads field `i` as a load value. A `%NAME%` must name a TABLE whose primary variable is TIME
/// (Model::time_functions); a missing table is an error.
LoadField load_field(DeckReader& r, const Command& c, int i);

/// Nodes of the selected elements' free faces whose nodes are all selected, per the SF,ALL face
/// rule (APDL_MODELING §5.1): the (element, face) pairs that receive the load.
std::vector<FaceKey> faces_on_selected_nodes(const DeckReader& r, const Command& c);

/// At SOLVE (and LSWRITE): copies the solid-model loads to the mesh (SBCTRAN).
void transfer_solid_loads(DeckReader& r, const Command& c);
/// At SOLVE: stops when an element uses a material whose TB law is not implemented yet.
void check_material_tables(DeckReader& r, const Command& c);

}  // namespace impactfe::deck
