#include "results/block_compressor.h"

#include <fmt/format.h>
#include <libdeflate.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <functional>
#include <limits>
#include <stdexcept>

// HDF5's own Fletcher32 (H5checksum.c, exported by the library since 1.8 but declared only in
// its private header): the checksum the Fletcher32 filter appends, byte for byte.
extern "C" uint32_t H5_checksum_fletcher32(const void* data, size_t len);

namespace impactfe::result_series {

namespace {

constexpr double kFill = std::numeric_limits<double>::quiet_NaN();
/// Blocks up to this size are mapped with their pages (allocate_block).
constexpr std::size_t kPopulatedBlockBytes = 1 << 20;
/// Values of a block row given back to the system at a time (256 KiB), at least.
constexpr std::size_t kReleaseValues = 32768;

/// HDF5's shuffle filter for 8-byte elements: byte j of element i goes to j * n + i.
void shuffle8(const unsigned char* in, std::size_t n, unsigned char* out) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 8; ++j) out[j * n + i] = in[i * 8 + j];
}

/// Gives the whole pages within values [begin, end) of `data` back to the system.
void release_pages(double* data, std::size_t begin, std::size_t end) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t lo =
      (reinterpret_cast<std::uintptr_t>(data + begin) + page - 1) / page * page;
  const std::uintptr_t hi = reinterpret_cast<std::uintptr_t>(data + end) / page * page;
  if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);
}

}  // namespace

void PageDeleter::operator()(double* p) const {
  if (p != nullptr) munmap(p, bytes);
}

BlockBuffer allocate_block(std::size_t n) {
  if (n == 0) return {};
  const std::size_t bytes = (n + 1) * sizeof(double);
  // A small block is mapped with its pages at once (MAP_POPULATE): its rows fill it within one
  // block of points anyway, and on this VM one populating call costs about half as much per
  // page as the page faults of the rows (6 against 12 us; issue 11: the thesis helmet's 1670
  // page faults -> 1280, task-clock -3 %). A large one still takes its pages row by row.
  const int populate = bytes <= kPopulatedBlockBytes ? MAP_POPULATE : 0;
  void* p =
      mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | populate, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  return BlockBuffer(static_cast<double*>(p), PageDeleter{bytes});
}

std::optional<ChunkPipeline> pipeline_of(hid_t ds) {
  h5::Handle dcpl(h5::check(H5Dget_create_plist(ds), "get dataset creation list"));
  const int n = H5Pget_nfilters(dcpl);
  if (n < 0) return std::nullopt;
  ChunkPipeline p;
  int stage = 0;  // shuffle 1, deflate 2, Fletcher32 3: each at most once, in that order
  for (int k = 0; k < n; ++k) {
    unsigned flags = 0, config = 0;
    unsigned cd[8] = {};
    std::size_t n_cd = 8;
    const H5Z_filter_t id =
        H5Pget_filter2(dcpl, static_cast<unsigned>(k), &flags, &n_cd, cd, 0, nullptr, &config);
    int this_stage = 0;
    if (id == H5Z_FILTER_SHUFFLE) {
      this_stage = 1;
      p.shuffle = true;
    } else if (id == H5Z_FILTER_DEFLATE && n_cd >= 1 && cd[0] >= 1 && cd[0] <= 9) {
      this_stage = 2;
      p.deflate_level = static_cast<int>(cd[0]);
    } else if (id == H5Z_FILTER_FLETCHER32) {
      this_stage = 3;
      p.fletcher32 = true;
    }
    if (this_stage <= stage) return std::nullopt;  // unknown filter, or out of order
    stage = this_stage;
  }
  return p;
}

std::array<unsigned char, 4> fletcher32_trailer(const unsigned char* stored, std::size_t n) {
  const uint32_t sum = H5_checksum_fletcher32(stored, n);
  std::array<unsigned char, 4> trailer{};
  for (std::size_t b = 0; b < 4; ++b)
    trailer[b] = static_cast<unsigned char>((sum >> (8 * b)) & 0xff);
  return trailer;
}

ChunkFilter::ChunkFilter(const ChunkPipeline& pipeline) : pipeline_(pipeline) {}

ChunkFilter::~ChunkFilter() {
  if (compressor_ != nullptr) libdeflate_free_compressor(compressor_);
}

