// ResultsFileWriter (on ResultsWriter's thread, results_writer.cpp): the model section once, then
// one extendible dataset per quantity and analysis, appended a time point at a time (schema and
// reasons: docs/results_file.md). A per-time-point quantity (U, V, A, R, energy, element
// values, ...) has its main dataset chunked in time blocks of `block_rows` points (a node's
// history reads one chunk per block), compressed and checksummed. A compressed chunk cannot
// grow by one row cheaply, so the points of the block being filled are kept in memory and also
// written, one row per chunk, to a staging dataset under `recent/`. Appending a point only
// copies its rows into the block in memory (no HDF5 call, no allocation once the series exist):
// the points since the last sync reach the staging datasets, one chunk per row, and `time`
// after them, at a sync — every kSyncPoints points, kSyncBytes or kSyncSeconds, whichever comes
// first, and when a point completes its block — so a killed run keeps every point up to the
// last sync. A full block then goes to the main dataset, a compressed one deflated on a worker
// thread (BlockCompressor, issue 11) and stored at the next sync (Impl::sync); when the analysis
// closes, the last partial block goes there too and `recent/` is deleted.
#include <fmt/format.h>
#include <malloc.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "core/errors.h"
#include "core/log.h"
#include "core/thread_pool.h"
#include "io/h5_util.h"
#include "results/result_series.h"
#include "results/results_file_writer.h"

namespace impactfe {

using h5::check;
using h5::check_status;
using h5::Handle;
using h5::StringLayout;
using result_series::block_rows_for;
using result_series::BlockJob;
using result_series::BlockSeries;
using result_series::create_direct;
using result_series::create_series;
using result_series::DirectSeries;
using result_series::set_extent;
using result_series::write_direct;
using result_series::write_rows;

namespace {

/// A sync (staging rows, then `time`, each flushed) after this many points or seconds: what a
/// killed run can lose at most. A sync costs about a millisecond whatever it writes (two
/// flushes of the file's metadata and chunk cache): syncing every 32 points, a fast run spent a
/// quarter of its time there (the thesis superelement use pass, 190 points: 29 -> 22 ms with
/// 128; docs/benchmarks.md).
constexpr hsize_t kSyncPoints = 128;
constexpr double kSyncSeconds = 0.1;
/// ... or once the points since the last sync hold this many bytes: a big model syncs more
/// often, so that a full disk finds the earlier points synced (and the space a sync reserves,
/// see Impl::Guard, stays bounded). 4 MB: a model of up to 64 kB per point fills a block of
/// kMaxBlockRows first and, within kSyncSeconds, writes each point once (benchmarks.md, stop 40).
constexpr double kSyncBytes = 4.0 * 1024 * 1024;
/// Disk space reserved before every write beyond the data it stores (object headers, chunk
/// index nodes, free-space rounding), and the factor on the data (checksums, chunk padding,
/// deflate that does not shrink); see Impl::Guard.
constexpr double kReserveSlack = 64.0 * 1024;
constexpr double kReserveFactor = 2.0;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct FamilySeries {
  std::vector<int> element_ids;
  std::vector<std::string> items;
};

}  // namespace

struct ResultsFileWriter::Impl {
  std::string path;
  std::string title, jobname, units;
  Handle file;
  std::vector<int> node_ids;
  std::size_t n_elements = 0;
  int n_analyses = 0;
  // Current analysis (group invalid when none is open).
  Handle group;
  Handle recent_group;
  hsize_t n_t = 0;
  hsize_t block_rows = result_series::kMaxBlockRows;
  hsize_t block_start = 0;  // time index of the first point of the block being filled
  std::map<std::string, BlockSeries> series;
  std::map<std::string, DirectSeries> direct;
  // Finished blocks of compressed series: on a worker thread when --threads allows two.
  result_series::BlockCompressor compressor{threads::max_threads() > 1};
  bool first_row_pending = false;  // recent/first_row becomes first_row_after (complete_blocks)
  hsize_t first_row_after = 0;
  // Points appended since the last sync: [synced, n_t); their time, load step and substep.
  hsize_t synced = 0;
  std::vector<double> pending_time;
  std::vector<int> pending_load_step, pending_substep;
  std::chrono::steady_clock::time_point last_sync;
  std::map<std::string, FamilySeries> families;
  Handle elements_group;
  // Sparse reactions: the constrained DOFs (row in node_ids, DOF column 0..5) of R's columns.
  std::vector<std::pair<int, int>> reaction_dofs;
  std::map<std::pair<int, int>, std::size_t> reaction_column;
  Handle reaction_dofs_ds;

  /// A write failed: the file is left in its last flushed state and never written again.
  bool failed = false;
  bool sparse_output = true;  // set_sparse_output
  double reserved_end = 0.0;  // disk space allocated ahead (h5::reserve_space)

