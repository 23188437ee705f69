// ResultsReader: reads the model section and the analysis index once, then time series and
// time points on demand (schema: docs/results_file.md).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/errors.h"
#include "core/numbers.h"
#include "core/text.h"
#include "io/h5_util.h"
#include "results/live_writers.h"
#include "results/results_file.h"

namespace impactfe {

using h5::check;
using h5::check_status;
using h5::Handle;

namespace {

ResultsKind parse_kind(const std::string& name, const std::string& path) {
  for (auto k : {ResultsKind::Static, ResultsKind::Modal, ResultsKind::Transient,
                 ResultsKind::ReducedTransient, ResultsKind::Expansion, ResultsKind::Substructure,
                 ResultsKind::Harmonic, ResultsKind::Spectrum})
    if (name == results_kind_name(k)) return k;
  throw InputError(fmt::format("results file '{}': unknown analysis kind '{}'", path, name));
}

/// Where a nodal label lives: dataset and column.
struct NodalLabel {
  const char* dataset;
  int column;
};

std::optional<NodalLabel> parse_nodal_label(const std::string& lab) {
  static const std::pair<const char*, NodalLabel> table[] = {
      {"UX", {"U", 0}},   {"UY", {"U", 1}},   {"UZ", {"U", 2}}, {"ROTX", {"U", 3}},
      {"ROTY", {"U", 4}}, {"ROTZ", {"U", 5}}, {"VX", {"V", 0}}, {"VY", {"V", 1}},
      {"VZ", {"V", 2}},   {"AX", {"A", 0}},   {"AY", {"A", 1}}, {"AZ", {"A", 2}},
      {"FX", {"R", 0}},   {"FY", {"R", 1}},   {"FZ", {"R", 2}}, {"MX", {"R", 3}},
      {"MY", {"R", 4}},   {"MZ", {"R", 5}}};
  const std::string u = to_upper(lab);
  for (const auto& [name, where] : table)
    if (u == name) return where;
  return std::nullopt;
}

struct Family {
  std::string name;
  std::vector<int> element_ids;
  std::vector<std::string> items;
};

struct Analysis {
  ResultsReader::AnalysisInfo info;
  std::string group;
  std::vector<double> times;
  std::vector<Family> families;
  /// Points from this index on are in the staging datasets under recent/ (a file whose analysis
  /// is being written or was killed); all points are in the main datasets otherwise.
  std::size_t first_recent_row = std::numeric_limits<std::size_t>::max();
  /// Sparse reactions (format 2): column of R per (node row, DOF); empty with a dense R.
  std::map<std::pair<std::size_t, int>, hsize_t> reaction_column;
  bool sparse_reactions = false;
  /// Every chunk of the main datasets is written (attribute all_chunks_written): a chunk the
  /// index does not find is a corrupted index entry, not values never given.
  bool all_chunks_written = false;
};

using Series = std::vector<std::pair<double, double>>;

/// The merge rule of nodal_series: finite values only; a later analysis replaces values at the
/// same time; the result is stably sorted by time.
void merge_into(Series& merged, Series later) {
  if (later.empty()) return;
  std::vector<double> later_times;
  for (const auto& p : later) later_times.push_back(p.first);
  std::sort(later_times.begin(), later_times.end());
  auto in_later = [&](double t) {
    const double tol = 2e-12 * std::max(1.0, std::abs(t));  // wider than same_time's window
    for (auto it = std::lower_bound(later_times.begin(), later_times.end(), t - tol);
         it != later_times.end() && *it <= t + tol; ++it)
      if (same_time(*it, t)) return true;
    return false;
  };
  merged.erase(std::remove_if(merged.begin(), merged.end(),
                              [&](const auto& p) { return in_later(p.first); }),
               merged.end());
  merged.insert(merged.end(), later.begin(), later.end());
}

}  // namespace

struct ResultsReader::Impl {
  std::string path;
  Handle file;
  std::string title;
  std::string units;
  std::vector<int> node_ids;
  Eigen::MatrixXd coords;
  std::vector<ElementInfo> elements;
  std::vector<Analysis> analyses;

