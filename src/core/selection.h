#pragma once
/// Selection of entities (APDL_MODELING §1.0, §1.1): each kind — nodes, elements, keypoints,
/// lines, areas, volumes — keeps a selected flag per entity; selecting never deletes anything.
/// Stored as the set of *unselected* numbers, so that everything starts selected and entities
/// created later are selected, as in MAPDL.
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

namespace impactfe {

/// The Type field of NSEL/ESEL/KSEL/LSEL/ASEL/VSEL and the associative selects.
enum class SelectType { Select, Reselect, Also, Unselect, All, None, Invert, Stat };

/// "S" (or blank), "R", "A", "U", "ALL", "NONE", "INVE", "STAT" (upper case); nullopt otherwise.
std::optional<SelectType> parse_select_type(std::string_view label);

class Selection {
 public:
  bool selected(int id) const { return unselected_.count(id) == 0; }
  /// Applies a select of `type` over the defined entities `ids`: S keeps the candidates of the
  /// full set, R the candidates of the selected ones, A adds candidates, U removes them; ALL,
  /// NONE and INVE ignore `candidate`; STAT changes nothing.
  void apply(SelectType type, const std::vector<int>& ids,
             const std::function<bool(int)>& candidate);
  void select_all() { unselected_.clear(); }
  void set(int id, bool on);
  /// An entity was deleted: it no longer has a flag (a new entity with that number is selected).
  void forget(int id) { unselected_.erase(id); }
  /// Entities renumbered (NUMCMP, NUMMRG): flags follow their entity.
  void renumber(const std::map<int, int>& old_to_new);
  /// The selected members of `ids`.
  std::vector<int> selected_of(const std::vector<int>& ids) const;

 private:
  std::set<int> unselected_;
};

/// One Selection per entity kind of a model.
struct ModelSelection {
  Selection nodes;
  Selection elements;
  Selection keypoints;
  Selection lines;
  Selection areas;
  Selection volumes;
  void select_everything() {
    for (Selection* s : {&nodes, &elements, &keypoints, &lines, &areas, &volumes}) s->select_all();
  }
};

}  // namespace impactfe