  hsize_t n_nodes() const { return node_ids.size(); }
  hsize_t slot() const { return n_t - block_start; }

  /// Every public write holds a guard: the disk space it may need (`bytes` of data) is
  /// reserved first, so that a full disk stops the run before HDF5 writes anything; when
  /// anything fails after all, the file is abandoned in its last flushed state (docs/
  /// results_file.md, "Crash safety").
  struct Guard {
    Impl& m;
    const int exceptions = std::uncaught_exceptions();
    Guard(Impl& impl, double bytes) : m(impl) {
      // A full disk is a failure of the run, not of the input (exit 2, "results up to the
      // failure are kept"), also when it comes at the close after the last step.
      if (m.failed)
        throw SolutionError(
            fmt::format("cannot write {} any more: an earlier write failed", m.path));
      try {
        h5::reserve_space(m.file, m.path, kReserveFactor * bytes + kReserveSlack, m.reserved_end);
      } catch (const std::runtime_error& e) {
        m.abandon();
        throw SolutionError(e.what());
      }
    }
    ~Guard() {
      if (std::uncaught_exceptions() > exceptions) m.abandon();
    }
  };
  void abandon();
  /// Whether a sync stages its points: not when it completes a block that no dataset deflates
  /// (the block goes to the main datasets at once; a deflated one after its staging rows).
  bool sync_stages(bool block_full) const {
    return !block_full || std::any_of(series.begin(), series.end(),
                                      [](const auto& s) { return s.second.pipeline.has_value(); });
  }
  /// Bytes of the rows of the current block (all quantities), the data of a block flush.
  double block_bytes(hsize_t n_rows) const {
    double n = 0;
    for (const auto& [name, s] : series) n += static_cast<double>(n_rows * s.row_size());
    return 8.0 * n;
  }

  void require_open(const char* what) const {
    IMPACTFE_CHECK(group.valid(), fmt::format("ResultsWriter::{}: no analysis is open", what));
  }

  void write_model(const ResultsModelSection& model);
  void write_element_nodes(const std::vector<std::vector<int>>& lists);
  void close_analysis(const std::string& status);
  BlockSeries& series_for(const std::string& name, const std::vector<hsize_t>& row_dims,
                          bool growable = false);
  void put_row(BlockSeries& s, const double* row);
  /// The block row of the current point (row_size values), marked written.
  double* row_slot(BlockSeries& s);
  void finish_append();
  void sync(bool block_full);
  void write_pending_counters();
  void complete_blocks();
  void write_nodal(const std::string& name, const Eigen::MatrixXd& m);
  void write_reactions(const Eigen::MatrixXd& m);
  void write_family(const std::string& family, const ElementResultTable& table);
  void flush() { check_status(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path); }
  void compact();
};

/// The staging datasets freed when an analysis closed leave holes that HDF5 cannot give back
/// (up to one block of rows, uncompressed). When they are more than a tenth of the file, the
/// objects are copied (chunks as stored, no recompression) into a fresh file that replaces the
/// old one; on any failure the old file stays as it is.
void ResultsFileWriter::Impl::compact() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec || size < (1u << 20)) return;
  const double used = static_cast<double>(h5::stored_bytes(file));
  if (used > 0.9 * static_cast<double>(size)) return;
  const std::string tmp = path + ".compacting";
  try {
    {
      Handle fapl = h5::file_access_checksummed();
      Handle fcpl = h5::checksummed_group_creation_list(true);
      Handle out(check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl, fapl), "create " + tmp));
      constexpr auto kFixed = StringLayout::Fixed;
      h5::write_attribute(out, "format", std::string("impactfe-results"), kFixed);
      h5::write_integer_attribute(out, "format_version", kResultsFormatVersion);
      h5::write_attribute(out, "title", title, kFixed);
      h5::write_attribute(out, "jobname", jobname, kFixed);
      if (!units.empty()) h5::write_attribute(out, "units", units, kFixed);
      std::vector<std::string> names{"model"};
      for (int k = 1; k <= n_analyses; ++k) names.push_back(fmt::format("analysis_{}", k));
      for (const auto& name : names)
        check_status(H5Ocopy(file, name.c_str(), out, name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                     "copy " + name);
      check_status(H5Fflush(out, H5F_SCOPE_GLOBAL), "flush " + tmp);
    }
    file.reset();
    fs::rename(tmp, path);
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    Log::debug("results file {} not compacted: {}", path, e.what());
  }
}

void ResultsFileWriter::Impl::abandon() {
  failed = true;
  for (auto& [name, s] : series) {
    s.main.abandon();
    s.recent.abandon();
  }
  for (auto& [name, d] : direct) d.ds.abandon();
  for (Handle* h : {&reaction_dofs_ds, &elements_group, &recent_group, &group, &file}) h->abandon();
}