  int node_index(int node) const {
    auto it = std::lower_bound(node_ids.begin(), node_ids.end(), node);
    if (it == node_ids.end() || *it != node)
      throw InputError(fmt::format("node {} is not in results file '{}'", node, path));
    return static_cast<int>(it - node_ids.begin());
  }

  const Analysis& analysis(int a) const {
    if (a < 1 || a > static_cast<int>(analyses.size()))
      throw InputError(fmt::format("results file '{}' has no analysis {} (it has {})", path, a,
                                   analyses.size()));
    return analyses[static_cast<std::size_t>(a - 1)];
  }

  /// Datasets stay open for the reader's life, so that their chunk caches keep the blocks read
  /// last: reading the time points of a block one after the other decompresses it once.
  mutable std::map<std::string, Handle> open_datasets;
  hid_t dataset(const std::string& name) const {
    auto it = open_datasets.find(name);
    if (it == open_datasets.end())
      it = open_datasets
               .emplace(name,
                        Handle(check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "open " + name)))
               .first;
    return it->second;
  }

  /// Rows [0, n_t) of the slab (start, count) after the time axis of a per-time-point dataset,
  /// NaN where absent: the finished points from the main dataset, the recent ones from the
  /// staging dataset of a file still being written (docs/results_file.md, "Storage").
  std::vector<double> rows(const Analysis& an, const std::string& dataset,
                           const std::vector<hsize_t>& start, const std::vector<hsize_t>& count,
                           std::size_t first, std::size_t n_rows) const {
    hsize_t per_row = 1;
    for (auto c : count) per_row *= c;
    std::vector<double> out(n_rows * per_row, kNaN);
    if (n_rows == 0 || per_row == 0) return out;
    const std::string main = an.group + "/" + dataset;
    const std::string recent = an.group + "/recent/" + dataset;
    auto read_part = [&](const std::string& name, hsize_t file_first, std::size_t out_first,
                         std::size_t n) {
      if (n == 0 || !h5::exists_path(file, name)) return;
      const hid_t ds = this->dataset(name);
      const auto dims = h5::dims_of(ds);
      if (dims.size() != count.size() + 1)
        throw std::runtime_error(fmt::format("dataset {} has rank {}", name, dims.size()));
      for (std::size_t i = 0; i < count.size(); ++i)
        if (start[i] + count[i] > dims[i + 1]) return;  // e.g. a reaction column added later
      if (file_first >= dims[0]) return;
      const hsize_t avail = std::min<hsize_t>(n, dims[0] - file_first);
      std::vector<hsize_t> st{file_first}, ct{avail};
      st.insert(st.end(), start.begin(), start.end());
      ct.insert(ct.end(), count.begin(), count.end());
      // Writers since chunk-index verification write every chunk of a main dataset (NaN
      // where absent); the staging rows of a block are written one by one.
      h5::verify_chunk_index(ds, st, ct, an.all_chunks_written && name == main);
      const auto v = h5::read_slab(ds, st, ct);
      std::copy(v.begin(), v.end(), out.begin() + static_cast<long>(out_first * per_row));
    };
    const std::size_t end = first + n_rows;
    const std::size_t split = std::clamp(an.first_recent_row, first, end);
    read_part(main, first, 0, split - first);
    if (split < end) read_part(recent, split - an.first_recent_row, split - first, end - split);
    return out;
  }

  /// Column `col` of row `index` of dataset (n_t, n, m) (or `index` of (n_t, n) when col < 0)
  /// over the analysis's time points.
  std::vector<double> column(const Analysis& an, const std::string& dataset, hsize_t index,
                             long col) const {
    if (col < 0) return rows(an, dataset, {index}, {1}, 0, an.times.size());
    return rows(an, dataset, {index, static_cast<hsize_t>(col)}, {1, 1}, 0, an.times.size());
  }

