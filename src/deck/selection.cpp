#include "deck/selection.h"

#include <cmath>

namespace impactfe::deck {

std::optional<SelectType> parse_select_type(const std::string& label) {
  if (label.empty() || label == "S") return SelectType::S;
  if (label == "R") return SelectType::R;
  if (label == "A") return SelectType::A;
  if (label == "U") return SelectType::U;
  if (label == "ALL") return SelectType::All;
  if (label == "NONE") return SelectType::None;
  if (label == "INVE" || label == "INVERT") return SelectType::Inve;
  if (label == "STAT") return SelectType::Stat;
  return std::nullopt;
}

void EntitySelection::apply(SelectType type, const std::vector<int>& defined,
                            const std::function<bool(int)>& candidate) {
  switch (type) {
    case SelectType::S:
      unselected_.clear();
      for (int id : defined)
        if (!candidate(id)) unselected_.insert(id);
      break;
    case SelectType::R:
      for (int id : defined)
        if (selected(id) && !candidate(id)) unselected_.insert(id);
      break;
    case SelectType::A:
      for (int id : defined)
        if (candidate(id)) unselected_.erase(id);
      break;
    case SelectType::U:
      for (int id : defined)
        if (selected(id) && candidate(id)) unselected_.insert(id);
      break;
    case SelectType::All:
      unselected_.clear();
      break;
    case SelectType::None:
      unselected_ = std::set<int>(defined.begin(), defined.end());
      break;
    case SelectType::Inve: {
      std::set<int> inverted;
      for (int id : defined)
        if (selected(id)) inverted.insert(id);
      unselected_ = std::move(inverted);
      break;
    }
    case SelectType::Stat:
      break;
  }
}

std::vector<int> EntitySelection::selected_ids(const std::vector<int>& defined) const {
  std::vector<int> out;
  for (int id : defined)
    if (selected(id)) out.push_back(id);
  return out;
}

std::size_t EntitySelection::count(const std::vector<int>& defined) const {
  std::size_t n = 0;
  for (int id : defined) n += selected(id) ? 1 : 0;
  return n;
}

bool RealWindow::contains(double v) const {
  const double x = absolute ? std::fabs(v) : v;
  return x >= lo && x <= hi;
}

RealWindow real_window(double vmin, std::optional<double> vmax, bool absolute) {
  double hi = vmax.value_or(vmin);
  double lo = vmin;
  if (lo > hi) std::swap(lo, hi);
  double tol = 0.0;
  if (lo == hi)
    tol = lo != 0.0 ? 0.005 * std::fabs(lo) : 1e-6;
  else
    tol = 1e-8 * (hi - lo);
  return RealWindow{lo - tol, hi + tol, absolute};
}

}  // namespace impactfe::deck
