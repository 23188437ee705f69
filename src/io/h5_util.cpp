#include "io/h5_util.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/resource.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace impactfe::h5 {

void silence_errors() {
  // No library shutdown at exit: every file is flushed after each write and closed by its
  // owner, and after a failed write (a full disk) HDF5's shutdown crashes closing the dataset
  // whose close already failed (HDF5 1.10). Only effective before the library starts, so done
  // here, the first HDF5 call of every reader and writer.
  static const bool no_atexit = [] {
    H5dont_atexit();
    // HDF5 keeps freed fixed-size objects of a kind for reuse up to 64 kB per kind (1 MB in
    // all) by default: a file's metadata cache (0.5 MB, zeroed when created) went back to the
    // system at every close, and the next file open or create paid its page faults again
    // (issue 11). 1 MB per kind, 4 MB in all; the array and block lists keep their defaults
    // (-1 would lift their limits).
    H5set_free_list_limits(4 << 20, 1 << 20, 4 << 20, 256 << 10, 16 << 20, 1 << 20);
    return true;
  }();
  (void)no_atexit;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

namespace {

/// Walker of the HDF5 error stack, innermost entry first: keeps the system's reason when a
/// system call failed (the "error message = '...'" part: "No space left on device", "No such
/// file or directory"), else the most specific entry with a text of its own (e.g. "checksum
/// verification failed", "truncated file: eof = 4096, ...").
herr_t most_specific(unsigned, const H5E_error2_t* error, void* data) {
  auto& out = *static_cast<std::string*>(data);
  if (error->desc == nullptr || error->desc[0] == '\0') return 0;
  const std::string desc = error->desc;
  const std::string key = "error message = '";
  const auto pos = desc.find(key);
  if (pos != std::string::npos) {
    const auto end = desc.find('\'', pos + key.size());
    out = desc.substr(pos + key.size(), end == std::string::npos ? end : end - pos - key.size());
    return 1;  // the system's reason: stop here
  }
  if (out.empty()) out = desc;
  return 0;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string detail = error_detail();
  H5Eclear2(H5E_DEFAULT);
  throw std::runtime_error(detail.empty() ? fmt::format("cannot {}", what)
                                          : fmt::format("cannot {}: {}", what, detail));
}

}  // namespace

std::string error_detail() {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, most_specific, &detail);
  return detail;
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

void reserve_space(hid_t file, const std::string& path, double bytes, double& reserved_end) {
  hsize_t size = 0;  // max(end of file, end of allocation)
  check_status(H5Fget_filesize(file, &size), "get the size of " + path);
  const double target = static_cast<double>(size) + std::max(0.0, bytes);
  if (target <= reserved_end) return;
  int error = 0;
  double ahead = target + std::max(1024.0 * 1024.0, 0.25 * target);
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double most = static_cast<double>(limit.rlim_cur);
    if (target > most) error = EFBIG;
    ahead = std::min(ahead, most);
  }
  void* handle = nullptr;
  double reached = 0.0;
  if (error == 0 && H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) >= 0 && handle != nullptr) {
    const int fd = *static_cast<int*>(handle);  // the sec2 driver's descriptor
    // The margin first; on a disk too full for it, the need alone.
    for (const double end : {ahead, target}) {
      if (fallocate(fd, FALLOC_FL_KEEP_SIZE, 0, static_cast<off_t>(end)) == 0) {
        reached = end;
        break;
      }
      if (errno == EOPNOTSUPP || errno == ENOSYS) break;  // nothing to reserve with
      error = errno;
    }
    if (reached > 0.0) error = 0;
  }
  H5Eclear2(H5E_DEFAULT);
  if (error != 0)
    throw std::runtime_error(fmt::format("cannot write {}: {}", path, std::strerror(error)));
  reserved_end = reached;
}