  /// The merged time series of column 3(index − 1) + component of a per-point dataset of three
  /// values per entity (contact_forces, part_energies), `count` entities per analysis; `noun`
  /// names an entity in the messages, `none` says when the file has none.
  Series triple_series(const std::string& dataset, int AnalysisInfo::*count, int index,
                       const std::string& item, const std::array<const char*, 3>& items,
                       const std::string& bad_item, const std::string& noun,
                       const std::string& none) const {
    const auto at = std::find(items.begin(), items.end(), item);
    if (at == items.end()) throw InputError(bad_item);
    const auto component = static_cast<int>(at - items.begin());
    Series merged;
    bool found = false;
    int most = 0;
    for (const auto& an : analyses) {
      most = std::max(most, an.info.*count);
      if (index < 1 || index > an.info.*count) continue;
      found = true;
      merge_into(
          merged,
          collect(an, column(an, dataset, static_cast<hsize_t>(3 * (index - 1) + component), -1)));
    }
    if (!found)
      throw InputError(most == 0 ? fmt::format("no {} are stored in '{}'", none, path)
                                 : fmt::format("{} {} does not exist (the results file has {}s "
                                               "1..{})",
                                               noun, index, noun, most));
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return merged;
  }

  Series collect(const Analysis& an, const std::vector<double>& values) const {
    Series s;
    for (std::size_t k = 0; k < values.size(); ++k)
      if (std::isfinite(values[k])) s.emplace_back(an.times[k], values[k]);
    return s;
  }

  /// Time series of DOF column `col` of node row `index` of U, V, A or R.
  std::vector<double> nodal_column(const Analysis& an, const std::string& dataset, hsize_t index,
                                   int col) const {
    if (dataset != "R" || !an.sparse_reactions) return column(an, dataset, index, col);
    auto it = an.reaction_column.find({static_cast<std::size_t>(index), col});
    if (it == an.reaction_column.end()) return std::vector<double>(an.times.size(), kNaN);
    return column(an, "R", it->second, -1);
  }

  /// Reads a full (n_nodes x 6) row of U/V/A (or a dense format-1 R) or a NaN matrix when absent.
  Eigen::MatrixXd nodal_row(const Analysis& an, const std::string& dataset, int k) const {
    const auto n = node_ids.size();
    const auto v = rows(an, dataset, {0, 0}, {n, 6}, static_cast<std::size_t>(k), 1);
    Eigen::MatrixXd m(static_cast<Eigen::Index>(n), 6);
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < 6; ++j) m(static_cast<Eigen::Index>(i), j) = v[i * 6 + j];
    return m;
  }

  /// The reactions of point k as an n_nodes x 6 table (NaN at unconstrained DOFs).
  Eigen::MatrixXd reaction_row(const Analysis& an, int k) const {
    if (!an.sparse_reactions) return nodal_row(an, "R", k);
    Eigen::MatrixXd m =
        Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(node_ids.size()), 6, kNaN);
    if (an.reaction_column.empty()) return m;
    const auto v = rows(an, "R", {0}, {an.reaction_column.size()}, static_cast<std::size_t>(k), 1);
    for (const auto& [where, c] : an.reaction_column)
      m(static_cast<Eigen::Index>(where.first), where.second) = v[c];
    return m;
  }

  /// Runs a query; an HDF5 failure (a checksum that does not match, a truncated file) becomes an
  /// InputError naming the file instead of numbers that are wrong.
  template <typename F>
  auto guarded(F f) const {
    try {
      return f();
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      damaged(e);
    }
  }

  /// Translates an HDF5 failure while reading into the program's words.
  [[noreturn]] void damaged(const std::exception& e) const {
    throw InputError(fmt::format(
        "results file '{}' is damaged or incomplete: {} (a corrupted block fails its checksum; "
        "re-run the job to rewrite it)",
        path, e.what()));
  }

  void load();
  void load_model();
  Analysis load_analysis(int k, const std::string& group) const;
};

namespace {

/// The links of an HDF5 group in creation order (name order where creation order is not
/// tracked).
std::vector<std::string> link_names(hid_t group) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t idx = 0;
  H5Literate(group, H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, collect, &names);
  if (names.empty()) H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names);
  return names;
}

}  // namespace

void ResultsReader::Impl::load() {
  if (H5Aexists(file, "format") <= 0 ||
      h5::read_string_attribute(file, "format") != "impactfe-results")
    throw InputError(fmt::format("'{}' is not an impactfe results file", path));
  const double version =
      H5Aexists(file, "format_version") > 0 ? h5::read_double_attribute(file, "format_version") : 1;
  if (version > kResultsFormatVersion)
    throw InputError(fmt::format(
        "results file '{}' has format version {}, written by a newer impactfe; this one reads "
        "versions 1 to {}",
        path, version, kResultsFormatVersion));
  load_model();
  for (int k = 1;; ++k) {
    std::string group = fmt::format("analysis_{}", k);
    if (!h5::exists(file, group)) break;
    analyses.push_back(load_analysis(k, group));
  }
}

