#include "results/result_sets.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/numbers.h"
#include "core/text.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

void index_elements(SetData& d) {
  d.element_rows.clear();
  for (const auto& [family, table] : d.point.element_results)
    for (std::size_t k = 0; k < table.element_ids.size(); ++k)
      d.element_rows[table.element_ids[k]] = {family, static_cast<int>(k)};
}

Eigen::MatrixXd blend(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double w) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return Eigen::MatrixXd::Constant(a.rows(), a.cols(), kNaN);
  return a + w * (b - a);  // NaN in either stays NaN
}

}  // namespace

std::vector<ResultSet> result_sets(const ResultsReader& reader) {
  std::vector<ResultSet> sets;
  const auto analyses = reader.analyses();
  for (std::size_t i = 0; i < analyses.size(); ++i) {
    const auto& a = analyses[i];
    if (a.kind == ResultsKind::Substructure) continue;
    if (a.kind == ResultsKind::Modal) {
      const auto freqs = reader.frequencies_of(a.index);
      for (int m = 1; m <= static_cast<int>(freqs.size()); ++m) {
        ResultSet s;
        s.analysis = a.index;
        s.mode = m;
        s.time = freqs[static_cast<std::size_t>(m - 1)];
        s.load_step = 1;
        s.substep = m;
        s.kind = a.kind;
        sets.push_back(s);
      }
      continue;
    }
    if (a.kind == ResultsKind::ReducedTransient) {
      // MAPDL's results file holds only the expanded solutions of a reduced run.
      const bool expanded =
          std::any_of(analyses.begin() + static_cast<long>(i) + 1, analyses.end(),
                      [](const auto& later) { return later.kind == ResultsKind::Expansion; });
      if (expanded) continue;
    }
    const auto steps = reader.load_steps_of(a.index);
    const auto times = reader.times(a.index);
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (steps[k].first == 0) continue;  // the initial state t = 0 is not a data set
      ResultSet s;
      s.analysis = a.index;
      s.point = static_cast<int>(k);
      s.time = times[k];
      s.load_step = steps[k].first;
      s.substep = steps[k].second;
      s.kind = a.kind;
      sets.push_back(s);
    }
  }
  for (std::size_t k = 0; k < sets.size(); ++k) sets[k].number = static_cast<int>(k) + 1;
  return sets;
}

SetData read_set(const ResultsReader& reader, const ResultSet& set) {
  SetData d;
  d.set = set;
  if (set.mode > 0) {
    d.point.time = set.time;
    d.point.load_step = set.load_step;
    d.point.substep = set.substep;
    d.point.displacement = reader.mode_shape_of(set.analysis, set.mode);
    const auto n = d.point.displacement.rows();
    d.point.velocity = Eigen::MatrixXd::Constant(n, 6, kNaN);
    d.point.acceleration = d.point.velocity;
    d.point.reaction = d.point.velocity;
    d.frequency = set.time;
    // MXPAND Elcalc YES: the mode's element results are the analysis's time point of the mode.
    const auto steps = reader.load_steps_of(set.analysis);
    for (std::size_t k = 0; k < steps.size(); ++k)
      if (steps[k].second == set.mode) {
        TimePoint mode = reader.time_point(set.analysis, static_cast<int>(k));
        d.point.element_results = std::move(mode.element_results);
        d.point.reaction = std::move(mode.reaction);
      }
  } else {
    d.point = reader.time_point(set.analysis, set.point);
  }
  d.reduced = set.kind == ResultsKind::ReducedTransient;
  index_elements(d);
  return d;
}

SetData interpolate_sets(const SetData& a, const SetData& b, double t) {
  SetData d = a;
  const double span = b.set.time - a.set.time;
  const double w = span != 0.0 ? (t - a.set.time) / span : 0.0;
  d.interpolated = true;
  d.set.number = 0;
  d.set.time = t;
  d.point.time = t;
  d.point.displacement = blend(a.point.displacement, b.point.displacement, w);
  d.point.velocity = blend(a.point.velocity, b.point.velocity, w);
  d.point.acceleration = blend(a.point.acceleration, b.point.acceleration, w);
  d.point.reaction = blend(a.point.reaction, b.point.reaction, w);
  d.point.element_results.clear();
  for (const auto& [family, ta] : a.point.element_results) {
    auto it = b.point.element_results.find(family);
    if (it == b.point.element_results.end() || it->second.element_ids != ta.element_ids) continue;
    ElementResultTable t2 = ta;
    t2.values = blend(ta.values, it->second.values, w);
    d.point.element_results[family] = std::move(t2);
  }
  d.reduced = a.reduced || b.reduced;
  index_elements(d);
  return d;
}

