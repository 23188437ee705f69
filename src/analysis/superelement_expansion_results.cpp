// File-to-file superelement expansion: use-pass results file in, expanded results file out.
// Kept apart from expansion.cpp so that the in-memory expansion does not pull the results file.
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "analysis/superelement_expansion.h"
#include "core/errors.h"
#include "core/log.h"

namespace impactfe {

int expand_superelement_results(const std::string& sub_file, const std::string& use_results,
                                const std::string& out_results, const Vec3& acel) {
  const SuperelementExpansion expansion(read_superelement(sub_file));
  const SuperelementData& se = expansion.data();
  ResultsReader reader(use_results);
  std::map<int, int> row;
  for (std::size_t r = 0; r < reader.node_ids().size(); ++r)
    row[reader.node_ids()[r]] = static_cast<int>(r);
  std::vector<std::pair<int, int>> where;  // (table row, dof column) of each master
  for (const auto& m : se.masters) {
    auto it = row.find(m.key.node);
    if (it == row.end())
      throw InputError(fmt::format("{}: master node {} of superelement {} is not in the file",
                                   use_results, m.key.node, se.name));
    where.emplace_back(it->second, static_cast<int>(m.key.dof));
  }
  auto value = [](const Eigen::MatrixXd& table, int r, int c) {
    if (table.rows() <= r || table.cols() <= c) return 0.0;
    const double x = table(r, c);
    return std::isnan(x) ? 0.0 : x;
  };

  ResultsWriter writer(out_results, expansion.model());
  writer.begin_analysis(ResultsKind::Expansion, fmt::format("superelement {} expansion", se.name));
  writer.set_attribute("superelement_file", sub_file);
  writer.set_attribute("use_results", use_results);
  int written = 0;
  for (const auto& info : reader.analyses()) {
    if (info.kind != ResultsKind::Static && info.kind != ResultsKind::Transient &&
        info.kind != ResultsKind::ReducedTransient)
      continue;
    for (int k = 0; k < info.n_time_points; ++k) {
      const TimePoint use = reader.time_point(info.index, k);
      const int n = se.n_masters();
      VectorXd um(n), vm(n), am(n);
      for (int i = 0; i < n; ++i) {
        const auto [r, c] = where[static_cast<std::size_t>(i)];
        um(i) = value(use.displacement, r, c);
        vm(i) = value(use.velocity, r, c);
        am(i) = value(use.acceleration, r, c);
      }
      TimePoint p = expansion.time_point(use.time, um, vm, am, acel);
      p.load_step = use.load_step;
      p.substep = use.substep;
      writer.append(p);
      ++written;
    }
  }
  writer.set_attribute("n_expanded", static_cast<double>(written));
  writer.end_analysis("complete");
  Log::info("superelement {}: expanded {} time points into {}", se.name, written, out_results);
  return written;
}

}  // namespace impactfe
