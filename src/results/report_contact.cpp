// Contact-pair force sums of the report (report_contact.h).
#include "results/report_contact.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "elements/element_registry.h"

namespace impactfe {

ContactForceSums::ContactForceSums(const ResultsReader& reader) {
  for (const auto& e : reader.elements()) {
    const ElementTypeDescriptor* type = find_element_type(e.type_name);
    if (type == nullptr || type->role != ShapeRole::Contact) continue;
    real_of_[e.id] = e.real;
    Pair& pair = pairs_[e.real];
    pair.real = e.real;
    ++pair.n_elements;
  }
}

void ContactForceSums::add(const TimePoint& p) {
  if (real_of_.empty()) return;
  std::map<int, std::pair<double, double>> sums;  // real -> (ΣFN, ΣFT)
  bool any = false;
  for (const auto& [family, table] : p.element_results) {
    const auto& names = table.item_names;
    const auto fn = std::find(names.begin(), names.end(), std::string("FN"));
    if (fn == names.end()) continue;
    const auto ft = std::find(names.begin(), names.end(), std::string("FT"));
    for (std::size_t e = 0; e < table.element_ids.size(); ++e) {
      const auto it = real_of_.find(table.element_ids[e]);
      if (it == real_of_.end()) continue;
      const auto row = static_cast<Eigen::Index>(e);
      auto& [normal, friction] = sums[it->second];
      const double n = table.values(row, std::distance(names.begin(), fn));
      if (std::isfinite(n)) normal += n;
      if (ft != names.end())
        if (const double f = table.values(row, std::distance(names.begin(), ft)); std::isfinite(f))
          friction += f;
      any = true;
    }
  }
  if (!any) return;
  for (auto& [real, pair] : pairs_) {
    const auto s = sums.find(real);
    pair.normal.emplace_back(p.time, s == sums.end() ? 0.0 : s->second.first);
    pair.friction.emplace_back(p.time, s == sums.end() ? 0.0 : s->second.second);
  }
}

std::vector<ContactForceSums::Pair> ContactForceSums::pairs() const {
  std::vector<Pair> out;
  for (const auto& [real, pair] : pairs_)
    if (!pair.normal.empty()) out.push_back(pair);
  return out;
}

}  // namespace impactfe
