#pragma once
/// Thin RAII helpers over the HDF5 C API shared by the results file and the superelement file.
#include <hdf5.h>
#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace impactfe::h5 {

/// Owns one HDF5 identifier of any kind and releases it (H5Idec_ref) when destroyed.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      o.id_ = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0) H5Idec_ref(id_);
    id_ = -1;
  }
  /// Gives the identifier up without releasing it: a file whose write failed must not be
  /// closed, since closing flushes metadata that points at data the disk did not take.
  void abandon() { id_ = -1; }

 private:
  hid_t id_ = -1;
};

/// Silences the HDF5 error stack printer: libraries never print; failures become exceptions.
/// Also keeps HDF5 from installing its shutdown at exit (see h5_util.cpp).
void silence_errors();

/// Throws std::runtime_error("cannot <what>: <error_detail()>") when id < 0 (callers add the
/// file name).
hid_t check(hid_t id, const std::string& what);
void check_status(herr_t status, const std::string& what);
/// The reason for the last HDF5 failure ("" when the error stack is empty): the system's when
/// a system call failed ("No space left on device"), else the most specific message on the
/// stack, e.g. "checksum verification failed" or "truncated file: eof = 4096, ...".
std::string error_detail();

/// Makes sure the disk takes `bytes` more beyond the end of `file` (its HDF5 end of
/// allocation) before they are written: the blocks are allocated (fallocate, file size kept)
/// and the process's file size limit is checked. Throws std::runtime_error "cannot write
/// <path>: <reason>" (File too large, No space left on device) when it cannot, so that a write
/// never fails half-way through a flush (HDF5 would still rewrite the superblock with the new
/// end of file, leaving the file unreadable). Filesystems without fallocate: no reservation.
/// `reserved_end` (in/out, 0 at first) is the end of what was allocated before: a write that
/// fits in it costs no system call, and a new allocation reaches a quarter (at least 1 MB)
/// beyond the need, within the file size limit (a small model's run made 208 fallocate and
/// 209 getrlimit calls, one per stored point; issue 11).
void reserve_space(hid_t file, const std::string& path, double bytes, double& reserved_end);

/// Checks the index entries of the chunks holding the slab (start, count) of a chunked dataset
/// (no-op for other layouts). The chunk index of the HDF5 1.8 format (a v1 B-tree) carries no
/// checksum: a corrupted filter mask would switch the Fletcher32 check (and decompression) off
/// for its chunk, and corrupted chunk coordinates would lose the chunk, whose values would then
/// read as fill values. `require_all`: every chunk of the slab must exist (datasets whose every
/// chunk is written). Throws std::runtime_error naming the dataset.
void verify_chunk_index(hid_t dataset, const std::vector<hsize_t>& start,
                        const std::vector<hsize_t>& count, bool require_all);

/// File access property list of files written in the HDF5 1.8 format, whose superblock and
/// object headers carry checksums (readable by HDF5 1.8 and later, h5py included).
Handle file_access_checksummed();

/// How the dataset writers below store strings: variable length (no size limit; the bytes live
/// in the global heap, which carries no checksum) or fixed length (inline, so checksummed with
/// the object header or chunk that holds them).
enum class StringLayout { Variable, Fixed };
/// How they store numeric datasets: contiguous, or chunked with the shuffle, deflate and
/// Fletcher32 filters (compressed, and a corrupted chunk fails to read instead of returning
/// wrong numbers).
enum class Storage { Contiguous, Checked };

/// Chunks smaller than this (values) are not deflated whatever the level (see
/// checked_creation_list): 4096 values = 32 kB of float64.
inline constexpr hsize_t kMinDeflateChunkElements = 4096;

/// Dataset creation list for a chunked, compressed and checksummed dataset (shuffle, deflate at
/// `level` for chunks of at least kMinDeflateChunkElements values; otherwise, and at level 0:
/// Fletcher32 only); `fill` (optional) is the float64 fill value.
Handle checked_creation_list(const std::vector<hsize_t>& chunk, const double* fill = nullptr,
                             int level = 4);

/// Bytes of raw data the datasets of an open file hold (their storage sizes).
hsize_t stored_bytes(hid_t file);
bool exists(hid_t loc, const std::string& name);
/// Like exists() for a path "a/b/c" whose intermediate groups may be missing too.
bool exists_path(hid_t loc, const std::string& path);

Handle create_group(hid_t loc, const std::string& name);
/// Group (or file: `file_creation` for the root group) creation list that keeps links and
/// attributes in the object header, which carries a checksum, instead of moving them to "dense"
/// storage past 8 entries (fractal heap blocks without checksums).
Handle checksummed_group_creation_list(bool file_creation = false);
Handle open_group(hid_t loc, const std::string& name);

/// Variable-length UTF-8 string datatype.
Handle string_type();

void write_attribute(hid_t obj, const std::string& name, double value);
void write_attribute(hid_t obj, const std::string& name, const std::string& value,
                     StringLayout layout = StringLayout::Variable);
void write_attribute(hid_t obj, const std::string& name, const std::vector<std::string>& values,
                     StringLayout layout = StringLayout::Variable);
/// Integer attribute (int64): counts stay integers.
void write_integer_attribute(hid_t obj, const std::string& name, long long value);

std::string read_string_attribute(hid_t obj, const std::string& name);
double read_double_attribute(hid_t obj, const std::string& name);
std::vector<std::string> read_string_list_attribute(hid_t obj, const std::string& name);
/// Names of all attributes of an object in creation/name order.
std::vector<std::string> attribute_names(hid_t obj);

/// Fixed-size dataset (row-major data, dims as given). Zero-sized datasets are allowed.
void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const double* data, Storage storage = Storage::Contiguous);
void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const int* data, Storage storage = Storage::Contiguous);
void write_dataset(hid_t loc, const std::string& name, const std::vector<std::string>& values,
                   StringLayout layout = StringLayout::Variable);

/// Current dimensions of a dataset.
std::vector<hsize_t> dims_of(hid_t dataset);

std::vector<double> read_doubles(hid_t loc, const std::string& name);
/// A 2-D float64 dataset (row-major in the file) as a matrix.
Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name);
void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m);
std::vector<int> read_ints(hid_t loc, const std::string& name);
std::vector<std::string> read_strings(hid_t loc, const std::string& name);

/// Writes the hyperslab (start, count) of a float64 dataset from `data` (row-major); nothing
/// when the slab is empty.
void write_slab(hid_t dataset, const std::vector<hsize_t>& start, const std::vector<hsize_t>& count,
                const double* data);

/// Reads the hyperslab [start, start+count) of a dataset into a dense row-major buffer.
std::vector<double> read_slab(hid_t dataset, const std::vector<hsize_t>& start,
                              const std::vector<hsize_t>& count);

}  // namespace impactfe::h5