void ResultsReader::Impl::load_model() {
  title = h5::read_string_attribute(file, "title");
  if (H5Aexists(file, "units") > 0) units = h5::read_string_attribute(file, "units");
  node_ids = h5::read_ints(file, "model/node_ids");
  auto xyz = h5::read_doubles(file, "model/node_coordinates");
  coords.resize(static_cast<Eigen::Index>(node_ids.size()), 3);
  for (std::size_t i = 0; i < node_ids.size(); ++i)
    for (int j = 0; j < 3; ++j) coords(static_cast<Eigen::Index>(i), j) = xyz[i * 3 + j];

  auto ids = h5::read_ints(file, "model/element_ids");
  auto names = h5::read_strings(file, "model/element_type_names");
  auto types = h5::read_ints(file, "model/element_types");
  auto mats = h5::read_ints(file, "model/element_materials");
  auto reals = h5::read_ints(file, "model/element_reals");
  auto nodes = h5::read_ints(file, "model/element_nodes");
  const std::size_t width = ids.empty() ? 0 : nodes.size() / ids.size();
  for (std::size_t e = 0; e < ids.size(); ++e) {
    ElementInfo info{ids[e], names[e], types[e], mats[e], reals[e], {}};
    for (std::size_t i = 0; i < width; ++i)
      if (int n = nodes[e * width + i]; n != 0) info.nodes.push_back(n);
    elements.push_back(std::move(info));
  }
}

