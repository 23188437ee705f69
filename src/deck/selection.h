#pragma once
/// Entity selection (APDL_MODELING §1): each entity kind keeps a selected flag per entity; the
/// "current set" is what ALL means on later commands (D,ALL, PRNSOL, ETABLE rows, FSUM, ...).
/// Selection never deletes anything. The state lives in the deck session (DeckReader); named
/// components (CM) live in the Model.
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace impactfe::deck {

/// xSEL Type field: S new set, R reselect, A add, U unselect, ALL, NONE, INVE(rt), STAT.
enum class SelectType { S, R, A, U, All, None, Inve, Stat };

/// Parses the Type field (blank → S); nullopt when unknown.
std::optional<SelectType> parse_select_type(const std::string& label);

/// The ids (keys) of an id-keyed map, ascending.
template <typename Map>
std::vector<int> ids_of(const Map& map) {
  std::vector<int> out;
  out.reserve(map.size());
  for (const auto& entry : map) out.push_back(entry.first);
  return out;
}

/// The selected flag of one entity kind. Stored as the set of unselected ids, so that an entity
/// created later is selected (MAPDL selects new entities) and ALLSEL is O(1).
class EntitySelection {
 public:
  /// True when `id` is not unselected (the caller checks that it exists).
  bool selected(int id) const { return unselected_.count(id) == 0; }
  /// Applies a select operation over the defined ids (ascending): S keeps the candidates, R the
  /// selected candidates, A adds candidates, U removes candidates, ALL/NONE/INVE ignore
  /// `candidate`; STAT changes nothing.
  void apply(SelectType type, const std::vector<int>& defined,
             const std::function<bool(int)>& candidate);
  void select_all() { unselected_.clear(); }
  /// The selected ones among `defined` (ascending).
  std::vector<int> selected_ids(const std::vector<int>& defined) const;
  /// Number of selected ones among `defined`.
  std::size_t count(const std::vector<int>& defined) const;
  bool operator==(const EntitySelection&) const = default;

 private:
  std::set<int> unselected_;
};

/// The selection state of a deck session: one EntitySelection per kind (the solid-model kinds
/// KP/LINE/AREA/VOLU join when the model has them).
struct Selection {
  EntitySelection nodes;
  EntitySelection elements;
  void select_all() {
    nodes.select_all();
    elements.select_all();
  }
};

/// A real-valued selection window [lo, hi] on value or |value| (KABS = 1).
struct RealWindow {
  double lo = 0.0;
  double hi = 0.0;
  bool absolute = false;
  bool contains(double v) const;
};

/// MAPDL's tolerance for real-valued ranges (APDL_MODELING §1.1): VMIN = VMAX ≠ 0 →
/// ±0.005·|VMIN|, VMIN = VMAX = 0 → ±1e-6, else ±1e-8·(VMAX − VMIN); VMAX blank = VMIN.
RealWindow real_window(double vmin, std::optional<double> vmax, bool absolute);

/// An integer range VMIN..VMAX step VINC (VMIN > VMAX swapped; VINC ≥ 1).
struct IntRange {
  int first = 0;
  int last = 0;
  int step = 1;
  bool contains(int v) const { return v >= first && v <= last && (v - first) % step == 0; }
};

}  // namespace impactfe::deck
