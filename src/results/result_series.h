#pragma once
/// The datasets of a results file's time series (used by ResultsWriter; layout and reasons in
/// the header comment of results_writer.cpp and in docs/results_file.md): a block series (main
/// dataset chunked in time blocks plus its staging dataset under `recent/`) and a direct 1-D
/// series (time, load step, substep).
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/numbers.h"
#include "io/h5_util.h"
#include "results/block_compressor.h"

namespace impactfe::result_series {

/// Time points per block (main chunk length along time), at most. An uncompressed main chunk
/// stores the unwritten rows of its last block too (as NaN): 64 bounds that waste, and a
/// history of n points still reads n / 64 chunks.
constexpr hsize_t kMaxBlockRows = 64;
/// A main dataset is compressed (shuffle + deflate) when its time point holds at least this many
/// values, or when the output is sparse (ResultsWriter::set_sparse_output). Below it a file of a
/// few MB is not worth the CPU: deflate was ~20 % of the thesis helmet run (issue 11).
constexpr hsize_t kMinCompressedPointValues = 4096;
/// Values of a staging chunk, at most (512 MB): a row of up to this many values is one chunk.
constexpr hsize_t kMaxStagingChunkValues = hsize_t{1} << 26;

hsize_t product(const std::vector<hsize_t>& d);

/// Time points per block for a model: kMaxBlockRows, fewer (down to 4) when a block of every
/// nodal quantity and element value would need more than 32 MB, or when the analysis is known
/// to store fewer points (`expected_points` > 0; the power of two that holds them, at least 4):
/// a main chunk holds a whole block, so the last, partial block of a dataset that is not
/// deflated is stored whole, its unwritten rows filled with NaN (the thesis helmet with results
/// at the ends of its load steps only, 4 points, took 1.75 MB with blocks of 64 points, 0.2 MB
/// with blocks of 4).
hsize_t block_rows_for(std::size_t n_nodes, std::size_t n_elements, long long expected_points = 0);

/// Writes rows [first, first + n_rows) of a dataset of rows `row_dims`.
void write_rows(hid_t ds, hsize_t first, hsize_t n_rows, const std::vector<hsize_t>& row_dims,
                const double* data);
void set_extent(hid_t ds, hsize_t rows, const std::vector<hsize_t>& row_dims);

/// A float64 quantity of one row per time point (NaN = absent).
struct BlockSeries {
  std::string name;                   // path below the analysis group, e.g. "elements/Spar/values"
  std::vector<hsize_t> row_dims;      // dimensions after the time axis
  h5::Handle main;                    // (n_t, row_dims...), chunks (block_rows, ...)
  h5::Handle recent;                  // (block_rows, row_dims...), one row per chunk
  std::vector<hsize_t> recent_chunk;  // of the staging dataset: 1, then the row dimensions'
  /// The staging dataset's only filter is Fletcher32: write_staging_rows stores a row that is
  /// one chunk with H5Dwrite_chunk.
  bool recent_checksum_only = false;
  std::vector<hsize_t> chunk;  // of the main dataset: block_rows, then the row dimensions'
  /// The main dataset's filters, when it deflates (its finished blocks are then compressed by a
  /// BlockCompressor and stored with H5Dwrite_chunk).
  std::optional<ChunkPipeline> pipeline;
  /// The main dataset's only filter is Fletcher32: flush_block stores its finished blocks with
  /// write_checksummed_block. Through H5Dwrite, HDF5 cleared every new chunk, filled the rows
  /// past a partial block with NaN and copied the chunk again into its cache (issue 11: most of
  /// the thesis helmet's ~1100 page faults in storing its results).
  bool main_checksum_only = false;
  // The block being filled, block_rows x row_size, not initialised: a row becomes valid when the
  // point's values (or NaN, finish_append) are put into it.
  BlockBuffer block;
  bool written = false;  // a row was given in the current append

  hsize_t row_size() const { return product(row_dims); }
};

/// Creates both datasets of a series. `growable_columns`: the second dimension may grow (R).
/// `compress`: the main dataset is deflated (the staging one never is).
BlockSeries create_series(hid_t group, hid_t recent_group, const std::string& name,
                          std::vector<hsize_t> row_dims, hsize_t block_rows, hsize_t main_rows,
                          bool growable_columns, bool compress);

/// Rows [first, first + n) of the series' block to its staging dataset. A row that is one whole
/// chunk (every staging row but those of a model of more than kMaxStagingChunkValues values per
/// row, or of R once it has widened) is stored as it is in the block, with its checksum in the
/// block's next 4 bytes for the write (allocate_block's slack after the last row): H5Dwrite
/// allocated, filled and copied a chunk buffer for every row, then copied it again to append the
/// checksum, mostly page faults (issue 11: 5 % of the 155 522-DOF dome's samples).
void write_staging_rows(BlockSeries& s, hsize_t first, hsize_t n);

/// Rows [first_row, first_row + n_rows) of the series' block go to its main dataset (extended to
/// them): written now when it does not deflate or the compressor works on this thread (the
/// series keeps its block), otherwise handed to the compressor's worker with the block (freed
/// once compressed), and the series takes a new one for the points that follow.
void flush_block(BlockSeries& s, BlockCompressor& compressor, hsize_t first_row, hsize_t n_rows,
                 hsize_t block_rows);

/// A 1-D series written straight into its dataset at every sync (time, load step, substep):
/// tiny, and `time` must be complete in the main dataset (its length counts the points).
struct DirectSeries {
  h5::Handle ds;
  hid_t mem_type = H5T_NATIVE_DOUBLE;
};

DirectSeries create_direct(hid_t group, const std::string& name, bool integer);

/// Writes rows [first, first + n) of a 1-D series (n values at `values`).
void write_direct(DirectSeries& s, hsize_t first, hsize_t n, const void* values);

}  // namespace impactfe::result_series
