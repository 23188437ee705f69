// Data of the `impactfe report` page (schema: docs/report.md). One pass over every stored time
// point finds the peaks (largest nodal response, most stressed element, most loaded gap) and
// keeps the frames of the 3-D view; the curves then come from the ResultsReader series, so they
// follow its analysis-merge rule (an expansion pass replaces the reduced run at its times), and
// are sampled to at most max_points points.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>

#include "core/errors.h"
#include "core/numbers.h"
#include "core/text.h"
#include "results/report.h"
#include "results/report_contact.h"
#include "results/report_mesh.h"
#include "results/report_units.h"

namespace impactfe {

namespace {

using json = nlohmann::ordered_json;
using Series = std::vector<std::pair<double, double>>;
constexpr const char* kAxes[3] = {"X", "Y", "Z"};
/// Values kept for the 3-D view (frames x (3 nodes + fields x elements)): ~2.5 MB of base64.
constexpr std::size_t kFrameValueBudget = 480000;
/// Curves per figure, nodes per body, gap curves and gap rows of the timeline.
constexpr std::size_t kMaxCurves = 8, kMaxBodyNodes = 4, kMaxGapCurves = 8, kMaxGapRows = 40;

/// {"label", "t", "y" (base64 float32), "n_stored", "n"} of a series sampled to max_points.
json curve(const std::string& label, const Series& series, int max_points) {
  const Series s = sample_min_max(series, max_points);
  std::vector<double> t, y;
  for (const auto& [ti, yi] : s) {
    t.push_back(ti);
    y.push_back(yi);
  }
  double peak = 0.0;
  for (const auto& p : series) peak = std::max(peak, std::abs(p.second));
  return {{"label", label},   {"n_stored", series.size()}, {"n", s.size()},
          {"peak_abs", peak}, {"t", float32_base64(t)},    {"y", float32_base64(y)}};
}

/// How an element family's rows are summarised: the stress measure whose peak picks the most
/// stressed element, the items plotted for it, and whether it is a gap (has a STAT item).
struct FamilyMeasure {
  std::vector<std::string> items;    // every item of the family
  std::vector<int> measure_columns;  // max |value| over these columns
  std::vector<std::string> plot_items;
  bool stress = false;  // measure is a stress (else a force, e.g. COMBIN14)
  bool gap = false;
  int forc_column = -1;
  int stat_column = -1;
};

FamilyMeasure family_measure(const std::vector<std::string>& items) {
  FamilyMeasure m;
  m.items = items;
  auto col = [&](const char* name) {
    auto it = std::find(items.begin(), items.end(), name);
    return it == items.end() ? -1 : static_cast<int>(it - items.begin());
  };
  m.forc_column = col("FORC");
  m.stat_column = col("STAT");
  m.gap = m.stat_column >= 0;
  auto use = [&](std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (int c = col(n); c >= 0) {
        m.measure_columns.push_back(c);
        m.plot_items.emplace_back(n);
      }
    return !m.measure_columns.empty();
  };
  if (use({"SEQV"}) || use({"SEQV_TOP", "SEQV_BOT"}) || use({"SAXL"})) {
    m.stress = true;
  } else if (m.gap) {
    if (m.forc_column >= 0) m.plot_items = {"FORC"};  // peak kept in Peaks::gap_force instead
  } else if (m.forc_column >= 0) {
    use({"FORC"});  // springs: the most loaded one gets a force figure
  }
  return m;
}

/// Peak values over every stored time point of every analysis.
struct Peaks {
  Eigen::MatrixXd node;           // n_nodes x 3: max |U_d|; NaN when never stored
  std::map<int, double> measure;  // element id -> max |stress| or |force| (FamilyMeasure)
  std::map<int, double> gap_force;
  std::map<int, FamilyMeasure> family_of;  // element id -> its family's measure
};

/// Element result fields of the 3-D view: name and, per family, the columns whose max it is.
struct Field {
  std::string name;
  std::map<std::string, std::vector<int>> columns;  // family -> columns
};

std::vector<Field> element_fields(const std::vector<TimePoint>& samples) {
  std::vector<Field> fields = {{"SEQV", {}}, {"SAXL", {}}, {"FORC", {}}, {"STAT", {}}};
  for (const auto& p : samples)
    for (const auto& entry : p.element_results) {
      // Not a structured binding: clang 14 cannot capture one in the lambda below.
      const std::string& family = entry.first;
      const auto& table = entry.second;
      auto col = [&](const char* name) {
        auto it = std::find(table.item_names.begin(), table.item_names.end(), name);
        return it == table.item_names.end() ? -1 : static_cast<int>(it - table.item_names.begin());
      };
      for (auto& f : fields) {
        std::vector<int> cols;
        if (f.name == "SEQV") {
          for (const char* n : {"SEQV", "SEQV_TOP", "SEQV_BOT"})
            if (col(n) >= 0) cols.push_back(col(n));
        } else if (col(f.name.c_str()) >= 0) {
          cols.push_back(col(f.name.c_str()));
        }
        if (!cols.empty()) f.columns[family] = cols;
      }
    }
  fields.erase(std::remove_if(fields.begin(), fields.end(),
                              [](const Field& f) { return f.columns.empty(); }),
               fields.end());
  return fields;
}

/// One time point of the 3-D view: which analysis and row it comes from.
struct FrameRef {
  double time;
  int analysis;
  int row;
};

/// The frames of the 3-D view: the time points of the analyses whose displacements are the
/// most complete (an expansion pass rather than the reduced run it expands), merged by time
/// with the later analysis winning, then evenly thinned to `max_frames` (last one kept).
std::vector<FrameRef> choose_frames(const ResultsReader& reader, const ReportMesh& mesh,
                                    std::size_t max_frames) {
  std::vector<std::pair<int, double>> completeness;  // analysis, fraction of finite U
  for (const auto& a : reader.analyses()) {
    if (!is_time_history(a.kind) || a.n_time_points == 0) continue;
    const TimePoint p = reader.time_point(a.index, a.n_time_points - 1);
    std::size_t finite = 0, total = 0;
    for (int i : mesh.used_nodes)
      for (int d = 0; d < 3; ++d, ++total) finite += std::isfinite(p.displacement(i, d)) ? 1 : 0;
    completeness.emplace_back(a.index, total ? double(finite) / double(total) : 0.0);
  }
  double best = 0.0;
  for (const auto& c : completeness) best = std::max(best, c.second);
  std::vector<FrameRef> all;
  for (const auto& [a, fraction] : completeness) {
    if (fraction < best * 0.999 || fraction == 0.0) continue;
    const auto times = reader.times(a);
    for (std::size_t k = 0; k < times.size(); ++k)
      all.push_back({times[k], a, static_cast<int>(k)});
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const FrameRef& x, const FrameRef& y) { return x.time < y.time; });
  std::vector<FrameRef> merged;
  for (const auto& f : all) {
    if (!merged.empty() && same_time(merged.back().time, f.time) &&
        merged.back().analysis < f.analysis)
      merged.back() = f;  // the later analysis wins, as in ResultsReader's series
    else
      merged.push_back(f);
  }
  if (merged.size() <= max_frames) return merged;
  std::vector<FrameRef> thinned;
  for (std::size_t i = 0; i < max_frames; ++i)
    thinned.push_back(merged[i * (merged.size() - 1) / (max_frames - 1)]);
  return thinned;
}

/// Everything gathered in the single pass over the stored time points.
struct Pass {
  Peaks peaks;
  json energy = json::array();
  std::vector<TimePoint> frames;  // the chosen frames, in frame order
};

Pass scan_time_points(const ResultsReader& reader, const std::vector<FrameRef>& frames,
                      int max_points, ContactForceSums& contact) {
  Pass pass;
  const auto n_nodes = static_cast<Eigen::Index>(reader.node_ids().size());
  pass.peaks.node = Eigen::MatrixXd::Constant(n_nodes, 3, kNaN);
  std::map<std::pair<int, int>, std::size_t> frame_slot;
  for (std::size_t f = 0; f < frames.size(); ++f)
    frame_slot[{frames[f].analysis, frames[f].row}] = f;
  pass.frames.resize(frames.size());
  // The kinetic energy of the initial velocities (IC), put in like external work: the kinetic
  // energy of the initial state (load step 0) a transient stores first. A transient without one
  // continues the run before it in the file (ANTYPE,,RESTART) and carries its T0 (0 when the
  // file does not hold that run); static analyses start at rest.
  double run_t0 = 0.0;
  for (const auto& a : reader.analyses()) {
    if (!is_time_history(a.kind)) continue;
    std::vector<double> t;
    std::map<std::string, std::vector<double>> energy;
    std::optional<double> initial_kinetic;
    for (int k = 0; k < a.n_time_points; ++k) {
      TimePoint p = reader.time_point(a.index, k);
      for (Eigen::Index i = 0; i < n_nodes; ++i)
        for (int d = 0; d < 3; ++d) {
          const double v = p.displacement(i, d);
          if (!std::isfinite(v)) continue;
          double& peak = pass.peaks.node(i, d);
          peak = std::isfinite(peak) ? std::max(peak, std::abs(v)) : std::abs(v);
        }
      for (const auto& [family, table] : p.element_results) {
        const FamilyMeasure m = family_measure(table.item_names);
        for (std::size_t e = 0; e < table.element_ids.size(); ++e) {
          const int id = table.element_ids[e];
          const auto row = static_cast<Eigen::Index>(e);
          pass.peaks.family_of.emplace(id, m);
          for (int c : m.measure_columns)
            if (const double v = table.values(row, c); std::isfinite(v))
              pass.peaks.measure[id] = std::max(pass.peaks.measure[id], std::abs(v));
          if (m.gap && m.forc_column >= 0)
            if (const double v = table.values(row, m.forc_column); std::isfinite(v))
              pass.peaks.gap_force[id] = std::max(pass.peaks.gap_force[id], std::abs(v));
        }
      }
      contact.add(p);
      if (p.energy.count("external_work") && p.energy.count("kinetic")) {
        if (p.load_step == 0 && !initial_kinetic && std::isfinite(p.energy.at("kinetic")))
          initial_kinetic = p.energy.at("kinetic");
        t.push_back(p.time);
        for (const char* name : kEnergyNames)
          energy[name].push_back(p.energy.count(name) ? p.energy.at(name) : kNaN);
      }
      if (auto it = frame_slot.find({a.index, k}); it != frame_slot.end())
        pass.frames[it->second] = std::move(p);
    }
    if (t.empty()) continue;
    if (initial_kinetic) run_t0 = *initial_kinetic;
    const double t0 = a.kind == ResultsKind::Transient ? run_t0 : 0.0;
    // Numerical dissipation: the remainder of the balance, T0 + W_ext - (T + U + W_gap + D + W_p),
    // the energy the integrator removed (Houbolt damps the high modes; thesis Fig. 3-4).
    std::vector<double> remainder(t.size());
    for (std::size_t k = 0; k < t.size(); ++k) {
      double sum = 0.0;
      for (const char* name : {"kinetic", "strain", "gap_work", "dissipation", "plastic_work"})
        if (std::isfinite(energy[name][k])) sum += energy[name][k];
      remainder[k] = t0 + energy["external_work"][k] - sum;
    }
    energy["numerical_dissipation"] = remainder;
    json e = {{"analysis", a.index}, {"description", a.description}, {"curves", json::array()}};
    json final_values = json::object();
    for (const auto& name : {"kinetic", "strain", "external_work", "gap_work", "dissipation",
                             "plastic_work", "numerical_dissipation"}) {
      Series s;
      for (std::size_t k = 0; k < t.size(); ++k)
        if (std::isfinite(energy[name][k])) s.emplace_back(t[k], energy[name][k]);
      if (s.size() < 2) continue;
      e["curves"].push_back(curve(name, s, max_points));
      final_values[name] = s.back().second;
    }
    if (e["curves"].empty()) continue;  // a single static point: no balance over time
    if (t0 != 0.0) final_values["initial_kinetic"] = t0;
    e["final"] = final_values;
    e["time_final"] = t.back();
    pass.energy.push_back(std::move(e));
  }
  return pass;
}

/// Stress items (SX .. SEQV, SAXL, SEQV_TOP, ...) share one figure; STAT, STRETCH, SLIDE and
/// the strain energy SENE are not stresses.
bool is_stress_item(const std::string& item) {
  return item.size() >= 2 && item[0] == 'S' && item != "STAT" && item != "STRETCH" &&
         item != "SLIDE" && item != "SENE";
}

/// "element 39 (SHELL63)" or "elements 39 (SHELL63), 73 (SOLID45)" from the curves' labels
/// ("Element 39 (SHELL63) SEQV_TOP").
std::string element_names(const json& series) {
  std::vector<std::string> ids;
  for (const auto& s : series) {
    const std::string label = s["label"];
    const std::string id = label.substr(8, label.find(')') - 7);
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  std::string list;
  for (const auto& id : ids) list += (list.empty() ? "" : ", ") + id;
  return fmt::format("element{} {}", ids.size() == 1 ? "" : "s", list);
}

std::string dof_label(const char* prefix, int d) {
  return std::string(prefix) + kAxes[d];
}

/// Nodal time-history figures: displacement, velocity, acceleration of each node group.
json nodal_figures(const ResultsReader& reader, const std::vector<std::vector<int>>& groups,
                   const std::vector<std::string>& group_names, const std::vector<int>& dirs,
                   int max_points) {
  json figures = json::array();
  static const struct {
    const char* prefix;
    const char* quantity;
  } quantities[] = {{"U", "Displacement"}, {"V", "Velocity"}, {"A", "Acceleration"}};
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (const auto& q : quantities) {
      json series = json::array();
      for (int node : groups[g])
        for (int d : dirs) {
          const Series s = reader.nodal_series(node, dof_label(q.prefix, d));
          if (s.size() >= 2 && series.size() < kMaxCurves)  // one point is no history
            series.push_back(
                curve(fmt::format("Node {} {}", node, dof_label(q.prefix, d)), s, max_points));
        }
      if (series.empty()) continue;
      const std::string comp =
          dirs.size() == 1 ? fmt::format(" {}", dof_label(q.prefix, dirs[0])) : std::string();
      figures.push_back(
          {{"group", "nodal"},
           {"title", fmt::format("{}{} of {} vs time", q.quantity, comp, group_names[g])},
           {"xlabel", "Time"},
           {"ylabel", fmt::format("{}{}", q.quantity, comp)},
           {"series", std::move(series)}});
    }
  return figures;
}

/// The mesh of the 3-D view: coordinates once, connectivity as node indices.
json report_mesh_json(const ReportMesh& mesh, const ResultsReader& reader) {
  const Eigen::MatrixXd xyz = reader.node_coordinates();
  std::vector<double> coords;
  for (Eigen::Index i = 0; i < xyz.rows(); ++i)
    for (int d = 0; d < 3; ++d) coords.push_back(xyz(i, d));
  std::vector<std::string> types;
  for (const auto& e : reader.elements()) types.push_back(e.type_name);
  json bodies = json::array();
  for (const auto& b : mesh.bodies)
    bodies.push_back({{"name", b.name}, {"n_nodes", b.nodes.size()}});
  return {{"node_ids", reader.node_ids()},
          {"xyz", float32_base64(coords)},
          {"element_ids", mesh.element_ids},
          {"element_types", types},
          {"triangles", mesh.triangles},
          {"triangle_element", mesh.triangle_element},
          {"edges", mesh.edges},
          {"lines", mesh.lines},
          {"line_element", mesh.line_element},
          {"points", mesh.points},
          {"point_element", mesh.point_element},
          {"overlay_triangles", mesh.overlay_triangles},
          {"overlay_element", mesh.overlay_element},
          {"framed_nodes", mesh.framed_nodes},
          {"bodies", bodies}};
}

/// The directions (UX .. AZ: X, Y, Z) and the element items of --item.
struct RequestedItems {
  std::vector<int> dirs;
  std::vector<std::string> items;
};

RequestedItems requested_items(const ReportOptions& options) {
  RequestedItems out;
  for (const auto& raw : options.items) {
    const std::string item = to_upper(raw);
    const bool nodal = item.size() == 2 && std::string("UVA").find(item[0]) != std::string::npos &&
                       item[1] >= 'X' && item[1] <= 'Z';
    if (nodal) {
      if (std::find(out.dirs.begin(), out.dirs.end(), item[1] - 'X') == out.dirs.end())
        out.dirs.push_back(item[1] - 'X');
    } else {
      out.items.push_back(item);
    }
  }
  return out;
}

json analyses_json(const std::vector<ResultsReader::AnalysisInfo>& analyses) {
  json an = json::array();
  for (const auto& a : analyses)
    an.push_back({{"index", a.index},
                  {"kind", results_kind_name(a.kind)},
                  {"description", a.description},
                  {"status", a.status},
                  {"n_time_points", a.n_time_points},
                  {"time_first", a.time_first},
                  {"time_last", a.time_last},
                  {"n_gaps", a.n_gaps},
                  {"n_modes", a.n_modes},
                  {"element_families", a.element_families},
                  {"numeric", a.numeric_attributes},
                  {"text", a.text_attributes}});
  return an;
}

/// The directions of the nodal figures (the requested ones, else those whose peak reaches a
/// tenth of the largest) and the node groups they show.
struct NodalSelection {
  std::vector<int> dirs;
  std::vector<std::vector<int>> groups;
  std::vector<std::string> group_names;
};

/// Per body: the node with the largest response, then its moving gap nodes, most loaded gap
/// first (the helmet's crown, node 43, on the ground gap). A node whose peak equals one already
/// picked (a rigid part moves as one) would only hide under its curve: skipped.
std::vector<int> body_nodes(const ReportMesh::Body& body, const ReportMesh& mesh,
                            const std::vector<int>& node_ids,
                            const std::function<double(int)>& response,
                            std::map<int, double>& gap_load) {
  std::vector<int> by_response = body.nodes;
  std::stable_sort(by_response.begin(), by_response.end(),
                   [&](int a, int b) { return response(a) > response(b); });
  if (by_response.empty() || response(by_response.front()) <= 0.0) return {};
  std::vector<int> candidates = {by_response.front()};
  std::vector<int> gap_nodes;
  for (int idx : by_response)
    if (mesh.gap_nodes.count(idx) && response(idx) > 0.0) gap_nodes.push_back(idx);
  std::stable_sort(gap_nodes.begin(), gap_nodes.end(),
                   [&](int a, int b) { return gap_load[a] > gap_load[b]; });
  candidates.insert(candidates.end(), gap_nodes.begin(), gap_nodes.end());
  std::vector<int> picked, picked_index;
  for (int idx : candidates) {
    const bool same = std::any_of(picked_index.begin(), picked_index.end(), [&](int p) {
      return std::abs(response(p) - response(idx)) <= 1e-5 * response(p);
    });
    if (same) continue;
    picked_index.push_back(idx);
    picked.push_back(node_ids[static_cast<std::size_t>(idx)]);
    if (picked.size() >= kMaxBodyNodes) break;
  }
  std::sort(picked.begin(), picked.end());
  return picked;
}

NodalSelection nodal_selection(const ResultsReader& reader, const ReportMesh& mesh,
                               const Peaks& peaks, const ReportOptions& options,
                               const std::vector<int>& user_dirs) {
  const auto& node_ids = reader.node_ids();
  NodalSelection out;
  double largest = 0.0;
  for (Eigen::Index i = 0; i < peaks.node.rows(); ++i)
    for (int d = 0; d < 3; ++d)
      if (std::isfinite(peaks.node(i, d))) largest = std::max(largest, peaks.node(i, d));
  std::vector<int>& dirs = out.dirs;
  dirs = user_dirs;
  if (dirs.empty())
    for (int d = 0; d < 3; ++d) {
      double peak = 0.0;
      for (Eigen::Index i = 0; i < peaks.node.rows(); ++i)
        if (std::isfinite(peaks.node(i, d))) peak = std::max(peak, peaks.node(i, d));
      if (largest > 0.0 && peak >= 0.1 * largest) dirs.push_back(d);
    }
  const std::function<double(int)> response = [&](int index) {
    double r = 0.0;
    for (int d : dirs)
      if (std::isfinite(peaks.node(index, d))) r = std::max(r, peaks.node(index, d));
    return r;
  };
  if (!options.nodes.empty()) {
    out.groups.push_back(options.nodes);
    out.group_names.push_back(options.nodes.size() == 1 ? fmt::format("node {}", options.nodes[0])
                                                        : "the selected nodes");
  } else if (!dirs.empty()) {
    // Load on each node from its gaps: the peak |FORC| of the gap elements it belongs to.
    std::map<int, double> gap_load;  // node index -> peak gap force
    for (const auto& e : reader.elements()) {
      auto f = peaks.gap_force.find(e.id);
      if (!is_gap_type(e.type_name) || f == peaks.gap_force.end()) continue;
      for (int n : e.nodes)
        if (const int row = node_row(node_ids, n); row >= 0)
          gap_load[row] = std::max(gap_load[row], f->second);
    }
    for (const auto& body : mesh.bodies) {
      std::vector<int> picked = body_nodes(body, mesh, node_ids, response, gap_load);
      if (picked.empty()) continue;
      out.groups.push_back(picked);
      out.group_names.push_back(mesh.bodies.size() == 1 ? "the model" : body.name);
    }
  }
  return out;
}

/// Element figures: the requested elements, else the most stressed element of each element
/// type (gaps aside); stresses of one type share a figure, every other item has its own.
void add_element_figures(const ResultsReader& reader, const ReportMesh& mesh, const Peaks& peaks,
                         const ReportOptions& options, const std::vector<std::string>& user_items,
                         json& figures) {
  std::vector<int> stress_elements = options.elements;
  for (int e : stress_elements)
    if (!mesh.element_index.count(e))
      throw InputError(fmt::format("element {} is not in results file '{}'", e, reader.path()));
  if (stress_elements.empty()) {
    std::map<std::string, std::pair<int, double>> best;  // family type name -> element, peak
    for (const auto& [id, peak] : peaks.measure) {
      const auto& m = peaks.family_of.at(id);
      if (m.gap || peak <= 0.0) continue;
      const std::string key = reader.elements()[mesh.element_index.at(id)].type_name;
      if (!best.count(key) || peak > best[key].second) best[key] = {id, peak};
    }
    for (const auto& [type, pick] : best) stress_elements.push_back(pick.first);
  }
  // Curves by figure: stresses together, every other item in a figure of its own.
  std::map<std::string, json> by_figure;
  std::map<std::string, std::set<std::string>> figure_items;
  for (int e : stress_elements) {
    const auto& info = reader.elements()[mesh.element_index.at(e)];
    const auto fam = peaks.family_of.find(e);
    const FamilyMeasure* m = fam == peaks.family_of.end() ? nullptr : &fam->second;
    std::vector<std::string> items;
    for (const auto& item : user_items)  // chosen elements: every item must exist
      if (!options.elements.empty() ||
          (m && std::find(m->items.begin(), m->items.end(), item) != m->items.end()))
        items.push_back(item);
    if (items.empty() && m) items = m->plot_items;
    if (items.empty())
      throw InputError(fmt::format("no element results are stored for element {} ({}) in '{}'", e,
                                   info.type_name, reader.path()));
    for (const auto& item : items) {
      const Series s = reader.element_series(e, item);
      if (s.size() < 2) continue;
      const std::string key = is_stress_item(item) ? "stress|" + info.type_name : item;
      if (!by_figure.count(key)) by_figure[key] = json::array();
      by_figure[key].push_back(
          curve(fmt::format("Element {} ({}) {}", e, info.type_name, item), s, options.max_points));
      figure_items[key].insert(item);
    }
  }
  for (auto& [key, series] : by_figure) {
    const auto& items = figure_items[key];
    const std::string one = items.size() == 1 ? " " + *items.begin() : "";
    const bool stress = key.rfind("stress|", 0) == 0;  // one stress figure per element type
    const std::string title =
        fmt::format("{} of {} vs time", stress ? "Stress" : key, element_names(series));
    const std::string ylabel = stress ? "Stress" + one : key;
    figures.push_back({{"group", "element"},
                       {"title", title},
                       {"xlabel", "Time"},
                       {"ylabel", ylabel},
                       {"series", std::move(series)}});
  }
}

/// Gaps: forces of the most loaded gaps and gap conditions, the status timeline of each
/// (data["gap_force"], data["gap_status"]).
void add_gaps(const ResultsReader& reader, const ReportMesh& mesh, const Peaks& peaks,
              const std::vector<ResultsReader::AnalysisInfo>& analyses, int max_points,
              json& data) {
  std::vector<std::pair<int, double>> gaps(peaks.gap_force.begin(), peaks.gap_force.end());
  std::stable_sort(gaps.begin(), gaps.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  json gap_curves = json::array(), rows = json::array();
  std::size_t n_gap_rows = 0;
  for (const auto& [id, peak] : gaps) {
    const auto& type = reader.elements()[mesh.element_index.at(id)].type_name;
    if (!is_gap_type(type)) continue;
    const Series s = reader.element_series(id, "FORC");
    if (gap_curves.size() < kMaxGapCurves && s.size() >= 2)
      gap_curves.push_back(curve(fmt::format("Element {} ({}) FORC", id, type), s, max_points));
  }
  std::vector<int> gap_ids;  // gaps only: contact elements are summed per pair instead
  for (const auto& [id, m] : peaks.family_of)
    if (m.gap && is_gap_type(reader.elements()[mesh.element_index.at(id)].type_name))
      gap_ids.push_back(id);
  auto status_changes = [](const Series& s, bool from_force) {
    json changes = json::array();
    double last = kNaN;
    for (const auto& [t, v] : s) {
      const double state = from_force ? (v != 0.0 ? 1.0 : 0.0) : v;
      if (state != last) changes.push_back({t, state});
      last = state;
    }
    return changes;
  };
  for (int id : gap_ids) {
    if (++n_gap_rows > kMaxGapRows) break;
    const auto& type = reader.elements()[mesh.element_index.at(id)].type_name;
    rows.push_back({{"label", fmt::format("Element {} ({})", id, type)},
                    {"changes", status_changes(reader.element_series(id, "STAT"), false)}});
  }
  int n_conditions = 0;
  for (const auto& a : analyses) n_conditions = std::max(n_conditions, a.n_gaps);
  for (int g = 1; g <= n_conditions; ++g) {
    const Series s = reader.gap_force_series(g);
    if (gap_curves.size() < kMaxGapCurves && s.size() >= 2)
      gap_curves.push_back(curve(fmt::format("Gap condition {} force", g), s, max_points));
    if (++n_gap_rows <= kMaxGapRows)
      rows.push_back(
          {{"label", fmt::format("Gap condition {}", g)}, {"changes", status_changes(s, true)}});
  }
  data["gap_force"] = gap_curves.empty()
                          ? json()
                          : json{{"title", "Gap force vs time (negative: compression)"},
                                 {"xlabel", "Time"},
                                 {"ylabel", "Gap force"},
                                 {"series", std::move(gap_curves)}};
  data["gap_status"] = {{"rows", std::move(rows)},
                        {"n_gaps", gap_ids.size() + static_cast<std::size_t>(n_conditions)}};
}

/// Contact pairs: ΣFN and ΣFT of each pair vs time (data["contact_force"]), the pairs with the
/// largest peak normal force first, and the first time a pair carries force.
void add_contact_forces(const ContactForceSums& contact, int max_points, json& data) {
  auto pairs = contact.pairs();
  auto peak = [](const ContactForceSums::Series& s) {
    double m = 0.0;
    for (const auto& [t, v] : s) m = std::max(m, std::abs(v));
    return m;
  };
  std::stable_sort(pairs.begin(), pairs.end(),
                   [&](const auto& a, const auto& b) { return peak(a.normal) > peak(b.normal); });
  json figures = json::array();
  double first = kNaN;
  for (const auto& pair : pairs) {
    for (const auto& [t, v] : pair.normal)
      if (v != 0.0 && !(t >= first)) first = t;
    if (pair.normal.size() < 2) continue;
    json series = json::array();
    series.push_back(curve("normal ΣFN", pair.normal, max_points));
    if (peak(pair.friction) > 0.0)
      series.push_back(curve("friction ΣFT", pair.friction, max_points));
    figures.push_back(
        {{"group", "contact"},
         {"title", fmt::format("Contact force of pair {} ({} contact elements) vs time", pair.real,
                               pair.n_elements)},
         {"xlabel", "Time"},
         {"ylabel", "Contact force"},
         {"series", std::move(series)}});
  }
  data["contact_force"] = std::move(figures);
  data["first_contact_time"] = std::isfinite(first) ? json(first) : json();
}

/// Units of the axes from /UNITS (report_units.h): appended to every figure's axis labels, and
/// data["units"] for the page's own labels (energy). Nothing when the deck gave no /UNITS.
void label_units(const std::string& system, json& data) {
  const auto units = unit_labels(system);
  if (!units) {
    data["units"] = json();
    return;
  }
  data["units"] = {{"system", system},      {"time", units->time},     {"length", units->length},
                   {"force", units->force}, {"stress", units->stress}, {"energy", units->energy}};
  auto label = [&](json& figure) {
    for (const char* axis : {"xlabel", "ylabel"}) {
      if (!figure.contains(axis) || !figure[axis].is_string()) continue;
      const std::string text = figure[axis];
      if (const std::string u = unit_of_quantity(*units, text); !u.empty())
        figure[axis] = fmt::format("{} ({})", text, u);
    }
  };
  for (json& f : data["figures"]) label(f);
  for (json& f : data["contact_force"]) label(f);
  if (data["gap_force"].is_object()) label(data["gap_force"]);
}

/// Frequencies and the first 20 mode shapes.
json modes_json(const ResultsReader& reader) {
  const auto freqs = reader.frequencies();
  json modes = {{"frequencies", freqs}};
  if (!freqs.empty()) {
    std::vector<double> shapes;
    const int n_shapes = std::min<int>(static_cast<int>(freqs.size()), 20);
    for (int m = 1; m <= n_shapes; ++m) {
      const Eigen::MatrixXd s = reader.mode_shape(m);
      for (Eigen::Index i = 0; i < s.rows(); ++i)
        for (int d = 0; d < 3; ++d) shapes.push_back(s(i, d));
    }
    modes["n_shapes"] = n_shapes;
    modes["shapes"] = float32_base64(shapes);
  }
  return modes;
}

/// The 3-D view's frames: displacements and element fields (the max over a field's columns).
json frames_json(const ReportMesh& mesh, const std::vector<TimePoint>& frames,
                 const std::vector<FrameRef>& frame_refs) {
  const std::vector<Field> fields = element_fields(frames);
  std::vector<double> u, times;
  std::vector<std::vector<double>> field_values(fields.size());
  for (const auto& p : frames) {
    times.push_back(p.time);
    for (Eigen::Index i = 0; i < p.displacement.rows(); ++i)
      for (int d = 0; d < 3; ++d) u.push_back(p.displacement(i, d));
    for (std::size_t f = 0; f < fields.size(); ++f) {
      std::vector<double> row(mesh.element_ids.size(), kNaN);
      for (const auto& [family, table] : p.element_results) {
        auto cols = fields[f].columns.find(family);
        if (cols == fields[f].columns.end()) continue;
        for (std::size_t e = 0; e < table.element_ids.size(); ++e) {
          auto idx = mesh.element_index.find(table.element_ids[e]);
          if (idx == mesh.element_index.end()) continue;
          double v = kNaN;
          for (int c : cols->second) {
            const double x = table.values(static_cast<Eigen::Index>(e), c);
            if (std::isfinite(x)) v = std::isfinite(v) ? std::max(v, x) : x;
          }
          row[idx->second] = v;
        }
      }
      field_values[f].insert(field_values[f].end(), row.begin(), row.end());
    }
  }
  json frame_json = {{"times", times}, {"U", float32_base64(u)}, {"fields", json::array()}};
  std::set<int> frame_analyses;
  for (const auto& f : frame_refs) frame_analyses.insert(f.analysis);
  frame_json["analyses"] = frame_analyses;
  for (std::size_t f = 0; f < fields.size(); ++f)
    frame_json["fields"].push_back(
        {{"name", fields[f].name}, {"values", float32_base64(field_values[f])}});
  return frame_json;
}

}  // namespace

std::string report_data_json(const ResultsReader& reader, const ReportOptions& options) {
  if (options.max_points < 4) throw InputError("--max-points must be at least 4");
  if (options.max_frames < 2) throw InputError("--frames must be at least 2");
  const auto& node_ids = reader.node_ids();
  const auto analyses = reader.analyses();
  const ReportMesh mesh = build_report_mesh(reader);
  const RequestedItems requested = requested_items(options);
  for (int node : options.nodes)
    if (node_row(node_ids, node) < 0)
      throw InputError(fmt::format("node {} is not in results file '{}'", node, reader.path()));

  // Frames of the 3-D view within the value budget, then the single pass.
  std::size_t per_frame = 3 * node_ids.size() + 4 * mesh.element_ids.size();
  std::size_t max_frames =
      std::min<std::size_t>(static_cast<std::size_t>(options.max_frames),
                            std::max<std::size_t>(2, kFrameValueBudget / per_frame));
  const auto frame_refs = choose_frames(reader, mesh, max_frames);
  ContactForceSums contact(reader);
  Pass pass = scan_time_points(reader, frame_refs, options.max_points, contact);
  const Peaks& peaks = pass.peaks;

  json data;
  data["format"] = "impactfe-report";
  data["format_version"] = 1;
  data["file"] = reader.path();
  data["title"] = reader.title();
  data["n_nodes"] = node_ids.size();
  data["n_elements"] = reader.elements().size();
  data["analyses"] = analyses_json(analyses);
  data["energy"] = std::move(pass.energy);

  const NodalSelection nodal = nodal_selection(reader, mesh, peaks, options, requested.dirs);
  data["selection"] = {{"nodes_auto", options.nodes.empty()},
                       {"elements_auto", options.elements.empty()},
                       {"directions_auto", requested.dirs.empty()}};
  data["directions"] = json::array();
  for (int d : nodal.dirs) data["directions"].push_back(kAxes[d]);
  json figures =
      nodal_figures(reader, nodal.groups, nodal.group_names, nodal.dirs, options.max_points);
  add_element_figures(reader, mesh, peaks, options, requested.items, figures);
  data["figures"] = std::move(figures);
  add_gaps(reader, mesh, peaks, analyses, options.max_points, data);
  add_contact_forces(contact, options.max_points, data);
  label_units(reader.units(), data);
  data["modes"] = modes_json(reader);
  data["mesh"] = report_mesh_json(mesh, reader);
  data["frames"] = frames_json(mesh, pass.frames, frame_refs);
  // Titles of old decks may hold bytes that are not UTF-8: replaced, not an exception.
  return data.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace impactfe