void ResultsFileWriter::Impl::write_model(const ResultsModelSection& model) {
  constexpr auto kFixed = StringLayout::Fixed;
  h5::write_attribute(file, "format", std::string("impactfe-results"), kFixed);
  h5::write_integer_attribute(file, "format_version", kResultsFormatVersion);
  title = model.title;
  jobname = model.jobname;
  units = model.units;
  h5::write_attribute(file, "title", model.title, kFixed);
  h5::write_attribute(file, "jobname", model.jobname, kFixed);
  if (!units.empty()) h5::write_attribute(file, "units", units, kFixed);
  Handle gcpl = h5::checksummed_group_creation_list();
  Handle g(check(H5Gcreate2(file, "model", H5P_DEFAULT, gcpl, H5P_DEFAULT), "create group /model"));
  constexpr auto kChecked = h5::Storage::Checked;
  node_ids = model.node_ids;
  h5::write_dataset(g, "node_ids", {n_nodes()}, node_ids.data(), kChecked);
  h5::write_dataset(g, "node_coordinates", {n_nodes(), 3}, model.node_xyz.data(), kChecked);
  n_elements = model.element_ids.size();
  const hsize_t n_e = n_elements;
  h5::write_dataset(g, "element_ids", {n_e}, model.element_ids.data(), kChecked);
  h5::write_dataset(g, "element_type_names", model.element_type_names, kFixed);
  h5::write_dataset(g, "element_types", {n_e}, model.element_types.data(), kChecked);
  h5::write_dataset(g, "element_materials", {n_e}, model.element_materials.data(), kChecked);
  h5::write_dataset(g, "element_reals", {n_e}, model.element_reals.data(), kChecked);
  write_element_nodes(model.element_nodes);
}

void ResultsFileWriter::Impl::write_element_nodes(const std::vector<std::vector<int>>& lists) {
  std::size_t width = 8;  // ANSYS elements have at most 8 nodes; superelements may have more
  for (const auto& l : lists) width = std::max(width, l.size());
  std::vector<int> nodes;
  for (const auto& l : lists)
    for (std::size_t i = 0; i < width; ++i) nodes.push_back(i < l.size() ? l[i] : 0);
  Handle g(check(H5Gopen2(file, "model", H5P_DEFAULT), "open group /model"));
  if (h5::exists(g, "element_nodes")) H5Ldelete(g, "element_nodes", H5P_DEFAULT);
  h5::write_dataset(g, "element_nodes", {lists.size(), width}, nodes.data(), h5::Storage::Checked);
}

BlockSeries& ResultsFileWriter::Impl::series_for(const std::string& name,
                                                 const std::vector<hsize_t>& row_dims,
                                                 bool growable) {
  auto it = series.find(name);
  if (it != series.end()) return it->second;
  if (!recent_group.valid()) {
    Handle gcpl = h5::checksummed_group_creation_list();
    recent_group = Handle(
        check(H5Gcreate2(group, "recent", H5P_DEFAULT, gcpl, H5P_DEFAULT), "create group recent"));
    h5::write_integer_attribute(recent_group, "first_row", static_cast<long long>(block_start));
  }
  // A quantity that starts later: its main dataset spans the finished blocks already (NaN).
  const bool compress =
      sparse_output || result_series::product(row_dims) >= result_series::kMinCompressedPointValues;
  BlockSeries s = create_series(group, recent_group, name, row_dims, block_rows, block_start,
                                growable, compress);
  // The rows of the current block before this point are NaN (written to the new staging
  // dataset at the next sync like every row of the block). After finished blocks the whole
  // block starts NaN: those blocks are written from it, so that every chunk exists
  // (all_chunks_written). Otherwise the later rows are left untouched until their points fill
  // them: the block of a large model becomes resident row by row, not whole at the first point
  // (issue 11: three rows, 23 MB, of the 155 522-DOF dome's peak during its factorization).
  std::fill_n(s.block.get(), (block_start > 0 ? block_rows : slot()) * s.row_size(), kNaN);
  for (hsize_t b = 0; b < block_start; b += block_rows)
    write_rows(s.main, b, std::min(block_rows, block_start - b), s.row_dims, s.block.get());
  return series.emplace(name, std::move(s)).first->second;
}

double* ResultsFileWriter::Impl::row_slot(BlockSeries& s) {
  s.written = true;
  return s.block.get() + slot() * s.row_size();
}

void ResultsFileWriter::Impl::put_row(BlockSeries& s, const double* row) {
  std::copy(row, row + s.row_size(), row_slot(s));
}

