#include "core/selection.h"

namespace impactfe {

std::optional<SelectType> parse_select_type(std::string_view label) {
  if (label.empty() || label == "S") return SelectType::Select;
  if (label == "R") return SelectType::Reselect;
  if (label == "A") return SelectType::Also;
  if (label == "U") return SelectType::Unselect;
  if (label == "ALL") return SelectType::All;
  if (label == "NONE") return SelectType::None;
  // INVE and STAT as MAPDL reads them: their first four characters (INVERT, STATUS).
  if (label.size() >= 4 && std::string_view("INVERT").substr(0, label.size()) == label)
    return SelectType::Invert;
  if (label.size() >= 4 && std::string_view("STATUS").substr(0, label.size()) == label)
    return SelectType::Stat;
  return std::nullopt;
}

void Selection::apply(SelectType type, const std::vector<int>& ids,
                      const std::function<bool(int)>& candidate) {
  switch (type) {
    case SelectType::All:
      unselected_.clear();
      return;
    case SelectType::None:
      unselected_.insert(ids.begin(), ids.end());
      return;
    case SelectType::Invert:
      for (int id : ids) set(id, !selected(id));
      return;
    case SelectType::Stat:
      return;
    case SelectType::Select:
      for (int id : ids) set(id, candidate(id));
      return;
    case SelectType::Reselect:
      for (int id : ids)
        if (selected(id) && !candidate(id)) set(id, false);
      return;
    case SelectType::Also:
      for (int id : ids)
        if (!selected(id) && candidate(id)) set(id, true);
      return;
    case SelectType::Unselect:
      for (int id : ids)
        if (selected(id) && candidate(id)) set(id, false);
      return;
  }
}

void Selection::set(int id, bool on) {
  if (on)
    unselected_.erase(id);
  else
    unselected_.insert(id);
}

void Selection::renumber(const std::map<int, int>& old_to_new) {
  std::set<int> out;
  for (int id : unselected_) {
    const auto it = old_to_new.find(id);
    out.insert(it == old_to_new.end() ? id : it->second);
  }
  unselected_ = std::move(out);
}

std::vector<int> Selection::selected_of(const std::vector<int>& ids) const {
  std::vector<int> out;
  for (int id : ids)
    if (selected(id)) out.push_back(id);
  return out;
}

}  // namespace impactfe