Analysis ResultsReader::Impl::load_analysis(int k, const std::string& group) const {
  Handle g(check(H5Gopen2(file, group.c_str(), H5P_DEFAULT), "open group " + group));
  Analysis an;
  an.group = group;
  an.info.index = k;
  an.info.kind = parse_kind(h5::read_string_attribute(g, "kind"), path);
  an.info.description = h5::read_string_attribute(g, "description");
  an.info.status = h5::read_string_attribute(g, "status");
  for (const auto& name : h5::attribute_names(g)) {
    if (name == "kind" || name == "description" || name == "status" || name == "block_rows" ||
        name == "all_chunks_written")
      continue;  // storage details
    Handle attr(check(H5Aopen(g, name.c_str(), H5P_DEFAULT), "open attribute " + name));
    Handle type(check(H5Aget_type(attr), "get attribute type"));
    const auto cls = H5Tget_class(type);
    if (cls == H5T_STRING) {
      an.info.text_attributes[name] = h5::read_string_attribute(g, name);
    } else if (cls == H5T_FLOAT || cls == H5T_INTEGER) {
      double v = 0.0;
      check_status(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
      an.info.numeric_attributes[name] = v;
    }
  }
  an.all_chunks_written = H5Aexists(g, "all_chunks_written") > 0;
  if (h5::exists(g, "time")) an.times = h5::read_doubles(g, "time");
  an.info.n_time_points = static_cast<int>(an.times.size());
  if (!an.times.empty()) {
    an.info.time_first = an.times.front();
    an.info.time_last = an.times.back();
  }
  if (h5::exists(g, "recent") && H5Aexists_by_name(g, "recent", "first_row", H5P_DEFAULT) > 0) {
    Handle rg(check(H5Gopen2(g, "recent", H5P_DEFAULT), "open group recent"));
    an.first_recent_row = static_cast<std::size_t>(h5::read_double_attribute(rg, "first_row"));
  }
  if (h5::exists(g, "reaction_dofs")) {
    an.sparse_reactions = true;
    const auto rd = h5::read_ints(g, "reaction_dofs");
    for (std::size_t c = 0; c + 1 < rd.size(); c += 2) {
      auto it = std::lower_bound(node_ids.begin(), node_ids.end(), rd[c]);
      if (it == node_ids.end() || *it != rd[c] || rd[c + 1] < 0 || rd[c + 1] > 5)
        throw std::runtime_error("reaction_dofs names a node or DOF the model does not have");
      an.reaction_column[{static_cast<std::size_t>(it - node_ids.begin()), rd[c + 1]}] = c / 2;
    }
  }
  if (h5::exists(g, "gap_forces")) {
    Handle ds(check(H5Dopen2(g, "gap_forces", H5P_DEFAULT), "open gap_forces"));
    an.info.n_gaps = static_cast<int>(h5::dims_of(ds).at(1));
  }
  // Three values per entity: the explicit contacts' forces, the parts' energies.
  for (const auto& [dataset, count] : {std::pair{"contact_forces", &an.info.n_contacts},
                                       std::pair{"part_energies", &an.info.n_parts}}) {
    if (!h5::exists(g, dataset)) continue;
    Handle ds(check(H5Dopen2(g, dataset, H5P_DEFAULT), std::string("open ") + dataset));
    const hsize_t columns = h5::dims_of(ds).at(1);
    if (columns % 3 != 0)
      throw std::runtime_error(std::string(dataset) + " has a column count that is not 3 each");
    *count = static_cast<int>(columns / 3);
  }
  if (h5::exists(g, "frequencies")) {
    Handle fds(check(H5Dopen2(g, "frequencies", H5P_DEFAULT), "open frequencies"));
    an.info.n_modes = static_cast<int>(h5::dims_of(fds).at(0));
  }
  if (h5::exists(g, "elements")) {
    Handle eg(check(H5Gopen2(g, "elements", H5P_DEFAULT), "open elements group"));
    for (const auto& fname : link_names(eg)) {
      Handle fg(check(H5Gopen2(eg, fname.c_str(), H5P_DEFAULT), "open family " + fname));
      Family f{fname, h5::read_ints(fg, "element_ids"),
               h5::read_string_list_attribute(fg, "items")};
      an.info.element_families.push_back(fname);
      an.families.push_back(std::move(f));
    }
  }
  return an;
}

int node_row(const std::vector<int>& node_ids, int node) {
  auto it = std::lower_bound(node_ids.begin(), node_ids.end(), node);
  return it == node_ids.end() || *it != node ? -1 : static_cast<int>(it - node_ids.begin());
}

ResultsReader::ResultsReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  h5::silence_errors();
  impl_->path = path;
  // A writer of this process syncs first: its buffered points are part of the file, and on its
  // writer thread the file may not yet be renamed into place (ResultsWriter's constructor).
  sync_live_writer(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("results file '{}' does not exist", path));
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError(fmt::format("'{}' is not an impactfe results file (not HDF5)", path));
  // Default access first: in the same process this shares the file a live ResultsWriter has
  // open. Another process's running job holds the file lock: then read without taking it.
  // Chunk cache per dataset: a whole block (at most 64 MB for all quantities, see the writer).
  Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "create file access list"));
  H5Pset_cache(fapl, 0, 4099, 64u << 20, 0.75);
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (f < 0) {
    H5Pset_file_locking(fapl, false, true);
    f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  }
  if (f < 0) {
    const std::string detail = h5::error_detail();
    if (detail.find("truncated") != std::string::npos)
      throw InputError(fmt::format(
          "results file '{}' is truncated ({} bytes; HDF5 says: {}): the run that wrote it "
          "stopped while the file grew, or the file was cut short when copied",
          path, std::filesystem::file_size(path, ec), detail));
    throw InputError(
        fmt::format("cannot open results file '{}'{}", path, detail.empty() ? "" : ": " + detail));
  }
  impl_->file = Handle(f);
  try {
    impl_->load();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    impl_->damaged(e);
  }
}

ResultsReader::~ResultsReader() = default;

const std::string& ResultsReader::path() const {
  return impl_->path;
}
std::string ResultsReader::title() const {
  return impl_->title;
}
std::string ResultsReader::units() const {
  return impl_->units;
}
const std::vector<int>& ResultsReader::node_ids() const {
  return impl_->node_ids;
}
Eigen::MatrixXd ResultsReader::node_coordinates() const {
  return impl_->coords;
}
const std::vector<ResultsReader::ElementInfo>& ResultsReader::elements() const {
  return impl_->elements;
}

std::vector<ResultsReader::AnalysisInfo> ResultsReader::analyses() const {
  std::vector<AnalysisInfo> out;
  for (const auto& a : impl_->analyses) out.push_back(a.info);
  return out;
}

