// The superelement expansion pass on results files: the use pass's master histories in, the
// expanded substructure results out. Kept apart from superelement_expansion.cpp so that the
// in-memory expansion does not pull the results reader.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "analysis/superelement_expansion.h"
#include "core/errors.h"
#include "core/files.h"
#include "core/log.h"
#include "time/time_axis.h"

namespace impactfe {

namespace {

std::string existing_file(const std::string& name, const char* extension,
                          const SourceLocation& where, const char* what) {
  for (const std::string& candidate : {name + extension, name})
    if (file_exists(candidate)) return candidate;
  throw InputError(where,
                   fmt::format("{} '{}' not found (looked for {}{} and {} in {})", what, name, name,
                               extension, name, std::filesystem::current_path().string()));
}

}  // namespace

std::string superelement_file_of(const SuperelementExpansionSource& source) {
  return existing_file(source.name, ".sub.h5", source.where, "superelement file");
}

std::string use_results_file_of(const SuperelementExpansionSource& source) {
  return existing_file(source.use_file, ".h5", source.where, "use-pass results file");
}

int expand_superelement_use_pass(const SuperelementExpansion& expansion, const ResultsReader& use,
                                 const ExpansionPassRequest& request, ResultsWriter& writer) {
  const SuperelementData& se = expansion.data();
  std::map<int, int> row;
  for (std::size_t r = 0; r < use.node_ids().size(); ++r)
    row[use.node_ids()[r]] = static_cast<int>(r);
  std::vector<std::pair<int, int>> where;  // (table row, dof column) of each master
  for (const auto& m : se.masters) {
    auto it = row.find(m.key.node);
    if (it == row.end())
      throw InputError(request.where,
                       fmt::format("{}: master node {} of superelement {} is not in the use pass",
                                   use.path(), m.key.node, se.name));
    where.emplace_back(it->second, static_cast<int>(m.key.dof));
  }
  auto value = [](const Eigen::MatrixXd& table, int r, int c) {
    if (table.rows() <= r || table.cols() <= c) return 0.0;
    const double x = table(r, c);
    return std::isnan(x) ? 0.0 : x;
  };

  // The use pass's solutions in time order (a later analysis wins at a repeated time).
  std::vector<std::pair<int, int>> solutions;  // (analysis, time point)
  std::vector<double> times;
  for (const auto& info : use.analyses()) {
    if (info.kind != ResultsKind::Static && info.kind != ResultsKind::Transient &&
        info.kind != ResultsKind::ReducedTransient)
      continue;
    const std::vector<double> t = use.times(info.index);
    for (int k = 0; k < info.n_time_points; ++k) {
      if (!times.empty() && same_time(times.back(), t[static_cast<std::size_t>(k)])) {
        solutions.back() = {info.index, k};
        continue;
      }
      solutions.emplace_back(info.index, k);
      times.push_back(t[static_cast<std::size_t>(k)]);
    }
  }
  if (solutions.empty())
    throw InputError(request.where, fmt::format("{}: the use pass stored no static or transient "
                                                "solution to expand",
                                                use.path()));
  const std::vector<int> selected = expansion_points(request.requests, times);

  writer.begin_analysis(ResultsKind::Expansion, fmt::format("superelement {} expansion", se.name));
  writer.set_attribute("use_results", use.path());
  int written = 0;
  const int n = se.n_masters();
  for (int index : selected) {
    const auto [analysis, k] = solutions[static_cast<std::size_t>(index)];
    const TimePoint used = use.time_point(analysis, k);
    VectorXd um(n), vm(n), am(n);
    for (int i = 0; i < n; ++i) {
      const auto [r, c] = where[static_cast<std::size_t>(i)];
      um(i) = value(used.displacement, r, c);
      vm(i) = value(used.velocity, r, c);
      am(i) = value(used.acceleration, r, c);
    }
    const Vec3 acel = request.static_correction && used.frame_acceleration
                          ? Vec3(*used.frame_acceleration)
                          : Vec3::Zero();
    TimePoint p = expansion.time_point(used.time, um, vm, am, acel);
    p.load_step = used.load_step;
    p.substep = used.substep;
    writer.append(std::move(p));
    ++written;
  }
  writer.set_count("n_expanded", static_cast<long long>(written));
  Log::info("superelement {}: expanded {} of the {} use-pass solutions", se.name, written,
            solutions.size());
  return written;
}

}  // namespace impactfe
