#pragma once
/// Numbering control (APDL_MODELING §3.7): renumbering (NUMCMP) and merging of coincident items
/// (NUMMRG). A renumbering is a map old → new number; every reference follows it (element
/// connectivity, loads of the current load state, initial conditions, master DOFs, gap
/// conditions, solid-model ownership and loads, selection flags). Two numbers mapped onto the
/// same new one are merged: the kept item is the one whose number is the target.
#include <map>

#include "core/model.h"

namespace impactfe::geometry {

void renumber_nodes(Model& model, const std::map<int, int>& map);
void renumber_elements(Model& model, const std::map<int, int>& map);
void renumber_keypoints(Model& model, const std::map<int, int>& map);
void renumber_lines(Model& model, const std::map<int, int>& map);
void renumber_areas(Model& model, const std::map<int, int>& map);
void renumber_volumes(Model& model, const std::map<int, int>& map);

/// NUMCMP: the map that numbers the keys of `items` consecutively from 1 in their order.
template <class Map>
std::map<int, int> compress_map(const Map& items) {
  std::map<int, int> out;
  int next = 1;
  for (const auto& entry : items) out[entry.first] = next++;
  return out;
}

/// Coincident selected nodes within `toler` (largest coordinate difference): map of each merged
/// node to the kept one (the lowest number, or the highest when `keep_high`).
std::map<int, int> coincident_nodes(const Model& model, double toler, bool keep_high);
/// Coincident selected keypoints (the lowest number is kept).
std::map<int, int> coincident_keypoints(const Model& model, double toler);
/// After keypoints merged: lines joining the same keypoints along the same path, areas bounded by
/// the same lines, volumes bounded by the same areas (each merged into the lowest number).
std::map<int, int> duplicate_lines(const Model& model);
std::map<int, int> duplicate_areas(const Model& model);
std::map<int, int> duplicate_volumes(const Model& model);
/// Selected elements with the same type and the same node set (the lowest number is kept).
std::map<int, int> duplicate_elements(const Model& model);

/// NUMMRG,MAT / TYPE / REAL / SECT: identical definitions (relative tolerance `toler`) merged
/// into the lowest number; element records and solid-model attributes follow.
int merge_materials(Model& model, double toler);
int merge_element_types(Model& model);
int merge_real_sets(Model& model, double toler);
int merge_sections(Model& model, double toler);

}  // namespace impactfe::geometry
