#pragma once
/// Test support: the chunks of a chunked HDF5 dataset as stored (raw, filtered bytes).
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace impactfe::testing {

struct StoredChunk {
  std::vector<unsigned char> bytes;
  unsigned filter_mask = 0;  // filters skipped for the chunk (0: every filter applied)
  bool read = false;         // H5Dread_chunk succeeded
};

/// Every chunk of dataset `ds`, in HDF5's chunk order (at most 4 dimensions).
inline std::vector<StoredChunk> stored_chunks(hid_t ds) {
  hid_t space = H5Dget_space(ds);
  hsize_t n = 0;
  H5Dget_num_chunks(ds, space, &n);
  std::vector<StoredChunk> chunks;
  for (hsize_t c = 0; c < n; ++c) {
    hsize_t offset[4] = {};
    StoredChunk chunk;
    haddr_t addr = 0;
    hsize_t size = 0;
    H5Dget_chunk_info(ds, space, c, offset, &chunk.filter_mask, &addr, &size);
    chunk.bytes.resize(size);
    uint32_t filters = 0;
    chunk.read = H5Dread_chunk(ds, H5P_DEFAULT, offset, &filters, chunk.bytes.data()) >= 0;
    chunks.push_back(std::move(chunk));
  }
  H5Sclose(space);
  return chunks;
}

/// How a dataset of a results file is stored: its chunk dimensions (the first along time: the
/// writer's block rows; empty when not chunked) and its bytes on disk.
struct StoredLayout {
  std::vector<hsize_t> chunk;
  hsize_t bytes = 0;
};
inline StoredLayout stored_layout(const std::string& path, const std::string& dataset) {
  StoredLayout layout;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(ds);
  hsize_t chunk[8] = {};
  const int rank = H5Pget_chunk(dcpl, 8, chunk);
  if (rank > 0) layout.chunk.assign(chunk, chunk + rank);
  layout.bytes = H5Dget_storage_size(ds);
  H5Pclose(dcpl);
  H5Dclose(ds);
  H5Fclose(f);
  return layout;
}

}  // namespace impactfe::testing