std::vector<double> ResultsReader::times(int analysis) const {
  return impl_->analysis(analysis).times;
}

std::vector<std::pair<double, double>> ResultsReader::nodal_series(int node,
                                                                   const std::string& lab) const {
  return impl_->guarded([&] {
    auto where = parse_nodal_label(lab);
    if (!where)
      throw InputError(fmt::format(
          "unknown nodal result label '{}' (expected UX UY UZ ROTX ROTY ROTZ, VX VY VZ, AX AY AZ "
          "or FX FY FZ MX MY MZ)",
          lab));
    const auto index = static_cast<hsize_t>(impl_->node_index(node));
    Series merged;
    for (const auto& an : impl_->analyses)
      if (is_time_history(an.info.kind))
        merge_into(merged, impl_->collect(
                               an, impl_->nodal_column(an, where->dataset, index, where->column)));
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return merged;
  });
}

std::vector<std::pair<double, double>> ResultsReader::nodal_series_imaginary(
    int node, const std::string& lab) const {
  return impl_->guarded([&] {
    auto where = parse_nodal_label(lab);
    if (!where || std::string(where->dataset) != "U")
      throw InputError(fmt::format(
          "nodal result label '{}' has no imaginary part (UX UY UZ ROTX ROTY ROTZ have)", lab));
    const auto index = static_cast<hsize_t>(impl_->node_index(node));
    Series merged;
    for (const auto& an : impl_->analyses)
      if (an.info.kind == ResultsKind::Harmonic)
        merge_into(merged, impl_->collect(an, impl_->column(an, "UI", index, where->column)));
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return merged;
  });
}

std::vector<std::pair<double, double>> ResultsReader::element_series(
    int element, const std::string& item) const {
  return impl_->guarded([&] {
    const bool known = std::any_of(impl_->elements.begin(), impl_->elements.end(),
                                   [&](const ElementInfo& e) { return e.id == element; });
    if (!known)
      throw InputError(fmt::format("element {} is not in results file '{}'", element, impl_->path));
    const std::string it_name = to_upper(item);
    Series merged;
    bool found = false;
    std::vector<std::string> available;
    for (const auto& an : impl_->analyses) {
      if (!is_time_history(an.info.kind)) continue;
      for (const auto& fam : an.families) {
        auto e = std::find(fam.element_ids.begin(), fam.element_ids.end(), element);
        if (e == fam.element_ids.end()) continue;
        auto i = std::find_if(fam.items.begin(), fam.items.end(),
                              [&](const std::string& s) { return to_upper(s) == it_name; });
        if (i == fam.items.end()) {
          for (const auto& s : fam.items)
            if (std::find(available.begin(), available.end(), s) == available.end())
              available.push_back(s);
          continue;
        }
        found = true;
        merge_into(merged, impl_->collect(
                               an, impl_->column(an, "elements/" + fam.name + "/values",
                                                 static_cast<hsize_t>(e - fam.element_ids.begin()),
                                                 static_cast<long>(i - fam.items.begin()))));
      }
    }
    if (!found) {
      if (available.empty())
        throw InputError(fmt::format("no element results are stored for element {} in '{}'",
                                     element, impl_->path));
      std::string list;
      for (const auto& s : available) list += (list.empty() ? "" : " ") + s;
      throw InputError(fmt::format("element item '{}' is not stored for element {} (available: {})",
                                   item, element, list));
    }
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return merged;
  });
}

std::vector<std::pair<double, double>> ResultsReader::gap_force_series(int gap) const {
  return impl_->guarded([&] {
    Series merged;
    bool found = false;
    int max_gaps = 0;
    for (const auto& an : impl_->analyses) {
      max_gaps = std::max(max_gaps, an.info.n_gaps);
      if (gap < 1 || gap > an.info.n_gaps) continue;
      found = true;
      merge_into(merged, impl_->collect(an, impl_->column(an, "gap_forces",
                                                          static_cast<hsize_t>(gap - 1), -1)));
    }
    if (!found)
      throw InputError(max_gaps == 0
                           ? fmt::format("no gap forces are stored in '{}'", impl_->path)
                           : fmt::format("gap {} does not exist (the results file has gaps 1..{})",
                                         gap, max_gaps));
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return merged;
  });
}