/// Stores the chunks of the blocks submitted to the compressor (waiting for it if it is still at
/// work), then moves recent/first_row past the block: its staging rows are then free.
void ResultsFileWriter::Impl::complete_blocks() {
  if (compressor.pending()) {
    std::vector<BlockJob> jobs = compressor.wait_all();
    double bytes = 0.0;
    for (const BlockJob& job : jobs) {
      if (job.error) std::rethrow_exception(job.error);
      bytes += job.stored_bytes();
    }
    try {
      h5::reserve_space(file, path, kReserveFactor * bytes + kReserveSlack, reserved_end);
    } catch (const std::runtime_error& e) {
      throw SolutionError(e.what());  // the Guard of the public call abandons the file
    }
    for (const BlockJob& job : jobs) job.write();
    // The chunks were allocated on the compressor's thread, in an arena glibc keeps when they
    // are freed here: given back now, or they stay resident (+4.7 MB at the dome's peak, over
    // 1.5 x factor + model, once the compressor stopped trimming its arena with every chunk).
    jobs.clear();
    malloc_trim(0);
  }
  if (first_row_pending && recent_group.valid()) {
    // HDF5 writes what is dirty in an order of its own at a flush: the main chunks reach the
    // file before first_row moves past their rows, and first_row before the next block's rows
    // overwrite the staging rows (a run killed in between reads each point from where it is).
    flush();
    h5::write_integer_attribute(recent_group, "first_row", static_cast<long long>(first_row_after));
    flush();
  }
  first_row_pending = false;
}

void ResultsFileWriter::Impl::finish_append() {
  // A quantity not given at this point is absent (NaN) there; the staging rows are written from
  // the block.
  for (auto& [name, s] : series) {
    if (!s.written) std::fill_n(row_slot(s), s.row_size(), kNaN);
    s.written = false;
  }
}

void ResultsFileWriter::Impl::write_pending_counters() {
  const hsize_t n = pending_time.size();
  const std::pair<const char*, const void*> columns[] = {
      {"load_step", pending_load_step.data()},
      {"substep", pending_substep.data()},
      {"time", pending_time.data()}};  // last: its length counts the complete points
  for (const auto& [name, data] : columns) {
    auto it = direct.find(name);
    if (it == direct.end())
      it = direct.emplace(name, create_direct(group, name, std::string(name) != "time")).first;
    write_direct(it->second, synced, n, data);
  }
  synced += n;
  pending_time.clear();
  pending_load_step.clear();
  pending_substep.clear();
}

/// Makes the points appended since the last sync complete in the file: their rows first (to the
/// staging datasets), flushed, then `time` and the counters, flushed. HDF5 writes dirty chunks
/// and metadata in an order of its own at a flush (or a cache eviction), so with one flush a run
/// killed during it could leave `time` longer than the rows on disk
/// (CrashSafety.KilledExpansionPassKeepsCompletedSteps). A full block then goes to the main
/// datasets; its rows are read from the staging ones until complete_blocks has stored its
/// compressed chunks and moved recent/first_row, at the next sync (so that the compression
/// overlaps the steps in between), before the next block's rows overwrite them. When nothing is
/// compressed, the block's last rows go to the main datasets with the rest instead, and
/// first_row moves before `time` grows.
void ResultsFileWriter::Impl::sync(bool block_full) {
  if (pending_time.empty()) return;
  complete_blocks();
  const bool stages = sync_stages(block_full);
  const auto finish_block = [&] {
    for (auto& [name, s] : series)
      result_series::flush_block(s, compressor, block_start, block_rows, block_rows);
    first_row_pending = true;
    first_row_after = block_start + block_rows;
  };
  if (!stages) {
    finish_block();
    complete_blocks();
  } else {
    const hsize_t first = synced - block_start, n = n_t - synced;
    for (auto& [name, s] : series) result_series::write_staging_rows(s, first, n);
    flush();
  }
  write_pending_counters();
  flush();
  if (block_full && stages) {  // deflated
    finish_block();
    if (!compressor.background()) complete_blocks();
  }
  last_sync = std::chrono::steady_clock::now();
}

void ResultsFileWriter::Impl::close_analysis(const std::string& status) {
  if (!group.valid()) return;
  complete_blocks();  // the blocks submitted earlier, while recent/ still holds their rows
  // The staging datasets go first (the last partial block is in memory), so that HDF5 frees
  // their space now and the main chunks written next reuse it. Both reach the disk together at
  // the flush below.
  for (auto& [name, s] : series) s.recent.reset();
  if (recent_group.valid()) {
    recent_group.reset();
    H5Ldelete(group, "recent", H5P_DEFAULT);
  }
  if (n_t > block_start) {
    for (auto& [name, s] : series)
      result_series::flush_block(s, compressor, block_start, n_t - block_start, block_rows);
    complete_blocks();
  }
  if (!pending_time.empty()) {
    flush();  // the rows before `time` grows (see sync)
    write_pending_counters();
  }
  h5::write_attribute(group, "status", status, StringLayout::Fixed);
  series.clear();
  direct.clear();
  families.clear();
  reaction_dofs.clear();
  reaction_column.clear();
  reaction_dofs_ds.reset();
  elements_group.reset();
  group.reset();
  flush();
}