std::vector<unsigned char> ChunkFilter::apply(const double* values, std::size_t n) {
  const std::size_t n_bytes = n * sizeof(double);
  const auto* raw = reinterpret_cast<const unsigned char*>(values);
  std::vector<unsigned char> stored;
  // H5Z__filter_shuffle leaves a buffer of a single element as it is.
  const unsigned char* plain = raw;
  if (pipeline_.shuffle && n > 1) {
    shuffled_.resize(n_bytes);
    shuffle8(raw, n, shuffled_.data());
    plain = shuffled_.data();
  }
  if (pipeline_.deflate_level > 0) {
    // In place of H5Z__filter_deflate's compress2 (zlib format: header, deflate, Adler-32).
    // The compressor is allocated once: zlib's state (~270 KB) and an output buffer allocated
    // and freed for every chunk trimmed the worker's heap, ~17 000 madvise calls on the dome,
    // each interrupting the solver's threads to flush their TLBs (issue 11).
    if (compressor_ == nullptr) {
      compressor_ = libdeflate_alloc_compressor(pipeline_.deflate_level);
      if (compressor_ == nullptr) throw std::bad_alloc();
    }
    deflated_.resize(libdeflate_zlib_compress_bound(compressor_, n_bytes));
    const std::size_t n_deflated =
        libdeflate_zlib_compress(compressor_, plain, n_bytes, deflated_.data(), deflated_.size());
    if (n_deflated == 0)  // only when the bound is too small, which it is not
      throw std::runtime_error("deflate of a results chunk: no room for the stream");
    // Exactly the stored bytes (and room for the checksum): a block's chunks wait in memory
    // until they are written.
    stored.reserve(n_deflated + 4);
    stored.assign(deflated_.begin(), deflated_.begin() + static_cast<std::ptrdiff_t>(n_deflated));
  } else {
    stored.reserve(n_bytes + 4);
    stored.assign(plain, plain + n_bytes);
  }
  if (pipeline_.fletcher32) {
    const auto trailer = fletcher32_trailer(stored.data(), stored.size());
    stored.insert(stored.end(), trailer.begin(), trailer.end());
  }
  return stored;
}

void cut_block(const double* block, const std::vector<hsize_t>& row_dims,
               const std::vector<hsize_t>& chunk, hsize_t n_rows, double* buffer,
               const std::function<void(const std::vector<hsize_t>& origin)>& visit) {
  const std::size_t d = row_dims.size();
  if (d == 0 || chunk.size() != d + 1)
    throw std::logic_error("cut_block: a chunk needs one dimension more than a row");
  std::size_t row_size = 1, chunk_size = 1;
  for (auto x : row_dims) row_size *= static_cast<std::size_t>(x);
  for (auto x : chunk) chunk_size *= static_cast<std::size_t>(x);
  if (row_size == 0 || chunk_size == 0) return;
  // Strides of the row dimensions in a block row, and the chunk grid over them.
  std::vector<std::size_t> stride(d, 1);
  for (std::size_t i = d - 1; i-- > 0;)
    stride[i] = stride[i + 1] * static_cast<std::size_t>(row_dims[i + 1]);
  std::vector<hsize_t> origin(d, 0);  // chunk origin in the row dimensions
  std::vector<hsize_t> index(d, 0);   // within the chunk, the last dimension as runs
  const std::size_t inner = static_cast<std::size_t>(chunk[d]);  // contiguous run in a chunk
  while (true) {
    // Gather the chunk: (t, i_1 .. i_d) over chunk[0] x ... x chunk[d], NaN outside the rows
    // given and the dataset's edge, as HDF5 fills a chunk before writing the selection into it.
    std::fill_n(buffer, chunk_size, kFill);
    std::size_t out = 0;
    for (hsize_t t = 0; t < chunk[0]; ++t) {
      std::fill(index.begin(), index.end(), 0);
      while (true) {
        bool inside = t < n_rows;
        std::size_t at = static_cast<std::size_t>(t) * row_size;
        for (std::size_t i = 0; i + 1 < d; ++i) {
          const hsize_t g = origin[i] + index[i];
          inside = inside && g < row_dims[i];
          at += static_cast<std::size_t>(g) * stride[i];
        }
        if (inside) {
          const hsize_t g0 = origin[d - 1];
          const std::size_t run = static_cast<std::size_t>(
              std::min<hsize_t>(chunk[d], row_dims[d - 1] > g0 ? row_dims[d - 1] - g0 : 0));
          std::copy_n(block + at + static_cast<std::size_t>(g0), run, buffer + out);
        }
        out += inner;
        // Next run: the odometer over the chunk's dimensions 1 .. d-1.
        std::size_t i = d - 1;
        while (i > 0) {
          if (++index[i - 1] < chunk[i]) break;
          index[i - 1] = 0;
          --i;
        }
        if (i == 0) break;
      }
    }
    visit(origin);
    // Next chunk of the grid.
    std::size_t i = d;
    while (i > 0) {
      origin[i - 1] += chunk[i];
      if (origin[i - 1] < row_dims[i - 1]) break;
      origin[i - 1] = 0;
      --i;
    }
    if (i == 0) return;
  }
}

