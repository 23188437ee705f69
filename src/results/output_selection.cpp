#include "results/output_selection.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "core/numbers.h"

namespace impactfe {

namespace {

/// Does a specification write at substep k of n? The last substep of a load step is written
/// for every frequency but NONE (MAPDL: "every n-th and the last"); k = 0 (initial state)
/// likewise.
bool fires(int every, int k, int n) {
  if (every < 0) return false;
  if (k == 0 || k == n) return true;
  return every > 0 && k % every == 0;
}

/// Applies specifications in command order: one without a component sets every id, one with a
/// component sets its ids (a later one wins where they overlap).
IdSelection select(const std::vector<OutputSpec>& specs, int every, int k, int n) {
  IdSelection s;
  s.base = fires(every, k, n);
  for (const OutputSpec& spec : specs) {
    const bool on = fires(spec.every, k, n);
    if (spec.component.empty()) {
      s.base = on;
      s.exceptions.clear();
      continue;
    }
    // Ids that end up differing from the base are the exceptions.
    std::vector<int> merged;
    if (on == s.base) {
      std::set_difference(s.exceptions.begin(), s.exceptions.end(), spec.ids.begin(),
                          spec.ids.end(), std::back_inserter(merged));
    } else {
      std::set_union(s.exceptions.begin(), s.exceptions.end(), spec.ids.begin(), spec.ids.end(),
                     std::back_inserter(merged));
    }
    s.exceptions = std::move(merged);
  }
  return s;
}

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// Sets the rows of `m` whose id is not selected to NaN; empties `m` when none is.
void mask_rows(const IdSelection& s, const std::vector<int>& ids, Eigen::MatrixXd& m) {
  if (m.size() == 0 || s.all()) return;
  if (s.none()) {
    m.resize(0, 0);
    return;
  }
  for (std::size_t r = 0; r < ids.size() && r < static_cast<std::size_t>(m.rows()); ++r)
    if (!s.contains(ids[r])) m.row(static_cast<Eigen::Index>(r)).setConstant(kNaN);
}

}  // namespace

bool IdSelection::contains(int id) const {
  return std::binary_search(exceptions.begin(), exceptions.end(), id) != base;
}

bool OutputSelection::any() const {
  return std::any_of(items.begin(), items.end(), [](const IdSelection& s) { return !s.none(); });
}

bool OutputSelection::any_element_item() const {
  return !(*this)[OutputItem::STRS].none() || !(*this)[OutputItem::EPEL].none() ||
         !(*this)[OutputItem::MISC].none();
}

OutputSelection output_selection(const OutputControl& f, int substep, int n_substeps) {
  OutputSelection out;
  for (int i = 0; i < kOutputItems; ++i)
    out.items[static_cast<std::size_t>(i)] =
        select(f.items[static_cast<std::size_t>(i)], f.every, substep, n_substeps);
  return out;
}

OutputSelection output_selection_between(const OutputControl& f) {
  // k = -1 is neither the initial state, nor the last substep, nor a multiple of any n > 1:
  // only the specifications of frequency 1 (ALL) fire.
  return output_selection(f, -1, 0);
}

long long stored_substeps_at_most(const OutputControl& f, int n_substeps) {
  std::vector<int> frequencies{f.every};
  for (const auto& specs : f.items)
    for (const OutputSpec& spec : specs) frequencies.push_back(spec.every);
  const long long n = std::max(n_substeps, 0);
  long long count = 0;
  bool last = false;  // some item is written at the last substep (frequency 0 or n >= 1)
  for (int every : frequencies) {
    if (every < 0) continue;
    last = true;
    if (every >= 1) count += n / every - (n % every == 0 ? 1 : 0);  // the last counted below
  }
  return std::min(n, count + (last && n > 0 ? 1 : 0));
}

std::vector<int> output_strides(const OutputControl& f) {
  std::vector<int> strides;
  if (f.every > 1) strides.push_back(f.every);
  for (const auto& specs : f.items)
    for (const OutputSpec& spec : specs)
      if (spec.every > 1) strides.push_back(spec.every);
  return strides;
}

OutputItem element_item_category(const std::string& name) {
  if (starts_with(name, "EPEL")) return OutputItem::EPEL;
  for (const char* stress : {"SX", "SY", "SZ", "S1", "S2", "S3", "SINT", "SEQV", "SAXL"})
    if (starts_with(name, stress)) return OutputItem::STRS;
  return OutputItem::MISC;
}

void apply_output_selection(const OutputSelection& s, const std::vector<int>& node_ids,
                            TimePoint& p) {
  mask_rows(s[OutputItem::NSOL], node_ids, p.displacement);
  mask_rows(s[OutputItem::VSOL], node_ids, p.velocity);
  mask_rows(s[OutputItem::ASOL], node_ids, p.acceleration);
  mask_rows(s[OutputItem::RSOL], node_ids, p.reaction);
  if (!s.any_element_item()) {
    p.element_results.clear();
    return;
  }
  for (auto& [family, table] : p.element_results) {
    for (Eigen::Index c = 0; c < table.values.cols(); ++c) {
      const IdSelection& sel =
          s[element_item_category(table.item_names[static_cast<std::size_t>(c)])];
      if (sel.all()) continue;
      for (std::size_t r = 0; r < table.element_ids.size(); ++r)
        if (!sel.contains(table.element_ids[r]))
          table.values(static_cast<Eigen::Index>(r), c) = kNaN;
    }
  }
}

const char* output_item_name(OutputItem item) {
  static const char* const names[kOutputItems] = {"NSOL", "V", "A", "RSOL", "STRS", "EPEL", "MISC"};
  return names[static_cast<int>(item)];
}

std::vector<std::string> describe_output(const OutputControl& f) {
  auto frequency = [](int every) -> std::string {
    if (every < 0) return "NONE";
    if (every == 0) return "LAST";
    if (every == 1) return "ALL";
    return fmt::format("every {} substeps and the last", every);
  };
  std::vector<std::string> lines;
  for (int i = 0; i < kOutputItems; ++i) {
    const auto& specs = f.items[static_cast<std::size_t>(i)];
    std::string line = fmt::format("{:<5} {}", output_item_name(static_cast<OutputItem>(i)),
                                   specs.empty() ? frequency(f.every) : "");
    for (std::size_t k = 0; k < specs.size(); ++k)
      line += fmt::format(
          "{}{} for {}", k == 0 ? "" : "; ", frequency(specs[k].every),
          specs[k].component.empty() ? std::string("all") : "component " + specs[k].component);
    lines.push_back(line);
  }
  return lines;
}

}  // namespace impactfe