void verify_chunk_index(hid_t dataset, const std::vector<hsize_t>& start,
                        const std::vector<hsize_t>& count, bool require_all) {
  Handle dcpl(check(H5Dget_create_plist(dataset), "get dataset creation list"));
  if (H5Pget_layout(dcpl) != H5D_CHUNKED) return;
  const auto rank = start.size();
  std::vector<hsize_t> chunk(rank);
  if (H5Pget_chunk(dcpl, static_cast<int>(rank), chunk.data()) != static_cast<int>(rank)) return;
  std::vector<hsize_t> first(rank), last(rank), at(rank), offset(rank);
  for (std::size_t d = 0; d < rank; ++d) {
    if (count[d] == 0) return;
    first[d] = start[d] / chunk[d];
    last[d] = (start[d] + count[d] - 1) / chunk[d];
    at[d] = first[d];
  }
  auto name = [&] {
    std::string n(256, '\0');
    const auto len = H5Iget_name(dataset, n.data(), n.size());
    n.resize(len > 0 ? std::min<std::size_t>(static_cast<std::size_t>(len), n.size()) : 0);
    return n;
  };
  while (true) {
    for (std::size_t d = 0; d < rank; ++d) offset[d] = at[d] * chunk[d];
    unsigned mask = 0;
    haddr_t addr = HADDR_UNDEF;
    hsize_t size = 0;
    const bool found = H5Dget_chunk_info_by_coord(dataset, offset.data(), &mask, &addr, &size) >= 0;
    H5Eclear2(H5E_DEFAULT);
    if (found && addr != HADDR_UNDEF && mask != 0)
      throw std::runtime_error(
          fmt::format("a chunk index entry of {} is corrupted (its filter mask is not 0)", name()));
    if (require_all && (!found || addr == HADDR_UNDEF))
      throw std::runtime_error(
          fmt::format("a chunk index entry of {} is corrupted (a chunk is missing)", name()));
    std::size_t d = rank;
    while (d > 0) {
      --d;
      if (++at[d] <= last[d]) break;
      at[d] = first[d];
      if (d == 0) return;
    }
  }
}

Handle file_access_checksummed() {
  // The 1.8 format: checksummed superblock (v2) and object headers (v2). Not 1.10's superblock
  // v3, which marks a file open for writing so that other processes cannot read it while a run
  // writes it (without SWMR).
  Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "create file access list"));
  check_status(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18),
               "select the HDF5 1.8 file format");
  return fapl;
}

Handle checked_creation_list(const std::vector<hsize_t>& chunk, const double* fill, int level) {
  Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "create property list"));
  check_status(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), "set chunk");
  // Shuffle groups the bytes of equal significance, which deflate then compresses well.
  // Fletcher32 last, so the checksum covers the stored bytes.
  // A chunk of fewer than kMinDeflateChunkElements values is stored without deflate: zlib sets
  // up and clears ~256 kB of state for every chunk it compresses, which for a chunk of a few kB
  // costs far more than the bytes it saves (a 2-element deck: 16 % of its instructions went to
  // deflate for files a few kB smaller; issue 11).
  const hsize_t chunk_elements =
      std::accumulate(chunk.begin(), chunk.end(), hsize_t{1}, std::multiplies<>());
  if (level > 0 && chunk_elements >= kMinDeflateChunkElements) {
    check_status(H5Pset_shuffle(dcpl), "set shuffle filter");
    check_status(H5Pset_deflate(dcpl, static_cast<unsigned>(level)), "set deflate filter");
  }
  check_status(H5Pset_fletcher32(dcpl), "set Fletcher32 filter");
  if (fill != nullptr)
    check_status(H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, fill), "set fill value");
  return dcpl;
}

/// Bytes of raw data the datasets of a file hold (their storage sizes).
hsize_t stored_bytes(hid_t file) {
  hsize_t total = 0;
  H5Ovisit(
      file, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t loc, const char* name, const H5O_info_t* info, void* data) -> herr_t {
        if (info->type != H5O_TYPE_DATASET) return 0;
        const hid_t ds = H5Dopen2(loc, name, H5P_DEFAULT);
        if (ds < 0) return 0;
        *static_cast<hsize_t*>(data) += H5Dget_storage_size(ds);
        H5Dclose(ds);
        return 0;
      },
      &total);
  return total;
}

