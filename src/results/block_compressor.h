#pragma once
/// Compression of the results writer's finished blocks off the solution's critical path
/// (issue 11: "results writing buffered and off the critical path").
///
/// A full block of a compressed main dataset (docs/results_file.md) used to be written through
/// H5Dwrite, which runs the filters (shuffle, deflate, Fletcher32) chunk by chunk on the
/// calling thread: on the 155 522-DOF dome, 40 MB every fourth stored point, about 100 ms of
/// deflate per point, a third of a run that stores every step. Debian's HDF5 is not built
/// thread-safe, so no second thread may call it. The filters themselves are plain functions of
/// the chunk's bytes, though: a worker thread applies them here (the same pipeline as HDF5's,
/// in the same order, so any HDF5 reader decodes the chunks), and the writer's thread stores
/// the finished chunks with H5Dwrite_chunk, which only does I/O.
#include <array>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "io/h5_util.h"

struct libdeflate_compressor;

namespace impactfe::result_series {

/// The values of a time block in pages of their own (mmap), returned to the system when freed,
/// and, for a block of more than 1 MB, taken from it only as its rows are written. From the
/// heap, a fresh block per finished block (10 MB per quantity on the dome) came from memory
/// glibc keeps once freed (its mmap threshold rises to the sizes it sees freed): the dome's RSS
/// crept up by 40 MB over 200 steps.
struct PageDeleter {
  std::size_t bytes = 0;
  void operator()(double* p) const;
};
using BlockBuffer = std::unique_ptr<double[], PageDeleter>;
/// `n` values, not initialised, and one value of slack after them (the pages of a block up to
/// 1 MB taken at once, a larger one's as they are written): a staging row is stored with
/// its checksum put in the 4 bytes that follow it (write_staging_rows); empty when n = 0.
/// Throws std::bad_alloc.
BlockBuffer allocate_block(std::size_t n);

/// The 4 bytes HDF5's Fletcher32 filter appends to a chunk of `n` stored bytes: its checksum
/// (H5Z__filter_fletcher32), little-endian.
std::array<unsigned char, 4> fletcher32_trailer(const unsigned char* stored, std::size_t n);

/// The filters of a chunked float64 dataset as HDF5 applies them on writing, in this order:
/// byte shuffle, deflate (a zlib stream of level `deflate_level`), Fletcher32 checksum appended.
struct ChunkPipeline {
  bool shuffle = false;
  int deflate_level = 0;  // 0: no deflate
  bool fletcher32 = false;
  /// Fletcher32 alone: a chunk is stored as its bytes and their checksum.
  bool checksum_only() const { return !shuffle && deflate_level == 0 && fletcher32; }
};

/// The pipeline of dataset `ds`; nullopt when it holds a filter this code does not apply
/// itself, or its filters in another order (the caller then writes through H5Dwrite).
std::optional<ChunkPipeline> pipeline_of(hid_t ds);

/// The stored bytes of chunks through a pipeline, what H5Dwrite_chunk takes with filter mask 0:
/// HDF5's shuffle and Fletcher32 byte for byte, and for deflate a zlib stream written by
/// libdeflate at the dataset's level, which HDF5's filter (zlib's inflate) reads like its own.
/// zlib's deflate_fast ran at ~64 MB/s on the shuffled results of the 155 522-DOF dome, 155 ms
/// of the second core per stored point beside the solve's threads; libdeflate at the same
/// level: ~2.2x the speed, the stream within 2 % of zlib's size (issue 11, docs/benchmarks.md).
/// Keeps the compressor and its buffers from chunk to chunk (one filter per thread).
class ChunkFilter {
 public:
  explicit ChunkFilter(const ChunkPipeline& pipeline);
  ~ChunkFilter();
  ChunkFilter(const ChunkFilter&) = delete;
  ChunkFilter& operator=(const ChunkFilter&) = delete;

  /// The stored bytes of one chunk of `n` doubles.
  std::vector<unsigned char> apply(const double* values, std::size_t n);