void scale_set(SetData& data, double factor) {
  data.point.displacement *= factor;
  data.point.velocity *= factor;
  data.point.acceleration *= factor;
  data.point.reaction *= factor;
  for (auto& [family, table] : data.point.element_results)
    for (std::size_t i = 0; i < table.item_names.size(); ++i)
      if (table.item_names[i] != "STAT") table.values.col(static_cast<Eigen::Index>(i)) *= factor;
}

std::optional<NodalLabel> parse_nodal_item(const std::string& label) {
  static const char* kU[] = {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"};
  static const char* kR[] = {"FX", "FY", "FZ", "MX", "MY", "MZ"};
  const std::string l = to_upper(label);
  for (int c = 0; c < 6; ++c) {
    if (l == kU[c]) return NodalLabel{'U', c};
    if (l == kR[c]) return NodalLabel{'R', c};
  }
  for (int c = 0; c < 3; ++c) {
    if (l == std::string("V") + static_cast<char>('X' + c)) return NodalLabel{'V', c};
    if (l == std::string("A") + static_cast<char>('X' + c)) return NodalLabel{'A', c};
  }
  if (l == "USUM") return NodalLabel{'U', -1};
  if (l == "ROTSUM") return NodalLabel{'U', -1, true};
  if (l == "VSUM") return NodalLabel{'V', -1};
  if (l == "ASUM") return NodalLabel{'A', -1};
  if (l == "RSUM" || l == "FSUM") return NodalLabel{'R', -1};
  if (l == "MSUM") return NodalLabel{'R', -1, true};
  return std::nullopt;
}

std::string nodal_label_of(const std::string& item_in, const std::string& comp_in) {
  const std::string item = to_upper(item_in), comp = to_upper(comp_in);
  if (comp.empty() && parse_nodal_item(item)) return item;  // NSOL,2,5,UX (direct label)
  const bool xyz = comp == "X" || comp == "Y" || comp == "Z" || comp == "SUM";
  if ((item == "U" || item == "V" || item == "A") && xyz) return item + comp;
  if (item == "VEL" && xyz) return "V" + comp;
  if (item == "ACC" && xyz) return "A" + comp;
  if (item == "ROT" && xyz) return "ROT" + comp;
  if ((item == "RF" || item == "F" || item == "M") && parse_nodal_item(comp)) return comp;
  if ((item == "F" || item == "M") && xyz) {
    if (comp == "SUM") return item == "F" ? "FSUM" : "MSUM";
    return item + comp;
  }
  return "";
}

double nodal_value(const SetData& data, int row, const NodalLabel& label) {
  const Eigen::MatrixXd* m = nullptr;
  switch (label.dataset) {
    case 'U':
      m = &data.point.displacement;
      break;
    case 'V':
      m = &data.point.velocity;
      break;
    case 'A':
      m = &data.point.acceleration;
      break;
    default:
      m = &data.point.reaction;
  }
  if (row < 0 || row >= m->rows()) return kNaN;
  if (label.column >= 0) return (*m)(row, label.column);
  const int c0 = label.rotation_sum ? 3 : 0;
  double sum = 0.0;
  bool any = false;
  for (int c = c0; c < c0 + 3; ++c) {
    const double v = (*m)(row, c);
    if (std::isfinite(v)) {
      sum += v * v;
      any = true;
    }
  }
  return any ? std::sqrt(sum) : kNaN;
}

bool nodal_row_written(const SetData& data, char dataset, int row) {
  const Eigen::MatrixXd& m = dataset == 'U'   ? data.point.displacement
                             : dataset == 'V' ? data.point.velocity
                                              : data.point.acceleration;
  if (m.size() == 0 || row < 0 || row >= m.rows()) return dataset != 'U';
  if (m.row(row).array().isFinite().any()) return true;
  if (dataset == 'U') return false;
  return !m.array().isFinite().any();  // V and A are absent altogether in a static set
}

std::optional<double> element_item(const SetData& data, int element, const std::string& type_name,
                                   const std::string& item, const std::string& comp) {
  const ElementTypeDescriptor* type = find_element_type(type_name);
  if (type == nullptr) return std::nullopt;
  const auto seq = find_result_sequence(*type, item, comp);
  if (!seq) return std::nullopt;
  const auto row = data.element_rows.find(element);
  if (row == data.element_rows.end()) return kNaN;
  const ElementResultTable& table = data.point.element_results.at(row->second.first);
  const auto col = std::find(table.item_names.begin(), table.item_names.end(), seq->name);
  if (col == table.item_names.end()) return kNaN;
  return table.values(row->second.second,
                      static_cast<Eigen::Index>(col - table.item_names.begin())) +
         seq->offset;
}

}  // namespace impactfe
