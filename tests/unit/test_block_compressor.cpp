// The results writer's block compressor (issue 11): the chunks it filters on a worker thread and
// stores with H5Dwrite_chunk hold what HDF5 stores for the same rows through H5Dwrite (shuffle,
// deflate, Fletcher32 in HDF5's order, NaN fill of a partial block and of a dataset's edge): byte
// for byte without deflate, the same inflated bytes with it (libdeflate writes the stream), and
// read back through HDF5's own filters to the values written.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "../support/stored_chunks.h"
#include "io/h5_util.h"
#include "results/block_compressor.h"
#include "results/result_series.h"

namespace impactfe::result_series::test_block_compressor {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Shape {
  std::vector<hsize_t> row_dims, chunk;  // chunk[0]: the block's rows
  hsize_t n_rows;                        // rows of the block given (<= chunk[0])
  int deflate_level;                     // as asked of checked_creation_list
};

/// Rows of smooth values with NaN holes, as results look (absent DOFs).
std::vector<double> block_values(const Shape& s) {
  hsize_t row_size = 1;
  for (auto d : s.row_dims) row_size *= d;
  std::vector<double> v(s.chunk[0] * row_size, 1e300);  // rows past n_rows: never stored
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  for (hsize_t r = 0; r < s.n_rows; ++r)
    for (hsize_t i = 0; i < row_size; ++i)
      v[r * row_size + i] = i % 11 == 5 ? kNaN : std::sin(0.1 * i + r) + noise(rng);
  return v;
}

/// Raw stored bytes of every chunk of a dataset, in chunk order.
std::vector<std::vector<unsigned char>> stored_chunks(hid_t ds) {
  std::vector<std::vector<unsigned char>> chunks;
  for (auto& c : testing::stored_chunks(ds)) {
    EXPECT_EQ(c.filter_mask, 0u);  // every filter applied
    EXPECT_TRUE(c.read);
    chunks.push_back(std::move(c.bytes));
  }
  return chunks;
}

/// The shuffled bytes of a deflated chunk: its zlib stream (the checksum's 4 bytes dropped)
/// inflated by zlib, which must find a complete stream of exactly `n_bytes`.
std::vector<unsigned char> inflated(const std::vector<unsigned char>& stored, std::size_t n_bytes) {
  std::vector<unsigned char> out(n_bytes);
  uLongf n_out = static_cast<uLongf>(n_bytes);
  EXPECT_EQ(uncompress(out.data(), &n_out, stored.data(), static_cast<uLong>(stored.size() - 4)),
            Z_OK);
  EXPECT_EQ(n_out, n_bytes);
  return out;
}

void check_shape(const Shape& s, bool background) {
  const fs::path path =
      fs::temp_directory_path() / ("impactfe_block_compressor_" + std::to_string(getpid()) + ".h5");
  const std::vector<double> block = block_values(s);
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<hsize_t> dims{s.n_rows}, maxdims{H5S_UNLIMITED};
  for (auto d : s.row_dims) {
    dims.push_back(d);
    maxdims.push_back(d);
  }
  const int rank = static_cast<int>(dims.size());
  const double fill = kNaN;
  h5::Handle dcpl = h5::checked_creation_list(s.chunk, &fill, s.deflate_level);
  h5::Handle space(H5Screate_simple(rank, dims.data(), maxdims.data()));
  // HDF5 filters the rows itself ...
  h5::Handle by_hdf5(
      H5Dcreate2(file, "by_hdf5", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  ASSERT_GE(H5Dwrite(by_hdf5, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, block.data()), 0);
  // ... and the compressor for the direct chunk writes.
  h5::Handle direct(
      H5Dcreate2(file, "direct", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  const auto pipeline = pipeline_of(direct);
  ASSERT_TRUE(pipeline.has_value());
  hsize_t chunk_elements = 1;
  for (auto c : s.chunk) chunk_elements *= c;
  EXPECT_EQ(pipeline->deflate_level,
            chunk_elements >= h5::kMinDeflateChunkElements ? s.deflate_level : 0);
  EXPECT_EQ(pipeline->shuffle, pipeline->deflate_level > 0);
  EXPECT_TRUE(pipeline->fletcher32);
  BlockJob job;
  job.dataset = direct;
  job.pipeline = *pipeline;
  job.row_dims = s.row_dims;
  job.chunk = s.chunk;
  job.first_row = 0;
  job.n_rows = s.n_rows;
  job.block = allocate_block(block.size());
  // On the worker the block's pages go back as they are compressed: a page released too early
  // would reach a later chunk as zeros.
  job.release_compressed_rows = background;
  std::copy(block.begin(), block.end(), job.block.get());
  BlockCompressor compressor(background);
  compressor.submit(std::move(job));
  EXPECT_TRUE(compressor.pending());
  std::vector<BlockJob> done = compressor.wait_all();
  EXPECT_FALSE(compressor.pending());
  ASSERT_EQ(done.size(), 1u);
  ASSERT_FALSE(done[0].error);
  EXPECT_FALSE(done[0].block);  // given back to the system once compressed
  for (const auto& c : done[0].chunks)
    ASSERT_GE(
        H5Dwrite_chunk(direct, H5P_DEFAULT, 0, c.offset.data(), c.bytes.size(), c.bytes.data()), 0);
  H5Fflush(file, H5F_SCOPE_GLOBAL);

  const auto want = stored_chunks(by_hdf5);
  const auto got = stored_chunks(direct);
  ASSERT_EQ(got.size(), want.size());
  EXPECT_EQ(got.size(), done[0].chunks.size());
  for (std::size_t c = 0; c < got.size(); ++c) {
    if (pipeline->deflate_level == 0) {
      EXPECT_EQ(got[c], want[c]) << "chunk " << c;
      continue;
    }
    // libdeflate's stream is not zlib's, but inflates to the same shuffled bytes.
    const std::size_t n_bytes = chunk_elements * sizeof(double);
    EXPECT_EQ(inflated(got[c], n_bytes), inflated(want[c], n_bytes)) << "chunk " << c;
    EXPECT_LT(got[c].size(), n_bytes);  // it compressed
  }

  // Read back through HDF5's filters (Fletcher32 checked on reading).
  std::vector<double> back(block.size() / s.chunk[0] * s.n_rows);
  ASSERT_GE(H5Dread(direct, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()), 0);
  for (std::size_t i = 0; i < back.size(); ++i) {
    if (std::isnan(block[i]))
      EXPECT_TRUE(std::isnan(back[i])) << i;
    else
      EXPECT_EQ(back[i], block[i]) << i;
  }
  H5Fclose(file);
  fs::remove(path);
}

TEST(BlockCompressor, ChunksHoldWhatHdf5StoresForTheSameRows) {
  const std::vector<Shape> shapes = {
      {{400, 6}, {4, 171, 6}, 4, 1},        // U of 400 nodes: three chunks, the last past the edge
      {{400, 6}, {4, 171, 6}, 3, 1},        // the partial last block of an analysis
      {{10000}, {8, 600}, 5, 1},            // a 1-D row (gap forces, R)
      {{100000}, {4, 9000}, 4, 1},          // rows long enough to be given back in two runs
      {{6, 40, 30}, {4, 4, 40, 30}, 2, 6},  // three row dimensions, another deflate level
      {{30, 6}, {4, 16, 6}, 4, 1},          // a chunk too small for deflate: Fletcher32 only
  };
  for (bool background : {false, true})
    for (const Shape& s : shapes) {
      SCOPED_TRACE(::testing::Message()
                   << "rows " << s.n_rows << " of " << s.chunk[0] << ", background " << background);
      check_shape(s, background);
    }
}

TEST(BlockCompressor, BackgroundJobsReturnInSubmissionOrder) {
  BlockCompressor compressor(true);
  for (int k = 0; k < 5; ++k) {
    BlockJob job;
    job.pipeline = {true, 1, true};
    job.row_dims = {1000};
    job.chunk = {4, 250};
    job.first_row = 4 * static_cast<hsize_t>(k);
    job.n_rows = 4;
    job.block = allocate_block(4000);
    for (int i = 0; i < 4000; ++i) job.block[static_cast<std::size_t>(i)] = k + 1e-3 * i;
    compressor.submit(std::move(job));
  }
  const std::vector<BlockJob> done = compressor.wait_all();
  ASSERT_EQ(done.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(done[k].first_row, 4 * k);
    ASSERT_EQ(done[k].chunks.size(), 4u);  // 1000 columns in chunks of 250
    EXPECT_EQ(done[k].chunks[3].offset, (std::vector<hsize_t>{4 * k, 750}));
  }
  EXPECT_TRUE(compressor.wait_all().empty());
}

TEST(BlockCompressor, AFilterItDoesNotApplyIsRefused) {
  const fs::path path =
      fs::temp_directory_path() / ("impactfe_block_pipeline_" + std::to_string(getpid()) + ".h5");
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  hsize_t dims[1] = {64}, chunk[1] = {16};
  h5::Handle space(H5Screate_simple(1, dims, nullptr));
  h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_chunk(dcpl, 1, chunk);
  H5Pset_fletcher32(dcpl);
  H5Pset_shuffle(dcpl);  // after Fletcher32: not the order this code applies
  h5::Handle ds(H5Dcreate2(file, "d", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  EXPECT_FALSE(pipeline_of(ds).has_value());
  H5Fclose(file);
  fs::remove(path);
}

/// The staging rows written chunk by chunk from the block (write_staging_rows) are byte for
/// byte what H5Dwrite stores for the same rows, their checksums read back through HDF5's filter,
/// and the block's values after each row (where its checksum was put for the write) are as they
/// were. A series whose rows no longer are one chunk (R once widened) is written through
/// H5Dwrite.
TEST(BlockCompressor, ChecksummedBlocksAreTheBytesHdf5StoresForTheSameRows) {
  // A main dataset that is not deflated (a small model's): write_checksummed_block stores the
  // chunks H5Dwrite stores, the NaN of a partial block and of the dataset's edge included, for a
  // first block and one after it.
  const fs::path path =
      fs::temp_directory_path() / ("impactfe_checksummed_" + std::to_string(getpid()) + ".h5");
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const std::vector<Shape> shapes = {
      {{68, 6}, {8, 17, 6}, 8, 0},        // the thesis helmet's U: 4 chunks of 17 nodes
      {{68, 6}, {8, 21, 6}, 5, 0},        // the last chunk past the edge, a partial block
      {{30}, {4, 30}, 1, 0},              // a 1-D row of one point
      {{3, 10, 4}, {4, 2, 10, 4}, 3, 0},  // three row dimensions, the edge in the first
  };
  int k = 0;
  for (const Shape& s : shapes) {
    SCOPED_TRACE(::testing::Message() << "shape " << k);
    const std::string name = "q" + std::to_string(k++);
    // A whole block, then s.n_rows of the next (its later rows hold values never stored).
    Shape whole = s;
    whole.n_rows = s.chunk[0];
    const std::vector<double> first = block_values(whole);
    std::vector<double> second = block_values(s);
    for (double& v : second) v = 2.0 * v + 1.0;
    const hsize_t rows = s.chunk[0] + s.n_rows;
    std::vector<hsize_t> dims{rows}, maxdims{H5S_UNLIMITED};
    for (auto d : s.row_dims) {
      dims.push_back(d);
      maxdims.push_back(d);
    }
    const double fill = kNaN;
    h5::Handle dcpl = h5::checked_creation_list(s.chunk, &fill, 0);
    h5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()));
    h5::Handle by_hdf5(H5Dcreate2(file, ("h" + name).c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                  dcpl, H5P_DEFAULT));
    h5::Handle direct(H5Dcreate2(file, ("d" + name).c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                 dcpl, H5P_DEFAULT));
    const auto pipeline = pipeline_of(direct);
    ASSERT_TRUE(pipeline.has_value());
    EXPECT_FALSE(pipeline->shuffle);
    EXPECT_EQ(pipeline->deflate_level, 0);
    EXPECT_TRUE(pipeline->fletcher32);
    write_rows(by_hdf5, 0, s.chunk[0], s.row_dims, first.data());
    write_rows(by_hdf5, s.chunk[0], s.n_rows, s.row_dims, second.data());
    write_checksummed_block(direct, first.data(), s.row_dims, s.chunk, 0, s.chunk[0]);
    write_checksummed_block(direct, second.data(), s.row_dims, s.chunk, s.chunk[0], s.n_rows);
    H5Fflush(file, H5F_SCOPE_GLOBAL);
    const auto want = stored_chunks(by_hdf5);
    const auto got = stored_chunks(direct);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t c = 0; c < got.size(); ++c) EXPECT_EQ(got[c], want[c]) << "chunk " << c;
    // Read back through HDF5's Fletcher32 check.
    std::vector<double> back(product(dims));
    ASSERT_GE(H5Dread(direct, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()), 0);
    const std::size_t block_size = first.size();
    for (std::size_t i = 0; i < back.size(); ++i) {
      const double want_value = i < block_size ? first[i] : second[i - block_size];
      EXPECT_EQ(std::memcmp(&back[i], &want_value, sizeof(double)), 0) << i;
    }
  }
  H5Fclose(file);
  fs::remove(path);
}

TEST(BlockCompressor, StagingRowsAreTheBytesHdf5StoresForTheSameRows) {
  const fs::path path =
      fs::temp_directory_path() / ("impactfe_staging_rows_" + std::to_string(getpid()) + ".h5");
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  h5::Handle recent_by_hdf5(H5Gcreate2(file, "by_hdf5", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  h5::Handle recent_direct(H5Gcreate2(file, "direct", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  constexpr hsize_t kRows = 4;
  const std::vector<std::vector<hsize_t>> shapes = {{400, 6}, {1000}, {30, 7, 3}};
  for (const auto& row_dims : shapes) {
    const std::string name =
        "q" + std::to_string(row_dims.size()) + "_" + std::to_string(row_dims[0]);
    SCOPED_TRACE(name);
    // (their main datasets, not used here, side by side in the file's root)
    BlockSeries by_hdf5 =
        create_series(file, recent_by_hdf5, "h" + name, row_dims, kRows, 0, false, true);
    BlockSeries direct =
        create_series(file, recent_direct, "d" + name, row_dims, kRows, 0, false, true);
    EXPECT_TRUE(direct.recent_checksum_only);
    std::vector<hsize_t> full{kRows};
    full.insert(full.end(), row_dims.begin(), row_dims.end());
    const std::vector<double> values = block_values({row_dims, full, kRows, 0});
    const hsize_t row_size = direct.row_size();
    std::copy(values.begin(), values.end(), direct.block.get());
    // The slack after the last row, as the memory there may hold anything.
    direct.block[kRows * row_size] = 0.125;
    // Rows 0..1, then 2..3, as two syncs would write them.
    write_staging_rows(direct, 0, 2);
    write_staging_rows(direct, 2, 2);
    for (hsize_t i = 0; i < kRows * row_size; ++i)
      ASSERT_EQ(std::memcmp(&direct.block[i], &values[i], sizeof(double)), 0) << i;
    EXPECT_EQ(direct.block[kRows * row_size], 0.125);
    write_rows(by_hdf5.recent, 0, kRows, row_dims, values.data());
    H5Fflush(file, H5F_SCOPE_GLOBAL);
    const auto want = stored_chunks(by_hdf5.recent);
    const auto got = stored_chunks(direct.recent);
    ASSERT_EQ(want.size(), kRows);  // a whole row per chunk
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t c = 0; c < got.size(); ++c) EXPECT_EQ(got[c], want[c]) << "row " << c;
    std::vector<double> back(values.size());
    ASSERT_GE(H5Dread(direct.recent, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()),
              0);
    for (std::size_t i = 0; i < back.size(); ++i)
      EXPECT_EQ(std::memcmp(&back[i], &values[i], sizeof(double)), 0) << i;
  }
  // A growable row widened past its chunk: the row is two chunks, written by HDF5.
  BlockSeries widened = create_series(file, recent_direct, "R", {5}, kRows, 0, true, true);
  widened.row_dims = {8};
  set_extent(widened.recent, kRows, widened.row_dims);
  widened.block = allocate_block(kRows * 8);
  for (hsize_t i = 0; i < kRows * 8; ++i) widened.block[i] = static_cast<double>(i);
  write_staging_rows(widened, 0, kRows);
  std::vector<double> back(kRows * 8);
  ASSERT_GE(H5Dread(widened.recent, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()),
            0);
  for (hsize_t i = 0; i < kRows * 8; ++i) EXPECT_EQ(back[i], static_cast<double>(i)) << i;
  EXPECT_EQ(testing::stored_chunks(widened.recent).size(), 2 * kRows);
  H5Fclose(file);
  fs::remove(path);
}

}  // namespace
}  // namespace impactfe::result_series::test_block_compressor
