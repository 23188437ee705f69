#include "results/result_series.h"

#include <algorithm>
#include <array>
#include <bit>

namespace impactfe::result_series {

using h5::check;
using h5::check_status;
using h5::Handle;

namespace {

/// Memory for the blocks being filled (all quantities of an analysis), at most, unless a block
/// of 4 points needs more. While a block is compressed on a worker, the next one fills beside
/// it: 32 MB (it was 64 MB) keeps the two within what one block took before.
constexpr double kBlockMemoryBytes = 32.0 * (1 << 20);
/// Target size of a main chunk (uncompressed): large enough to compress well, small enough that
/// a history reads little beyond what it needs (with kMaxBlockRows points, a chunk spans the
/// columns of 21 nodes of U).
constexpr hsize_t kChunkBytes = 64 * 1024;
/// Deflate level of the main datasets.
constexpr int kDeflateLevel = 1;

}  // namespace

hsize_t product(const std::vector<hsize_t>& d) {
  hsize_t n = 1;
  for (auto x : d) n *= x;
  return n;
}

hsize_t block_rows_for(std::size_t n_nodes, std::size_t n_elements, long long expected_points) {
  const double row_bytes = 8.0 * (4.0 * 6.0 * static_cast<double>(n_nodes) +
                                  24.0 * static_cast<double>(n_elements) + 16.0);
  hsize_t rows = kMaxBlockRows;
  while (rows > 4 && static_cast<double>(rows) * row_bytes > kBlockMemoryBytes) rows /= 2;
  if (expected_points > 0)
    while (rows > 4 && static_cast<long long>(rows / 2) >= expected_points) rows /= 2;
  return rows;
}

void write_rows(hid_t ds, hsize_t first, hsize_t n_rows, const std::vector<hsize_t>& row_dims,
                const double* data) {
  std::vector<hsize_t> start(row_dims.size() + 1, 0), count{n_rows};
  start[0] = first;
  count.insert(count.end(), row_dims.begin(), row_dims.end());
  h5::write_slab(ds, start, count, data);
}

void set_extent(hid_t ds, hsize_t rows, const std::vector<hsize_t>& row_dims) {
  std::vector<hsize_t> d{rows};
  d.insert(d.end(), row_dims.begin(), row_dims.end());
  check_status(H5Dset_extent(ds, d.data()), "extend dataset");
}

BlockSeries create_series(hid_t group, hid_t recent_group, const std::string& name,
                          std::vector<hsize_t> row_dims, hsize_t block_rows, hsize_t main_rows,
                          bool growable_columns, bool compress) {
  BlockSeries s;
  s.name = name;
  s.row_dims = std::move(row_dims);
  const double fill = kNaN;  // rows never written read as NaN ("absent")
  std::vector<hsize_t> dims{main_rows}, maxdims{H5S_UNLIMITED}, chunk{block_rows};
  // Split the first row dimension so that a chunk holds about kChunkBytes, in equal parts: HDF5
  // fills a new chunk that a write does not cover whole with the fill value first, as it does a
  // chunk reaching past the dataset's edge (the thesis helmet's 68 nodes were chunks of 21, 21,
  // 21 and 5 nodes; now 4 x 17).
  hsize_t rest = 1;
  for (std::size_t i = 1; i < s.row_dims.size(); ++i) rest *= std::max<hsize_t>(1, s.row_dims[i]);
  for (std::size_t i = 0; i < s.row_dims.size(); ++i) {
    dims.push_back(s.row_dims[i]);
    const bool grows = growable_columns && i == 0;
    maxdims.push_back(grows ? H5S_UNLIMITED : s.row_dims[i]);
    hsize_t c = std::max<hsize_t>(1, s.row_dims[i]);
    if (i == 0) {
      const hsize_t fit = std::max<hsize_t>(1, kChunkBytes / (block_rows * rest * 8));
      const hsize_t parts = (c + fit - 1) / fit;
      c = grows ? std::min<hsize_t>(fit, 64) : (c + parts - 1) / parts;
    }
    chunk.push_back(c);
  }
  {
    Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()),
                       "create dataspace for " + name));
    // deflate level 1 (deflate_fast): level 4 costs about 3x the CPU for files a few % smaller
    // (the helmet: docs/benchmarks.md, "Results writer").
    Handle dcpl = h5::checked_creation_list(chunk, &fill, compress ? kDeflateLevel : 0);
    s.main = Handle(check(
        H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
        "create dataset " + name));
    s.chunk = chunk;
    const auto p = pipeline_of(s.main);
    if (p && p->deflate_level > 0) s.pipeline = p;
    s.main_checksum_only = p && p->checksum_only();
  }
  {
    // Staging: one time point per chunk, the whole row when it is not huge (write_staging_rows
    // then stores it without HDF5's chunk buffer).
    std::vector<hsize_t> rdims{block_rows}, rmax{block_rows}, rchunk{1};
    for (std::size_t i = 0; i < s.row_dims.size(); ++i) {
      rdims.push_back(s.row_dims[i]);
      rmax.push_back(growable_columns && i == 0 ? H5S_UNLIMITED : s.row_dims[i]);
      const hsize_t fit = i == 0 ? std::max<hsize_t>(1, kMaxStagingChunkValues / rest) : 0;
      rchunk.push_back(std::max<hsize_t>(1, i == 0 ? std::min(s.row_dims[i], fit) : s.row_dims[i]));
    }
    Handle space(check(H5Screate_simple(static_cast<int>(rdims.size()), rdims.data(), rmax.data()),
                       "create dataspace for recent/" + name));
    // Checksummed but not compressed: written at every point, and deleted when the analysis
    // closes (deflate would allocate and clear its ~256 kB state for every row).
    Handle dcpl = h5::checked_creation_list(rchunk, &fill, 0);
    Handle lcpl(check(H5Pcreate(H5P_LINK_CREATE), "create link property list"));
    check_status(H5Pset_create_intermediate_group(lcpl, 1), "set intermediate groups");
    s.recent = Handle(check(
        H5Dcreate2(recent_group, name.c_str(), H5T_IEEE_F64LE, space, lcpl, dcpl, H5P_DEFAULT),
        "create dataset recent/" + name));
    s.recent_chunk = rchunk;
    const auto p = pipeline_of(s.recent);
    s.recent_checksum_only = p && p->checksum_only();
  }
  s.block = allocate_block(block_rows * s.row_size());
  return s;
}