bool exists(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

bool exists_path(hid_t loc, const std::string& path) {
  std::size_t pos = 0;
  while (true) {
    pos = path.find('/', pos + 1);
    const std::string prefix = path.substr(0, pos);
    if (!prefix.empty() && !exists(loc, prefix)) return false;
    if (pos == std::string::npos) return true;
  }
}

Handle checksummed_group_creation_list(bool file_creation) {
  Handle plist(check(H5Pcreate(file_creation ? H5P_FILE_CREATE : H5P_GROUP_CREATE),
                     "create group property list"));
  check_status(H5Pset_link_phase_change(plist, 65535, 65535), "keep links compact");
  check_status(H5Pset_attr_phase_change(plist, 65535, 65535), "keep attributes compact");
  return plist;
}

Handle create_group(hid_t loc, const std::string& name) {
  return Handle(check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      "create group " + name));
}

Handle open_group(hid_t loc, const std::string& name) {
  return Handle(check(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), "open group " + name));
}

Handle string_type() {
  Handle t(check(H5Tcopy(H5T_C_S1), "create string type"));
  check_status(H5Tset_size(t, H5T_VARIABLE), "set string size");
  check_status(H5Tset_cset(t, H5T_CSET_UTF8), "set string charset");
  return t;
}

namespace {

/// Fixed-length, NUL-padded UTF-8 string type of `size` bytes (at least 1).
Handle fixed_string_type(std::size_t size) {
  Handle t(check(H5Tcopy(H5T_C_S1), "create string type"));
  check_status(H5Tset_size(t, std::max<std::size_t>(1, size)), "set string size");
  check_status(H5Tset_strpad(t, H5T_STR_NULLPAD), "set string padding");
  check_status(H5Tset_cset(t, H5T_CSET_UTF8), "set string charset");
  return t;
}

std::size_t longest(const std::vector<std::string>& values) {
  std::size_t n = 1;
  for (const auto& v : values) n = std::max(n, v.size());
  return n;
}

/// The strings laid out for a fixed-length type of `size` bytes each.
std::vector<char> fixed_buffer(const std::vector<std::string>& values, std::size_t size) {
  std::vector<char> buf(values.size() * size, '\0');
  for (std::size_t i = 0; i < values.size(); ++i)
    std::copy(values[i].begin(), values[i].end(), buf.begin() + static_cast<long>(i * size));
  return buf;
}

}  // namespace

namespace {

void delete_attribute_if_present(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
}

hsize_t product(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

void write_dataset_raw(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                       hid_t file_type, hid_t mem_type, const void* data,
                       Storage storage = Storage::Contiguous) {
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                     "create dataspace for " + name));
  // An empty dataset cannot be chunked (a chunk dimension may not exceed a fixed extent of 0).
  Handle dcpl;
  if (storage == Storage::Checked && product(dims) > 0) {
    // One chunk of at most ~1 MB along the first dimension: the model section is read whole.
    std::vector<hsize_t> chunk = dims;
    const hsize_t row = product(dims) / dims[0] * H5Tget_size(file_type);
    chunk[0] =
        std::max<hsize_t>(1, std::min<hsize_t>(dims[0], (1u << 20) / std::max<hsize_t>(row, 1)));
    dcpl = checked_creation_list(chunk);
  }
  Handle ds(check(H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT,
                             dcpl.valid() ? dcpl.get() : H5P_DEFAULT, H5P_DEFAULT),
                  "create dataset " + name));
  if (product(dims) > 0)
    check_status(H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}

}  // namespace