void ResultsFileWriter::Impl::write_nodal(const std::string& name, const Eigen::MatrixXd& m) {
  if (m.size() == 0) return;  // not computed: the row stays NaN (finish_append)
  IMPACTFE_CHECK(m.rows() == static_cast<Eigen::Index>(n_nodes()) && m.cols() == 6,
                 fmt::format("ResultsWriter::append: {} is {}x{}, expected {}x6", name, m.rows(),
                             m.cols(), n_nodes()));
  BlockSeries& s = series_for(name, {n_nodes(), 6});
  // Row by row, the block's order: a column at a time missed the cold row at every value.
  Eigen::Map<RowMajor>(row_slot(s), m.rows(), 6) = m;
}

void ResultsFileWriter::Impl::write_reactions(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return;
  IMPACTFE_CHECK(m.rows() == static_cast<Eigen::Index>(n_nodes()) && m.cols() == 6,
                 fmt::format("ResultsWriter::append: R is {}x{}, expected {}x6", m.rows(), m.cols(),
                             n_nodes()));
  // Only constrained DOFs carry a reaction: R keeps one column per DOF that ever had one.
  std::vector<std::pair<int, int>> added;
  for (int i = 0; i < m.rows(); ++i)
    for (int j = 0; j < 6; ++j)
      if (std::isfinite(m(i, j)) && !reaction_column.count({i, j})) {
        reaction_column[{i, j}] = reaction_dofs.size();
        reaction_dofs.emplace_back(i, j);
        added.emplace_back(i, j);
      }
  if (reaction_dofs.empty()) return;
  const hsize_t n_r = reaction_dofs.size();
  if (!added.empty()) {
    // reaction_dofs: (n_r, 2) int32 = node id, DOF column (0..5 = UX..ROTZ / FX..MZ).
    std::vector<int> flat;
    for (const auto& [row, col] : reaction_dofs) flat.insert(flat.end(), {node_ids[row], col});
    if (!reaction_dofs_ds.valid()) {
      hsize_t dims[2] = {0, 2}, maxdims[2] = {H5S_UNLIMITED, 2};
      Handle space(check(H5Screate_simple(2, dims, maxdims), "create dataspace reaction_dofs"));
      Handle dcpl = h5::checked_creation_list({256, 2});
      reaction_dofs_ds = Handle(check(
          H5Dcreate2(group, "reaction_dofs", H5T_STD_I32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
          "create dataset reaction_dofs"));
    }
    hsize_t dims[2] = {n_r, 2};
    check_status(H5Dset_extent(reaction_dofs_ds, dims), "extend reaction_dofs");
    check_status(
        H5Dwrite(reaction_dofs_ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, flat.data()),
        "write reaction_dofs");
    auto it = series.find("R");
    if (it == series.end()) {
      series_for("R", {n_r}, true);
    } else {
      // More columns: widen both datasets and the block (old rows keep their columns). The
      // blocks being compressed are written first, at the width they were cut with.
      complete_blocks();
      BlockSeries& s = it->second;
      const hsize_t old_n = s.row_dims[0];
      result_series::BlockBuffer block = result_series::allocate_block(block_rows * n_r);
      for (hsize_t r = 0; r < slot(); ++r) {  // the rows of this block so far
        std::copy(s.block.get() + r * old_n, s.block.get() + (r + 1) * old_n,
                  block.get() + r * n_r);
        std::fill(block.get() + r * n_r + old_n, block.get() + (r + 1) * n_r, kNaN);
      }
      s.block = std::move(block);
      s.row_dims = {n_r};
      set_extent(s.main, h5::dims_of(s.main)[0], s.row_dims);
      // The new columns of the finished blocks: NaN, written (all_chunks_written).
      const std::vector<double> nan_rows(block_rows * (n_r - old_n), kNaN);
      for (hsize_t b = 0; b < block_start; b += block_rows)
        h5::write_slab(s.main, {b, old_n}, {std::min(block_rows, block_start - b), n_r - old_n},
                       nan_rows.data());
      set_extent(s.recent, block_rows, s.row_dims);
    }
  }
  double* row = row_slot(series.at("R"));
  for (hsize_t c = 0; c < n_r; ++c) row[c] = m(reaction_dofs[c].first, reaction_dofs[c].second);
}

void ResultsFileWriter::Impl::write_family(const std::string& family,
                                           const ElementResultTable& table) {
  IMPACTFE_CHECK(
      !(family.empty() || family.find('/') != std::string::npos || family == "." || family == ".."),
      fmt::format("ResultsWriter: bad element family name '{}'", family));
  const auto n_e = table.element_ids.size();
  const auto n_i = table.item_names.size();
  IMPACTFE_CHECK(static_cast<std::size_t>(table.values.rows()) == n_e &&
                     static_cast<std::size_t>(table.values.cols()) == n_i,
                 fmt::format("ResultsWriter::append: element table '{}' is {}x{}, expected {}x{}",
                             family, table.values.rows(), table.values.cols(), n_e, n_i));
  auto it = families.find(family);
  if (it == families.end()) {
    if (!elements_group.valid()) {
      // Track creation order so that the reader lists families in the order they appeared.
      Handle gcpl = h5::checksummed_group_creation_list();
      H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
      elements_group = Handle(check(H5Gcreate2(group, "elements", H5P_DEFAULT, gcpl, H5P_DEFAULT),
                                    "create group elements"));
    }
    Handle fgcpl = h5::checksummed_group_creation_list();
    Handle g(check(H5Gcreate2(elements_group, family.c_str(), H5P_DEFAULT, fgcpl, H5P_DEFAULT),
                   "create group elements/" + family));
    h5::write_dataset(g, "element_ids", {n_e}, table.element_ids.data(), h5::Storage::Checked);
    h5::write_attribute(g, "items", table.item_names, StringLayout::Fixed);
    it = families.emplace(family, FamilySeries{table.element_ids, table.item_names}).first;
  } else {
    IMPACTFE_CHECK(
        it->second.element_ids == table.element_ids && it->second.items == table.item_names,
        fmt::format("ResultsWriter::append: element ids or items of family '{}' "
                    "changed within an analysis",
                    family));
  }
  if (n_e == 0 || n_i == 0) return;
  BlockSeries& s = series_for("elements/" + family + "/values", {n_e, n_i});
  Eigen::Map<RowMajor>(row_slot(s), n_e, n_i) = table.values;  // row by row, as write_nodal
}

ResultsFileWriter::ResultsFileWriter(const std::string& path, const ResultsModelSection& model)
    : impl_(std::make_unique<Impl>()) {
  h5::silence_errors();
  impl_->path = path;
  Handle fapl = h5::file_access_checksummed();
  Handle fcpl = h5::checksummed_group_creation_list(true);
  // The new file is made under a temporary name and renamed into place once its model section
  // is written: a file already at `path` (an earlier run's) is replaced whole or not at all,
  // never truncated by a creation that fails.
  const std::string creating = path + ".creating";
  hid_t f = H5Fcreate(creating.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
  // Exit status 2 (the run cannot keep its results), with the system's reason.
  if (f < 0) {
    const std::string detail = h5::error_detail();
    std::error_code ec;
    std::filesystem::remove(creating, ec);
    throw SolutionError(fmt::format("cannot create results file '{}'{}", path,
                                    detail.empty() ? "" : ": " + detail));
  }
  impl_->file = Handle(f);
  try {
    impl_->write_model(model);
    impl_->flush();
    std::error_code ec;
    std::filesystem::rename(creating, path, ec);  // HDF5 keeps writing the same file
    if (ec) throw std::runtime_error(fmt::format("cannot rename {}: {}", creating, ec.message()));
  } catch (const std::runtime_error& e) {
    impl_->file.reset();
    std::error_code ec;
    std::filesystem::remove(creating, ec);
    throw SolutionError(fmt::format("results file '{}': {}", path, e.what()));
  }
}

ResultsFileWriter::ResultsFileWriter(const std::string& path, ResultsWriter::Append)
    : impl_(std::make_unique<Impl>()) {
  h5::silence_errors();
  Impl& m = *impl_;
  m.path = path;
  Handle fapl = h5::file_access_checksummed();
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl);
  if (f < 0) {
    const std::string detail = h5::error_detail();
    throw SolutionError(fmt::format("cannot open results file '{}' to continue it{}", path,
                                    detail.empty() ? "" : ": " + detail));
  }
  m.file = Handle(f);
  try {
    m.title = h5::read_string_attribute(m.file, "title");
    m.jobname = h5::read_string_attribute(m.file, "jobname");
    if (H5Aexists(m.file, "units") > 0) m.units = h5::read_string_attribute(m.file, "units");
    Handle g = h5::open_group(m.file, "model");
    m.node_ids = h5::read_ints(g, "node_ids");
    m.n_elements = h5::read_ints(g, "element_ids").size();
    while (h5::exists(m.file, fmt::format("analysis_{}", m.n_analyses + 1))) ++m.n_analyses;
  } catch (const std::runtime_error& e) {
    throw SolutionError(fmt::format("results file '{}': {}", path, e.what()));
  }
}

ResultsFileWriter::~ResultsFileWriter() {
  if (impl_->failed) return;  // the file keeps its last flushed state
  try {
    impl_->close_analysis("incomplete");
    impl_->compact();
  } catch (...) {
    // A destructor must not throw; the status simply stays "running".
  }
}

int ResultsFileWriter::begin_analysis(ResultsKind kind, const std::string& description,
                                      long long expected_points) {
  Impl& m = *impl_;
  const Impl::Guard guard(m, m.block_bytes(m.n_t - m.block_start));
  m.close_analysis("complete");
  const int k = ++m.n_analyses;
  const std::string name = fmt::format("analysis_{}", k);
  Handle gcpl = h5::checksummed_group_creation_list();
  m.group = Handle(check(H5Gcreate2(m.file, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT),
                         "create group " + name));
  m.n_t = 0;
  m.block_start = 0;
  m.synced = 0;
  m.last_sync = std::chrono::steady_clock::now();
  m.block_rows = block_rows_for(m.n_nodes(), m.n_elements, expected_points);
  h5::write_attribute(m.group, "kind", std::string(results_kind_name(kind)), StringLayout::Fixed);
  h5::write_attribute(m.group, "description", description, StringLayout::Fixed);
  h5::write_attribute(m.group, "status", std::string("running"), StringLayout::Fixed);
  h5::write_integer_attribute(m.group, "block_rows", static_cast<long long>(m.block_rows));
  h5::write_integer_attribute(m.group, "all_chunks_written", 1);  // see series_for
  m.flush();
  return k;
}

void ResultsFileWriter::set_sparse_output(bool sparse) {
  impl_->sparse_output = sparse;
}

void ResultsFileWriter::append(const TimePoint& point) {
  impl_->require_open("append");
  Impl& m = *impl_;
  double values = static_cast<double>(point.displacement.size() + point.displacement_imag.size() +
                                      point.velocity.size() + point.acceleration.size() +
                                      point.reaction.size() + point.gap_forces.size() +
                                      point.contact_forces.size() + point.part_energies.size()) +
                  16.0;
  for (const auto& [family, table] : point.element_results)
    values += static_cast<double>(table.values.size() + table.element_ids.size());
  // Whether a sync follows this point (decided now, so that the space reserved covers it): a
  // row of every quantity, the rows a sync writes, and the whole block when this point
  // completes it.
  const bool completes_block = m.slot() + 1 == m.block_rows;
  const double pending_bytes = m.block_bytes(m.n_t + 1 - m.synced);
  const bool sync_after =
      completes_block || m.n_t + 1 - m.synced >= kSyncPoints || pending_bytes >= kSyncBytes ||
      std::chrono::duration<double>(std::chrono::steady_clock::now() - m.last_sync).count() >=
          kSyncSeconds;
  const bool stages = sync_after && m.sync_stages(completes_block);
  const Impl::Guard guard(m, 8.0 * values + (stages ? pending_bytes : 0.0) +
                                 (completes_block ? m.block_bytes(m.block_rows) : 0.0));
  m.write_nodal("U", point.displacement);
  m.write_nodal("UI", point.displacement_imag);
  m.write_nodal("V", point.velocity);
  m.write_nodal("A", point.acceleration);
  m.write_reactions(point.reaction);

  // Per-point vectors whose length the analysis's first point fixes.
  for (const auto& [name, v] : {std::pair{"gap_forces", &point.gap_forces},
                                std::pair{"contact_forces", &point.contact_forces},
                                std::pair{"part_energies", &point.part_energies}}) {
    if (v->size() == 0) continue;
    BlockSeries& s = m.series_for(name, {static_cast<hsize_t>(v->size())});
    IMPACTFE_CHECK(static_cast<hsize_t>(v->size()) == s.row_dims[0],
                   fmt::format("ResultsWriter::append: {} {}, the analysis has {}", v->size(), name,
                               s.row_dims[0]));
    m.put_row(s, v->data());
  }
  if (point.frame_acceleration)
    m.put_row(m.series_for("frame_acceleration", {3}), point.frame_acceleration->data());

  if (!point.energy.empty()) {
    constexpr std::size_t n_energy = std::size(kEnergyNames);
    double row[n_energy];
    std::fill(row, row + n_energy, kNaN);
    for (const auto& [name, value] : point.energy) {
      auto pos = std::find(std::begin(kEnergyNames), std::end(kEnergyNames), name);
      IMPACTFE_CHECK(pos != std::end(kEnergyNames),
                     fmt::format("ResultsWriter::append: unknown energy term '{}'", name));
      row[pos - std::begin(kEnergyNames)] = value;
    }
    const bool is_new = !m.series.count("energy");
    BlockSeries& s = m.series_for("energy", {n_energy});
    if (is_new)
      h5::write_attribute(
          s.main, "columns",
          std::vector<std::string>(std::begin(kEnergyNames), std::end(kEnergyNames)),
          StringLayout::Fixed);
    m.put_row(s, row);
  }

  for (const auto& [family, table] : point.element_results) m.write_family(family, table);
  m.finish_append();
  m.pending_time.push_back(point.time);
  m.pending_load_step.push_back(point.load_step);
  m.pending_substep.push_back(point.substep);
  ++m.n_t;
  const bool block_full = m.n_t - m.block_start == m.block_rows;
  if (sync_after || block_full) m.sync(block_full);
  if (block_full) m.block_start = m.n_t;
}

void ResultsFileWriter::write_modes(const std::vector<double>& frequencies_hz,
                                    const std::vector<Eigen::MatrixXd>& shapes) {
  impl_->require_open("write_modes");
  Impl& m = *impl_;
  const Impl::Guard guard(m, 8.0 * static_cast<double>((shapes.size() + 1) * m.n_nodes() * 6));
  IMPACTFE_CHECK(shapes.size() == frequencies_hz.size(),
                 fmt::format("ResultsWriter::write_modes: {} frequencies, {} shapes",
                             frequencies_hz.size(), shapes.size()));
  const hsize_t n_modes = shapes.size();
  std::vector<double> buf;
  buf.reserve(n_modes * m.n_nodes() * 6);
  for (const auto& s : shapes) {
    IMPACTFE_CHECK(s.rows() == static_cast<Eigen::Index>(m.n_nodes()) && s.cols() == 6,
                   fmt::format("ResultsWriter::write_modes: shape is {}x{}, expected {}x6",
                               s.rows(), s.cols(), m.n_nodes()));
    const RowMajor r = s;
    buf.insert(buf.end(), r.data(), r.data() + r.size());
  }
  for (const char* name : {"frequencies", "mode_shapes"})
    if (h5::exists(m.group, name)) H5Ldelete(m.group, name, H5P_DEFAULT);
  h5::write_dataset(m.group, "frequencies", {n_modes}, frequencies_hz.data(), h5::Storage::Checked);
  h5::write_dataset(m.group, "mode_shapes", {n_modes, m.n_nodes(), 6}, buf.data(),
                    h5::Storage::Checked);
  m.flush();
}

void ResultsFileWriter::set_attribute(const std::string& name, double value) {
  impl_->require_open("set_attribute");
  const Impl::Guard guard(*impl_, 0.0);
  h5::write_attribute(impl_->group, name, value);
}

void ResultsFileWriter::set_attribute(const std::string& name, const std::string& value) {
  impl_->require_open("set_attribute");
  const Impl::Guard guard(*impl_, static_cast<double>(value.size()));
  h5::write_attribute(impl_->group, name, value, StringLayout::Fixed);
}

void ResultsFileWriter::set_count(const std::string& name, long long value) {
  impl_->require_open("set_count");
  const Impl::Guard guard(*impl_, 0.0);
  h5::write_integer_attribute(impl_->group, name, value);
}

void ResultsFileWriter::set_element_nodes(const std::map<int, std::vector<int>>& nodes) {
  Impl& m = *impl_;
  Handle g(check(H5Gopen2(m.file, "model", H5P_DEFAULT), "open group /model"));
  const std::vector<int> ids = h5::read_ints(g, "element_ids");
  const std::vector<int> flat = h5::read_ints(g, "element_nodes");
  const std::size_t width = ids.empty() ? 0 : flat.size() / ids.size();
  std::vector<std::vector<int>> lists(ids.size());
  bool changed = false;
  for (std::size_t e = 0; e < ids.size(); ++e) {
    for (std::size_t i = 0; i < width; ++i)
      if (flat[e * width + i] != 0) lists[e].push_back(flat[e * width + i]);
    auto it = nodes.find(ids[e]);
    if (it != nodes.end() && it->second != lists[e]) {
      lists[e] = it->second;
      changed = true;
    }
  }
  if (!changed) return;
  const Impl::Guard guard(m, 8.0 * static_cast<double>(flat.size() + nodes.size() * 8));
  m.write_element_nodes(lists);
  m.flush();
}

void ResultsFileWriter::end_analysis(const std::string& status) {
  impl_->require_open("end_analysis");
  Impl& m = *impl_;
  const Impl::Guard guard(m, m.block_bytes(m.n_t - m.block_start));
  m.close_analysis(status);
}

void ResultsFileWriter::sync_for_reader() {
  Impl& m = *impl_;
  if (m.failed || !m.group.valid()) return;
  const Impl::Guard guard(m, m.block_bytes(m.n_t - m.synced));
  m.sync(false);
}

const std::vector<int>& ResultsFileWriter::node_ids() const {
  return impl_->node_ids;
}
int ResultsFileWriter::n_analyses() const {
  return impl_->n_analyses;
}

}  // namespace impactfe
