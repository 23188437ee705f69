// ResultsWriter: the model section once, then one extendible dataset per quantity and analysis,
// appended and flushed one time point at a time (schema: docs/results_file.md).
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/errors.h"
#include "core/log.h"
#include "io/h5_util.h"
#include "results/results_file.h"

namespace impactfe {

using h5::check;
using h5::check_status;
using h5::Handle;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kFormatVersion = 1;
/// Node-direction chunk size: bounds the chunk to ~200 kB so that reading one node's history
/// touches one small chunk per time point even on large meshes.
constexpr hsize_t kNodeChunk = 4096;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// An extendible float64 dataset of shape (n_t, row_dims...), NaN-filled, growing along axis 0.
struct Series {
  Handle ds;
  std::vector<hsize_t> row_dims;  // dims after the time axis
  hsize_t row_size() const {
    hsize_t n = 1;
    for (auto d : row_dims) n *= d;
    return n;
  }
};

Series create_series(hid_t loc, const std::string& name, std::vector<hsize_t> row_dims,
                     hsize_t n_rows_now, hid_t file_type = H5T_IEEE_F64LE) {
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{1};
  for (std::size_t i = 0; i < row_dims.size(); ++i) {
    dims.push_back(row_dims[i]);
    maxdims.push_back(row_dims[i]);
    hsize_t c = std::max<hsize_t>(1, row_dims[i]);
    if (i == 0 && row_dims.size() > 1) c = std::min(c, kNodeChunk);
    chunk.push_back(c);
  }
  // 1-D series (time, load step): chunks of many points, since one element is tiny.
  if (row_dims.empty()) chunk[0] = 256;
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()),
                     "create dataspace for " + name));
  Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "create property list"));
  check_status(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), "set chunk");
  if (H5Tequal(file_type, H5T_IEEE_F64LE) > 0) {
    double fill = kNaN;  // absent values read back as NaN, also rows created after the fact
    check_status(H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &fill), "set fill value");
  }
  Series s;
  s.ds =
      Handle(check(H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                   "create dataset " + name));
  s.row_dims = std::move(row_dims);
  if (n_rows_now > 0) {
    std::vector<hsize_t> d{n_rows_now};
    d.insert(d.end(), s.row_dims.begin(), s.row_dims.end());
    check_status(H5Dset_extent(s.ds, d.data()), "extend " + name);
  }
  return s;
}

/// Extends the series to row+1 rows (if needed) and writes row `row` from `data`.
void write_row(Series& s, hsize_t row, hid_t mem_type, const void* data) {
  std::vector<hsize_t> dims = h5::dims_of(s.ds);
  if (dims[0] < row + 1) {
    dims[0] = row + 1;
    check_status(H5Dset_extent(s.ds, dims.data()), "extend dataset");
  }
  std::vector<hsize_t> start(dims.size(), 0), count{1};
  start[0] = row;
  count.insert(count.end(), s.row_dims.begin(), s.row_dims.end());
  Handle file_space(check(H5Dget_space(s.ds), "get dataspace"));
  check_status(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "select row");
  hsize_t n = s.row_size();
  Handle mem_space(check(H5Screate_simple(1, &n, nullptr), "create memory dataspace"));
  check_status(H5Dwrite(s.ds, mem_type, mem_space, file_space, H5P_DEFAULT, data), "write row");
}

struct FamilySeries {
  std::vector<int> element_ids;
  std::vector<std::string> items;
  Series values;
};

}  // namespace

const char* results_kind_name(ResultsKind kind) {
  switch (kind) {
    case ResultsKind::Static:
      return "static";
    case ResultsKind::Modal:
      return "modal";
    case ResultsKind::Transient:
      return "transient";
    case ResultsKind::ReducedTransient:
      return "reduced_transient";
    case ResultsKind::Expansion:
      return "expansion";
    case ResultsKind::Substructure:
      return "substructure";
  }
  return "unknown";
}

bool same_time(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
}

struct ResultsWriter::Impl {
  std::string path;
  Handle file;
  std::vector<int> node_ids;
  int n_analyses = 0;
  // Current analysis (group invalid when none is open).
  Handle group;
  hsize_t n_t = 0;
  std::map<std::string, Series> series;  // time, load_step, substep, U, V, A, R, gaps, energy
  std::map<std::string, FamilySeries> families;
  Handle elements_group;