void write_checksummed_block(hid_t dataset, const double* block,
                             const std::vector<hsize_t>& row_dims,
                             const std::vector<hsize_t>& chunk, hsize_t first_row, hsize_t n_rows) {
  static_assert(std::endian::native == std::endian::little, "the block holds H5T_IEEE_F64LE");
  std::size_t chunk_size = 1;
  for (auto x : chunk) chunk_size *= static_cast<std::size_t>(x);
  // One chunk and its 4-byte checksum after it: the stored bytes of a chunk that only Fletcher32
  // filters. Reused for every chunk of the block.
  std::vector<double> buffer(chunk_size + 1);
  const std::size_t bytes = chunk_size * sizeof(double);
  std::vector<hsize_t> offset(chunk.size());
  cut_block(block, row_dims, chunk, n_rows, buffer.data(), [&](const std::vector<hsize_t>& origin) {
    auto* stored = reinterpret_cast<unsigned char*>(buffer.data());
    const auto trailer = fletcher32_trailer(stored, bytes);
    std::copy(trailer.begin(), trailer.end(), stored + bytes);
    offset[0] = first_row;
    std::copy(origin.begin(), origin.end(), offset.begin() + 1);
    h5::check_status(H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, offset.data(), bytes + 4, stored),
                     "write a checksummed chunk");
  });
}

void BlockJob::compress() {
  try {
    std::size_t chunk_size = 1;
    for (auto x : chunk) chunk_size *= static_cast<std::size_t>(x);
    std::size_t row_size = 1;
    for (auto x : row_dims) row_size *= static_cast<std::size_t>(x);
    const std::size_t columns_stride =
        row_dims.empty() ? 0 : row_size / std::max<hsize_t>(1, row_dims[0]);
    std::vector<double> buffer(chunk_size);
    ChunkFilter filter(pipeline);
    std::size_t released = 0;  // values of each row given back (release_compressed_rows)
    cut_block(block.get(), row_dims, chunk, n_rows, buffer.data(),
              [&](const std::vector<hsize_t>& origin) {
                const std::size_t done = static_cast<std::size_t>(origin[0]) * columns_stride;
                if (release_compressed_rows && done - released >= kReleaseValues) {
                  // Every chunk of the columns before origin[0] is done: their values in every
                  // row go back to the system, so that the block shrinks as its compressed
                  // chunks grow. In runs of kReleaseValues per row at least: each call flushes
                  // the TLBs of every thread of the process (a call per narrow chunk column
                  // made ~11 000 of them on the dome).
                  for (std::size_t t = 0; t < static_cast<std::size_t>(chunk[0]); ++t)
                    release_pages(block.get(), t * row_size + released, t * row_size + done);
                  released = done;
                }
                std::vector<hsize_t> offset{first_row};
                offset.insert(offset.end(), origin.begin(), origin.end());
                chunks.push_back({std::move(offset), filter.apply(buffer.data(), chunk_size)});
              });
  } catch (...) {
    error = std::current_exception();
  }
}

double BlockJob::stored_bytes() const {
  double n = 0;
  for (const auto& c : chunks) n += static_cast<double>(c.bytes.size());
  return n;
}

void BlockJob::write() const {
  for (const Chunk& c : chunks)
    h5::check_status(
        H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, c.offset.data(), c.bytes.size(), c.bytes.data()),
        "write a compressed chunk");
}

BlockCompressor::BlockCompressor(bool background) : background_(background) {}

BlockCompressor::~BlockCompressor() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void BlockCompressor::submit(BlockJob job) {
  ++submitted_;
  if (background_) {
    std::unique_lock<std::mutex> lock(mutex_);
    bool started = worker_.joinable();
    if (!started) {
      try {
        worker_ = std::thread([this] { work(); });
        started = true;
      } catch (const std::system_error&) {
        // No thread to be had: compress here, as with --threads 1.
      }
    }
    if (started) {
      queue_.push_back(std::move(job));
      lock.unlock();
      wake_.notify_one();
      return;
    }
  }
  job.compress();
  job.block.reset();
  std::lock_guard<std::mutex> lock(mutex_);
  finished_.push_back(std::move(job));
}

void BlockCompressor::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    BlockJob job = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    job.compress();
    job.block.reset();  // back to the system now, not when the writer takes the chunks
    lock.lock();
    busy_ = false;
    finished_.push_back(std::move(job));
    done_.notify_all();
  }
}

std::vector<BlockJob> BlockCompressor::wait_all() {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return queue_.empty() && !busy_; });
  std::vector<BlockJob> jobs(std::make_move_iterator(finished_.begin()),
                             std::make_move_iterator(finished_.end()));
  finished_.clear();
  taken_ = submitted_;
  return jobs;
}

}  // namespace impactfe::result_series