void write_attribute(hid_t obj, const std::string& name, double value) {
  delete_attribute_if_present(obj, name);
  Handle space(check(H5Screate(H5S_SCALAR), "create scalar dataspace"));
  Handle attr(check(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute " + name));
  check_status(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

void write_integer_attribute(hid_t obj, const std::string& name, long long value) {
  delete_attribute_if_present(obj, name);
  Handle space(check(H5Screate(H5S_SCALAR), "create scalar dataspace"));
  Handle attr(check(H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute " + name));
  check_status(H5Awrite(attr, H5T_NATIVE_LLONG, &value), "write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, const std::string& value,
                     StringLayout layout) {
  delete_attribute_if_present(obj, name);
  Handle space(check(H5Screate(H5S_SCALAR), "create scalar dataspace"));
  if (layout == StringLayout::Fixed) {
    Handle type = fixed_string_type(value.size());
    Handle attr(check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name));
    const std::vector<char> buf = fixed_buffer({value}, std::max<std::size_t>(1, value.size()));
    check_status(H5Awrite(attr, type, buf.data()), "write attribute " + name);
    return;
  }
  Handle type = string_type();
  Handle attr(check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute " + name));
  const char* p = value.c_str();
  check_status(H5Awrite(attr, type, &p), "write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, const std::vector<std::string>& values,
                     StringLayout layout) {
  delete_attribute_if_present(obj, name);
  hsize_t n = values.size();
  Handle space(check(H5Screate_simple(1, &n, nullptr), "create dataspace"));
  if (layout == StringLayout::Fixed) {
    const std::size_t size = longest(values);
    Handle type = fixed_string_type(size);
    Handle attr(check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name));
    const std::vector<char> buf = fixed_buffer(values, size);
    if (n > 0) check_status(H5Awrite(attr, type, buf.data()), "write attribute " + name);
    return;
  }
  Handle type = string_type();
  Handle attr(check(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute " + name));
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  if (n > 0) check_status(H5Awrite(attr, type, ptrs.data()), "write attribute " + name);
}

namespace {

/// Reads n strings (variable or fixed length) from an attribute or dataset.
template <typename ReadFn>
std::vector<std::string> read_string_values(hid_t file_type, hid_t space, hsize_t n, ReadFn read) {
  std::vector<std::string> out;
  if (n == 0) return out;
  if (H5Tis_variable_str(file_type) > 0) {
    Handle mem = string_type();
    std::vector<char*> buf(n, nullptr);
    check_status(read(mem.get(), static_cast<void*>(buf.data())), "read strings");
    for (char* p : buf) out.emplace_back(p ? p : "");
    H5Dvlen_reclaim(mem, space, H5P_DEFAULT, buf.data());
  } else {
    std::size_t size = H5Tget_size(file_type);
    Handle mem(check(H5Tcopy(H5T_C_S1), "copy string type"));
    H5Tset_size(mem, size);
    H5Tset_cset(mem, H5Tget_cset(file_type));  // no conversion between character sets exists
    H5Tset_strpad(mem, H5T_STR_NULLPAD);       // all `size` bytes may be characters
    std::vector<char> buf(size * n, '\0');
    check_status(read(mem.get(), static_cast<void*>(buf.data())), "read strings");
    for (hsize_t i = 0; i < n; ++i) {
      std::string s(buf.data() + i * size, size);
      s.erase(s.find_last_not_of(std::string("\0 ", 2)) + 1);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace

std::string read_string_attribute(hid_t obj, const std::string& name) {
  auto v = read_string_list_attribute(obj, name);
  return v.empty() ? std::string() : v.front();
}

double read_double_attribute(hid_t obj, const std::string& name) {
  Handle attr(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name));
  double v = 0.0;
  check_status(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

std::vector<std::string> read_string_list_attribute(hid_t obj, const std::string& name) {
  Handle attr(check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name));
  Handle type(check(H5Aget_type(attr), "get attribute type"));
  Handle space(check(H5Aget_space(attr), "get attribute space"));
  hssize_t n = H5Sget_simple_extent_npoints(space);
  return read_string_values(type, space, static_cast<hsize_t>(n),
                            [&](hid_t mem, void* buf) { return H5Aread(attr, mem, buf); });
}

std::vector<std::string> attribute_names(hid_t obj) {
  std::vector<std::string> names;
  hsize_t idx = 0;
  H5Aiterate2(
      obj, H5_INDEX_NAME, H5_ITER_INC, &idx,
      [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const double* data, Storage storage) {
  write_dataset_raw(loc, name, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, storage);
}

void write_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const int* data, Storage storage) {
  write_dataset_raw(loc, name, dims, H5T_STD_I32LE, H5T_NATIVE_INT, data, storage);
}

void write_dataset(hid_t loc, const std::string& name, const std::vector<std::string>& values,
                   StringLayout layout) {
  if (layout == StringLayout::Fixed) {
    const std::size_t size = longest(values);
    Handle type = fixed_string_type(size);
    const std::vector<char> buf = fixed_buffer(values, size);
    write_dataset_raw(loc, name, {values.size()}, type, type, buf.data(), Storage::Checked);
    return;
  }
  Handle type = string_type();
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  write_dataset_raw(loc, name, {values.size()}, type, type, ptrs.data());
}

std::vector<hsize_t> dims_of(hid_t dataset) {
  Handle space(check(H5Dget_space(dataset), "get dataspace"));
  int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

namespace {
template <typename T>
std::vector<T> read_all(hid_t loc, const std::string& name, hid_t mem_type) {
  Handle ds(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset " + name));
  auto dims = dims_of(ds);
  std::vector<T> out(product(dims));
  // Every chunk of a dataset read whole was written (model sections, time axes, modes).
  if (!out.empty()) verify_chunk_index(ds, std::vector<hsize_t>(dims.size(), 0), dims, true);
  if (!out.empty())
    check_status(H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
                 "read dataset " + name);
  return out;
}
}  // namespace

std::vector<double> read_doubles(hid_t loc, const std::string& name) {
  return read_all<double>(loc, name, H5T_NATIVE_DOUBLE);
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd read_matrix(hid_t loc, const std::string& name) {
  Handle ds(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset " + name));
  const auto dims = dims_of(ds);
  if (dims.size() != 2) throw std::runtime_error(fmt::format("dataset {} is not 2-D", name));
  RowMajor r(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (r.size() > 0)
    check_status(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.data()),
                 "read dataset " + name);
  return r;
}

void write_matrix(hid_t loc, const std::string& name, const Eigen::MatrixXd& m) {
  const RowMajor r = m;
  write_dataset(loc, name, {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())},
                r.data());
}

std::vector<int> read_ints(hid_t loc, const std::string& name) {
  return read_all<int>(loc, name, H5T_NATIVE_INT);
}

std::vector<std::string> read_strings(hid_t loc, const std::string& name) {
  Handle ds(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset " + name));
  Handle type(check(H5Dget_type(ds), "get dataset type"));
  Handle space(check(H5Dget_space(ds), "get dataset space"));
  hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n > 0) verify_chunk_index(ds, {0}, {static_cast<hsize_t>(n)}, true);
  // The memory type differs from the file's (padding), so HDF5 converts through a buffer of
  // the transfer list's size: 1 MB by default, allocated and cleared for every read (256 page
  // faults, a tenth of a small run's). This read needs at most its own size.
  Handle transfer(check(H5Pcreate(H5P_DATASET_XFER), "create transfer property list"));
  const std::size_t bytes = static_cast<std::size_t>(std::max<hssize_t>(n, 1)) *
                            std::max(H5Tget_size(type), sizeof(char*));
  check_status(H5Pset_buffer(transfer, std::max<std::size_t>(bytes, 4096), nullptr, nullptr),
               "set conversion buffer");
  return read_string_values(type, space, static_cast<hsize_t>(n), [&](hid_t mem, void* buf) {
    return H5Dread(ds, mem, H5S_ALL, H5S_ALL, transfer, buf);
  });
}

void write_slab(hid_t dataset, const std::vector<hsize_t>& start, const std::vector<hsize_t>& count,
                const double* data) {
  hsize_t n = product(count);
  if (n == 0) return;
  Handle file_space(check(H5Dget_space(dataset), "get dataspace"));
  check_status(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "select hyperslab");
  // The memory space has the selection's own shape (same rank and extents), not a flat 1-D run
  // of n values: then HDF5 sees "same shape" and copies each chunk's part as contiguous runs;
  // with a 1-D memory space it maps every element to its chunk one by one (H5D__chunk_mem_cb,
  // 1.1 M calls and ~7 % of a helmet run's instructions). Same bytes in the file.
  Handle mem_space(check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                         "create memory dataspace"));
  check_status(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, data),
               "write hyperslab");
}

std::vector<double> read_slab(hid_t dataset, const std::vector<hsize_t>& start,
                              const std::vector<hsize_t>& count) {
  std::vector<double> out(product(count));
  if (out.empty()) return out;
  Handle file_space(check(H5Dget_space(dataset), "get dataspace"));
  check_status(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "select hyperslab");
  // Memory space of the selection's shape: see write_slab.
  Handle mem_space(check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                         "create memory dataspace"));
  check_status(H5Dread(dataset, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, out.data()),
               "read hyperslab");
  return out;
}

}  // namespace impactfe::h5