  hsize_t n_nodes() const { return node_ids.size(); }

  void require_open(const char* what) const {
    IMPACTFE_CHECK(!(!group.valid()), fmt::format("ResultsWriter::{}: no analysis is open", what));
  }

  void write_model(const Model& model);
  void close_analysis(const std::string& status);
  void write_nodal(const std::string& name, const Eigen::MatrixXd& m);
  void write_family(const std::string& family, const ElementResultTable& table);
};

void ResultsWriter::Impl::write_model(const Model& model) {
  h5::write_attribute(file, "format", std::string("impactfe-results"));
  h5::write_attribute(file, "format_version", static_cast<double>(kFormatVersion));
  h5::write_attribute(file, "title", model.title);
  h5::write_attribute(file, "jobname", model.jobname);
  Handle g(check(H5Gcreate2(file, "model", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 "create group /model"));

  std::vector<double> xyz;
  for (const auto& [id, node] : model.nodes) {
    node_ids.push_back(id);
    xyz.insert(xyz.end(), {node.x.x(), node.x.y(), node.x.z()});
  }
  h5::write_dataset(g, "node_ids", {n_nodes()}, node_ids.data());
  h5::write_dataset(g, "node_coordinates", {n_nodes(), 3}, xyz.data());

  std::size_t width = 8;  // ANSYS elements have at most 8 nodes; superelements may have more
  for (const auto& [id, e] : model.elements) width = std::max(width, e.nodes.size());
  std::vector<int> ids, type_ids, mats, reals, nodes;
  std::vector<std::string> names;
  for (const auto& [id, e] : model.elements) {
    ids.push_back(id);
    type_ids.push_back(e.type);
    mats.push_back(e.mat);
    reals.push_back(e.real);
    auto t = model.element_types.find(e.type);
    names.push_back(t == model.element_types.end() ? std::string() : t->second.ansys_name);
    for (std::size_t i = 0; i < width; ++i) nodes.push_back(i < e.nodes.size() ? e.nodes[i] : 0);
  }
  hsize_t n_e = ids.size();
  h5::write_dataset(g, "element_ids", {n_e}, ids.data());
  h5::write_dataset(g, "element_type_names", names);
  h5::write_dataset(g, "element_types", {n_e}, type_ids.data());
  h5::write_dataset(g, "element_materials", {n_e}, mats.data());
  h5::write_dataset(g, "element_reals", {n_e}, reals.data());
  h5::write_dataset(g, "element_nodes", {n_e, width}, nodes.data());
}

void ResultsWriter::Impl::close_analysis(const std::string& status) {
  if (!group.valid()) return;
  h5::write_attribute(group, "status", status);
  series.clear();
  families.clear();
  elements_group.reset();
  group.reset();
  H5Fflush(file, H5F_SCOPE_GLOBAL);
}

void ResultsWriter::Impl::write_nodal(const std::string& name, const Eigen::MatrixXd& m) {
  auto it = series.find(name);
  if (m.size() == 0) {
    // Nothing computed: the row stays NaN (written when the dataset exists or is created).
    if (it == series.end()) return;
    std::vector<double> nan_row(n_nodes() * 6, kNaN);
    write_row(it->second, n_t, H5T_NATIVE_DOUBLE, nan_row.data());
    return;
  }
  IMPACTFE_CHECK(!(m.rows() != static_cast<Eigen::Index>(n_nodes()) || m.cols() != 6),
                 fmt::format("ResultsWriter::append: {} is {}x{}, expected {}x6", name, m.rows(),
                             m.cols(), n_nodes()));
  if (it == series.end())
    it = series.emplace(name, create_series(group, name, {n_nodes(), 6}, n_t)).first;
  RowMajor r = m;
  write_row(it->second, n_t, H5T_NATIVE_DOUBLE, r.data());
}

void ResultsWriter::Impl::write_family(const std::string& family, const ElementResultTable& table) {
  IMPACTFE_CHECK(!(family.empty() || family.find('/') != std::string::npos || family == "."),
                 fmt::format("ResultsWriter: bad element family name '{}'", family));
  const auto n_e = table.element_ids.size();
  const auto n_i = table.item_names.size();
  IMPACTFE_CHECK(!(static_cast<std::size_t>(table.values.rows()) != n_e ||
                   static_cast<std::size_t>(table.values.cols()) != n_i),
                 fmt::format("ResultsWriter::append: element table '{}' is {}x{}, expected {}x{}",
                             family, table.values.rows(), table.values.cols(), n_e, n_i));
  auto it = families.find(family);
  if (it == families.end()) {
    if (!elements_group.valid()) {
      // Track creation order so that the reader lists families in the order they appeared.
      Handle gcpl(check(H5Pcreate(H5P_GROUP_CREATE), "create group property list"));
      H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
      elements_group = Handle(check(H5Gcreate2(group, "elements", H5P_DEFAULT, gcpl, H5P_DEFAULT),
                                    "create group elements"));
    }
    Handle g(
        check(H5Gcreate2(elements_group, family.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              "create group elements/" + family));
    h5::write_dataset(g, "element_ids", {n_e}, table.element_ids.data());
    FamilySeries fs;
    fs.element_ids = table.element_ids;
    fs.items = table.item_names;
    fs.values = create_series(g, "values", {n_e, n_i}, n_t);
    h5::write_attribute(g, "items", table.item_names);
    it = families.emplace(family, std::move(fs)).first;
  } else
    IMPACTFE_CHECK(
        !(it->second.element_ids != table.element_ids || it->second.items != table.item_names),
        fmt::format(
            "ResultsWriter::append: element ids or items of family '{}' changed within an analysis",
            family));
  if (n_e == 0 || n_i == 0) return;
  RowMajor r = table.values;
  write_row(it->second.values, n_t, H5T_NATIVE_DOUBLE, r.data());
}

ResultsWriter::ResultsWriter(const std::string& path, const Model& model)
    : impl_(std::make_unique<Impl>()) {
  h5::silence_errors();
  impl_->path = path;
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  // Exit status 2 (the run cannot keep its results), with the system's reason.
  if (f < 0)
    throw SolutionError(
        fmt::format("cannot create results file '{}': {}", path, h5::last_error_reason()));
  impl_->file = Handle(f);
  impl_->write_model(model);
  H5Fflush(impl_->file, H5F_SCOPE_GLOBAL);
}

ResultsWriter::~ResultsWriter() {
  try {
    impl_->close_analysis("incomplete");
  } catch (...) {
    // A destructor must not throw; the status simply stays "running".
  }
}

int ResultsWriter::begin_analysis(ResultsKind kind, const std::string& description) {
  impl_->close_analysis("complete");
  const int k = ++impl_->n_analyses;
  const std::string name = fmt::format("analysis_{}", k);
  impl_->group =
      Handle(check(H5Gcreate2(impl_->file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "create group " + name));
  impl_->n_t = 0;
  h5::write_attribute(impl_->group, "kind", std::string(results_kind_name(kind)));
  h5::write_attribute(impl_->group, "description", description);
  h5::write_attribute(impl_->group, "status", std::string("running"));
  H5Fflush(impl_->file, H5F_SCOPE_GLOBAL);
  return k;
}

void ResultsWriter::append(const TimePoint& point) {
  impl_->require_open("append");
  Impl& m = *impl_;
  m.write_nodal("U", point.displacement);
  m.write_nodal("V", point.velocity);
  m.write_nodal("A", point.acceleration);
  m.write_nodal("R", point.reaction);

  if (point.gap_forces.size() > 0 || m.series.count("gap_forces")) {
    auto it = m.series.find("gap_forces");
    const auto n_g = static_cast<hsize_t>(point.gap_forces.size());
    if (it == m.series.end())
      it = m.series.emplace("gap_forces", create_series(m.group, "gap_forces", {n_g}, m.n_t)).first;
    if (n_g > 0) {
      IMPACTFE_CHECK(!(n_g != it->second.row_dims[0]),
                     fmt::format("ResultsWriter::append: {} gap forces, the analysis has {}", n_g,
                                 it->second.row_dims[0]));
      write_row(it->second, m.n_t, H5T_NATIVE_DOUBLE, point.gap_forces.data());
    }
  }

  if (point.frame_acceleration) {
    auto it = m.series.find("frame_acceleration");
    if (it == m.series.end())
      it = m.series
               .emplace("frame_acceleration",
                        create_series(m.group, "frame_acceleration", {3}, m.n_t))
               .first;
    write_row(it->second, m.n_t, H5T_NATIVE_DOUBLE, point.frame_acceleration->data());
  }

  if (!point.energy.empty()) {
    double row[5];
    std::fill(row, row + 5, kNaN);
    for (const auto& [name, value] : point.energy) {
      auto pos = std::find_if(std::begin(kEnergyNames), std::end(kEnergyNames),
                              [&](const char* n) { return name == n; });
      IMPACTFE_CHECK(!(pos == std::end(kEnergyNames)),
                     fmt::format("ResultsWriter::append: unknown energy term '{}'", name));
      row[pos - std::begin(kEnergyNames)] = value;
    }
    auto it = m.series.find("energy");
    if (it == m.series.end()) {
      it = m.series.emplace("energy", create_series(m.group, "energy", {5}, m.n_t)).first;
      h5::write_attribute(
          it->second.ds, "columns",
          std::vector<std::string>(std::begin(kEnergyNames), std::end(kEnergyNames)));
    }
    write_row(it->second, m.n_t, H5T_NATIVE_DOUBLE, row);
  }

  for (const auto& [family, table] : point.element_results) m.write_family(family, table);

  // Counters and time last: a reader takes the length of `time` as the number of complete
  // points, so a run killed in the middle of an append shows only whole points.
  for (const char* name : {"load_step", "substep", "time"}) {
    auto it = m.series.find(name);
    if (it == m.series.end()) {
      const bool integer = std::string(name) != "time";
      it = m.series
               .emplace(name, create_series(m.group, name, {}, m.n_t,
                                            integer ? H5T_STD_I32LE : H5T_IEEE_F64LE))
               .first;
    }
    if (std::string(name) == "time")
      write_row(it->second, m.n_t, H5T_NATIVE_DOUBLE, &point.time);
    else
      write_row(it->second, m.n_t, H5T_NATIVE_INT,
                std::string(name) == "substep" ? &point.substep : &point.load_step);
  }
  ++m.n_t;
  check_status(H5Fflush(m.file, H5F_SCOPE_GLOBAL), "flush " + m.path);
}

void ResultsWriter::write_modes(const std::vector<double>& frequencies_hz,
                                const std::vector<Eigen::MatrixXd>& shapes) {
  impl_->require_open("write_modes");
  Impl& m = *impl_;
  IMPACTFE_CHECK(!(shapes.size() != frequencies_hz.size()),
                 fmt::format("ResultsWriter::write_modes: {} frequencies, {} shapes",
                             frequencies_hz.size(), shapes.size()));
  const hsize_t n_modes = shapes.size();
  std::vector<double> buf;
  buf.reserve(n_modes * m.n_nodes() * 6);
  for (const auto& s : shapes) {
    IMPACTFE_CHECK(!(s.rows() != static_cast<Eigen::Index>(m.n_nodes()) || s.cols() != 6),
                   fmt::format("ResultsWriter::write_modes: shape is {}x{}, "
                               "expected {}x6",
                               s.rows(), s.cols(), m.n_nodes()));
    RowMajor r = s;
    buf.insert(buf.end(), r.data(), r.data() + r.size());
  }
  for (const char* name : {"frequencies", "mode_shapes"})
    if (h5::exists(m.group, name)) H5Ldelete(m.group, name, H5P_DEFAULT);
  h5::write_dataset(m.group, "frequencies", {n_modes}, frequencies_hz.data());
  h5::write_dataset(m.group, "mode_shapes", {n_modes, m.n_nodes(), 6}, buf.data());
  check_status(H5Fflush(m.file, H5F_SCOPE_GLOBAL), "flush " + m.path);
}

void ResultsWriter::set_attribute(const std::string& name, double value) {
  impl_->require_open("set_attribute");
  h5::write_attribute(impl_->group, name, value);
}

void ResultsWriter::set_attribute(const std::string& name, const std::string& value) {
  impl_->require_open("set_attribute");
  h5::write_attribute(impl_->group, name, value);
}

void ResultsWriter::end_analysis(const std::string& status) {
  impl_->require_open("end_analysis");
  impl_->close_analysis(status);
}

const std::vector<int>& ResultsWriter::node_ids() const {
  return impl_->node_ids;
}
const std::string& ResultsWriter::path() const {
  return impl_->path;
}

}  // namespace impactfe
