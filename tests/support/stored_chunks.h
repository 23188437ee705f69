#pragma once
/// Test support: the chunks of a chunked HDF5 dataset as stored (raw, filtered bytes).
#include <hdf5.h>

#include <cstdint>
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

}  // namespace impactfe::testing