void write_staging_rows(BlockSeries& s, hsize_t first, hsize_t n) {
  static_assert(std::endian::native == std::endian::little, "the block holds H5T_IEEE_F64LE");
  const hsize_t row_size = s.row_size();
  std::vector<hsize_t> offset{1};
  offset.insert(offset.end(), s.row_dims.begin(), s.row_dims.end());
  if (row_size == 0 || !s.recent_checksum_only || s.recent_chunk != offset) {
    write_rows(s.recent, first, n, s.row_dims, s.block.get() + first * row_size);
    return;
  }
  std::fill(offset.begin(), offset.end(), 0);
  const std::size_t bytes = row_size * sizeof(double);
  for (hsize_t r = first; r < first + n; ++r) {
    // The stored chunk is the row's bytes (little-endian float64, as the block holds them)
    // followed by their checksum: put in the 4 bytes after the row for the write (the next row,
    // not written yet, or the block's slack), then restored.
    auto* row = reinterpret_cast<unsigned char*>(s.block.get() + r * row_size);
    const auto trailer = fletcher32_trailer(row, bytes);
    std::array<unsigned char, 4> next{};
    std::copy_n(row + bytes, 4, next.begin());
    std::copy(trailer.begin(), trailer.end(), row + bytes);
    offset[0] = r;
    const herr_t status = H5Dwrite_chunk(s.recent, H5P_DEFAULT, 0, offset.data(), bytes + 4, row);
    std::copy(next.begin(), next.end(), row + bytes);
    check_status(status, "write a staging row of " + s.name);
  }
}

void flush_block(BlockSeries& s, BlockCompressor& compressor, hsize_t first_row, hsize_t n_rows,
                 hsize_t block_rows) {
  set_extent(s.main, first_row + n_rows, s.row_dims);
  if (s.main_checksum_only) {
    write_checksummed_block(s.main, s.block.get(), s.row_dims, s.chunk, first_row, n_rows);
    return;
  }
  if (!s.pipeline) {
    write_rows(s.main, first_row, n_rows, s.row_dims, s.block.get());
    return;
  }
  BlockJob job;
  job.dataset = s.main;
  job.pipeline = *s.pipeline;
  job.row_dims = s.row_dims;
  job.chunk = s.chunk;
  job.first_row = first_row;
  job.n_rows = n_rows;
  job.block = std::move(s.block);
  if (!compressor.background()) {
    job.compress();
    if (job.error) std::rethrow_exception(job.error);
    job.write();
    s.block = std::move(job.block);
    return;
  }
  job.release_compressed_rows = true;
  s.block = allocate_block(block_rows * s.row_size());
  compressor.submit(std::move(job));
}

DirectSeries create_direct(hid_t group, const std::string& name, bool integer) {
  hsize_t dims = 0, maxdims = H5S_UNLIMITED, chunk = 1024;
  Handle space(check(H5Screate_simple(1, &dims, &maxdims), "create dataspace for " + name));
  const double fill = kNaN;
  Handle dcpl = h5::checked_creation_list({chunk}, integer ? nullptr : &fill, 0);
  DirectSeries s;
  s.ds = Handle(check(H5Dcreate2(group, name.c_str(), integer ? H5T_STD_I32LE : H5T_IEEE_F64LE,
                                 space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                      "create dataset " + name));
  s.mem_type = integer ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
  return s;
}

void write_direct(DirectSeries& s, hsize_t first, hsize_t n, const void* values) {
  if (n == 0) return;
  hsize_t end = first + n;
  check_status(H5Dset_extent(s.ds, &end), "extend dataset");
  Handle file_space(check(H5Dget_space(s.ds), "get dataspace"));
  check_status(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &first, nullptr, &n, nullptr),
               "select rows");
  Handle mem_space(check(H5Screate_simple(1, &n, nullptr), "create memory dataspace"));
  check_status(H5Dwrite(s.ds, s.mem_type, mem_space, file_space, H5P_DEFAULT, values),
               "write rows");
}

}  // namespace impactfe::result_series