std::vector<std::pair<double, double>> ResultsReader::contact_force_series(
    int entity, const std::string& component) const {
  return impl_->guarded([&] {
    return impl_->triple_series(
        "contact_forces", &AnalysisInfo::n_contacts, entity, component, {"FX", "FY", "FZ"},
        fmt::format("contact force component '{}': FX, FY or FZ", component), "contact",
        "contact forces (explicit runs with EDCGEN store them)");
  });
}

std::vector<std::pair<double, double>> ResultsReader::part_energy_series(
    int part, const std::string& item) const {
  return impl_->guarded([&] {
    return impl_->triple_series(
        "part_energies", &AnalysisInfo::n_parts, part, item, {"KE", "IE", "HE"},
        fmt::format("part energy '{}': KE (kinetic), IE (internal) or HE (hourglass)", item),
        "part", "part energies (explicit runs store them)");
  });
}

std::vector<std::pair<int, int>> ResultsReader::load_steps_of(int analysis) const {
  return impl_->guarded([&] {
    const Analysis& an = impl_->analysis(analysis);
    std::vector<std::pair<int, int>> out;
    if (an.times.empty()) return out;
    const auto ls = h5::read_ints(impl_->file, an.group + "/load_step");
    const auto ss = h5::read_ints(impl_->file, an.group + "/substep");
    for (std::size_t k = 0; k < an.times.size(); ++k) out.emplace_back(ls.at(k), ss.at(k));
    return out;
  });
}

std::vector<double> ResultsReader::frequencies_of(int analysis) const {
  return impl_->guarded([&]() -> std::vector<double> {
    const Analysis& an = impl_->analysis(analysis);
    if (an.info.n_modes == 0) return {};
    return h5::read_doubles(impl_->file, an.group + "/frequencies");
  });
}

Eigen::MatrixXd ResultsReader::mode_shape_of(int analysis, int mode) const {
  return impl_->guarded([&] {
    const Analysis& an = impl_->analysis(analysis);
    if (an.info.n_modes == 0)
      throw InputError(
          fmt::format("analysis {} of '{}' has no mode shapes", analysis, impl_->path));
    if (mode < 1 || mode > an.info.n_modes)
      throw InputError(fmt::format("mode {} does not exist (the results file has modes 1..{})",
                                   mode, an.info.n_modes));
    std::string name = an.group + "/mode_shapes";
    Handle ds(check(H5Dopen2(impl_->file, name.c_str(), H5P_DEFAULT), "open " + name));
    const auto n = impl_->node_ids.size();
    const std::vector<hsize_t> start{static_cast<hsize_t>(mode - 1), 0, 0}, count{1, n, 6};
    h5::verify_chunk_index(ds, start, count, true);  // written whole
    auto v = h5::read_slab(ds, start, count);
    Eigen::MatrixXd m(static_cast<Eigen::Index>(n), 6);
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < 6; ++j) m(static_cast<Eigen::Index>(i), j) = v[i * 6 + j];
    return m;
  });
}

std::vector<double> ResultsReader::frequencies() const {
  for (auto it = impl_->analyses.rbegin(); it != impl_->analyses.rend(); ++it)
    if (it->info.n_modes > 0) return frequencies_of(it->info.index);
  return {};
}

namespace {

/// The per-mode attributes <prefix>_1, <prefix>_2, ... of the last modal analysis, in order.
std::vector<double> last_modal_series(const std::vector<ResultsReader::AnalysisInfo>& analyses,
                                      const std::string& prefix) {
  std::vector<double> values;
  for (auto it = analyses.rbegin(); it != analyses.rend(); ++it) {
    if (it->n_modes == 0) continue;
    for (int n = 1;; ++n) {
      const auto v = it->numeric_attributes.find(prefix + "_" + std::to_string(n));
      if (v == it->numeric_attributes.end()) break;
      values.push_back(v->second);
    }
    break;
  }
  return values;
}

}  // namespace

std::vector<double> ResultsReader::damped_frequencies() const {
  return last_modal_series(analyses(), "damped_frequency");
}

std::vector<double> ResultsReader::stabilities() const {
  return last_modal_series(analyses(), "stability");
}