 private:
  ChunkPipeline pipeline_;
  libdeflate_compressor* compressor_ = nullptr;  // deflate's state, from the first chunk on
  std::vector<unsigned char> shuffled_, deflated_;
};

/// Cuts rows [0, n_rows) of a block (row-major, rows of dimensions `row_dims`) into the chunks
/// `chunk` of a dataset (chunk[0]: rows of a block): for each chunk of the grid, in order (the
/// last dimension fastest), gathers its values into `buffer` (product(chunk) values; NaN, the
/// datasets' fill value, for the rows from n_rows on and past the dataset's edge, as HDF5 fills
/// a new chunk) and calls `visit` with the chunk's origin in the row dimensions.
void cut_block(const double* block, const std::vector<hsize_t>& row_dims,
               const std::vector<hsize_t>& chunk, hsize_t n_rows, double* buffer,
               const std::function<void(const std::vector<hsize_t>& origin)>& visit);

/// Stores rows [0, n_rows) of a block as the chunks from row `first_row` of `dataset`, whose
/// only filter is Fletcher32 (H5Dwrite_chunk: the chunk's bytes and their checksum), on the
/// calling thread. The chunks' bytes are those H5Dwrite stores.
void write_checksummed_block(hid_t dataset, const double* block,
                             const std::vector<hsize_t>& row_dims,
                             const std::vector<hsize_t>& chunk, hsize_t first_row, hsize_t n_rows);

/// One finished block of a main dataset: rows [first_row, first_row + n_rows) of a dataset of
/// rows `row_dims`, chunked `chunk` (chunk[0] = block_rows, the block's length in time).
struct BlockJob {
  hid_t dataset = -1;  // only carried: the worker never calls HDF5
  ChunkPipeline pipeline;
  std::vector<hsize_t> row_dims, chunk;
  hsize_t first_row = 0, n_rows = 0;
  BlockBuffer block;  // chunk[0] x product(row_dims), row-major; rows >= n_rows unused
  /// The block is not needed after compress(): its pages go back to the system as the chunks
  /// that cover them are compressed (while a block is compressed, its compressed chunks then
  /// take the place of its values instead of adding to them).
  bool release_compressed_rows = false;

  struct Chunk {
    std::vector<hsize_t> offset;  // logical start of the chunk in the dataset
    std::vector<unsigned char> bytes;
  };
  std::vector<Chunk> chunks;  // filled by compress()
  std::exception_ptr error;   // what compress() threw, rethrown where the chunks are written

  /// Cuts the block into its chunks (rows past n_rows and columns past the dataset's edge are
  /// NaN, the datasets' fill value) and filters each. The block is left to its owner.
  void compress();
  /// Stored bytes of the chunks (after compress()).
  double stored_bytes() const;
  /// Stores the chunks in `dataset` (H5Dwrite_chunk, filter mask 0), on the thread that owns
  /// the file.
  void write() const;
};

/// Runs BlockJob::compress in submission order, on one worker thread when `background` (it
/// waits on a condition variable when idle), or at once on the caller's thread otherwise
/// (--threads 1: the run then stays on one thread).
class BlockCompressor {
 public:
  explicit BlockCompressor(bool background);
  /// Waits for the job being compressed; jobs still queued are dropped.
  ~BlockCompressor();
  BlockCompressor(const BlockCompressor&) = delete;
  BlockCompressor& operator=(const BlockCompressor&) = delete;

  bool background() const { return background_; }
  /// The job's block is freed once it is compressed.
  void submit(BlockJob job);
  /// Whether a submitted job has not been taken back by wait_all yet.
  bool pending() const { return submitted_ > taken_; }
  /// Waits until every submitted job is compressed; returns them in submission order.
  std::vector<BlockJob> wait_all();

 private:
  void work();

  const bool background_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::deque<BlockJob> queue_, finished_;
  bool busy_ = false, stop_ = false;
  std::size_t submitted_ = 0, taken_ = 0;
  std::thread worker_;  // started with the first job
};

}  // namespace impactfe::result_series