Eigen::MatrixXd ResultsReader::mode_shape(int mode) const {
  for (auto it = impl_->analyses.rbegin(); it != impl_->analyses.rend(); ++it)
    if (it->info.n_modes > 0) return mode_shape_of(it->info.index, mode);
  throw InputError(fmt::format("no mode shapes are stored in '{}'", impl_->path));
}

TimePoint ResultsReader::time_point(int analysis, int k) const {
  return impl_->guarded([&] {
    const Analysis& an = impl_->analysis(analysis);
    if (k < 0 || k >= static_cast<int>(an.times.size()))
      throw InputError(fmt::format("analysis {} has no time point {} (it has {})", analysis, k,
                                   an.times.size()));
    const hid_t file = impl_->file;
    const auto row = static_cast<hsize_t>(k);
    TimePoint p;
    p.time = an.times[row];
    auto integer_at = [&](const char* name) {
      const hid_t ds = impl_->dataset(an.group + "/" + name);
      h5::verify_chunk_index(ds, {row}, {1}, true);  // written at every point
      return static_cast<int>(h5::read_slab(ds, {row}, {1}).at(0));
    };
    p.load_step = integer_at("load_step");
    p.substep = integer_at("substep");
    const auto r = static_cast<std::size_t>(k);
    p.displacement = impl_->nodal_row(an, "U", k);
    if (an.info.kind == ResultsKind::Harmonic) p.displacement_imag = impl_->nodal_row(an, "UI", k);
    p.velocity = impl_->nodal_row(an, "V", k);
    p.acceleration = impl_->nodal_row(an, "A", k);
    p.reaction = impl_->reaction_row(an, k);
    if (an.info.n_gaps > 0) {
      const auto n_g = static_cast<hsize_t>(an.info.n_gaps);
      const auto v = impl_->rows(an, "gap_forces", {0}, {n_g}, r, 1);
      p.gap_forces = Eigen::Map<const Eigen::VectorXd>(v.data(), an.info.n_gaps);
    }
    if (an.info.n_contacts > 0) {
      const auto n_c = static_cast<hsize_t>(3 * an.info.n_contacts);
      const auto v = impl_->rows(an, "contact_forces", {0}, {n_c}, r, 1);
      p.contact_forces = Eigen::Map<const Eigen::VectorXd>(v.data(), 3 * an.info.n_contacts);
    }
    if (an.info.n_parts > 0) {
      const auto n_e = static_cast<hsize_t>(3 * an.info.n_parts);
      const auto v = impl_->rows(an, "part_energies", {0}, {n_e}, r, 1);
      p.part_energies = Eigen::Map<const Eigen::VectorXd>(v.data(), 3 * an.info.n_parts);
    }
    if (h5::exists(file, an.group + "/frame_acceleration")) {
      const auto v = impl_->rows(an, "frame_acceleration", {0}, {3}, r, 1);
      if (std::isfinite(v[0])) p.frame_acceleration = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    if (h5::exists(file, an.group + "/energy")) {
      const auto v = impl_->rows(an, "energy", {0}, {5}, r, 1);
      for (std::size_t i = 0; i < 5; ++i)
        if (std::isfinite(v[i])) p.energy[kEnergyNames[i]] = v[i];
      // Column 6 (plastic_work) is absent (NaN) in files written before it existed.
      const auto w = impl_->rows(an, "energy", {5}, {1}, r, 1);
      if (std::isfinite(w[0])) p.energy[kEnergyNames[5]] = w[0];
    }
    for (const auto& fam : an.families) {
      ElementResultTable t;
      t.element_ids = fam.element_ids;
      t.item_names = fam.items;
      const auto n_e = fam.element_ids.size(), n_i = fam.items.size();
      const auto v = impl_->rows(an, "elements/" + fam.name + "/values", {0, 0}, {n_e, n_i}, r, 1);
      t.values.resize(static_cast<Eigen::Index>(n_e), static_cast<Eigen::Index>(n_i));
      for (std::size_t e = 0; e < n_e; ++e)
        for (std::size_t i = 0; i < n_i; ++i)
          t.values(static_cast<Eigen::Index>(e), static_cast<Eigen::Index>(i)) = v[e * n_i + i];
      p.element_results[fam.name] = std::move(t);
    }
    return p;
  });
}

}  // namespace impactfe
