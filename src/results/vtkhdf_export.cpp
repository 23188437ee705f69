// VTKHDF export (VTK's "VTKHDF File Format", version 2.0): a transient UnstructuredGrid whose
// geometry is stored once (every step's PartOffsets, PointOffsets, CellOffsets and
// ConnectivityIdOffsets are 0) and whose point and cell data grow by one step at a time, the
// offsets of each step's rows in Steps/PointDataOffsets and Steps/CellDataOffsets.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/errors.h"
#include "io/h5_util.h"
#include "results/vtk_export.h"
#include "results/vtk_frames.h"

namespace impactfe {

using h5::check;
using h5::check_status;
using h5::Handle;

namespace {

/// A dataset that grows along its first axis by whole blocks of rows.
struct Growing {
  Handle ds;
  hsize_t cols = 0;  // 0: 1-D
  hsize_t rows = 0;
  hid_t file_type = H5T_IEEE_F64LE;
  hid_t mem_type = H5T_NATIVE_DOUBLE;
};

Growing create_growing(hid_t loc, const std::string& name, hsize_t cols, hsize_t chunk_rows,
                       hid_t file_type, hid_t mem_type) {
  Growing g;
  g.cols = cols;
  g.file_type = file_type;
  g.mem_type = mem_type;
  // Chunks of at least kMinDeflateChunkElements values, so that they are compressed (shuffle +
  // deflate, h5::checked_creation_list): a small model's step is a few hundred values, and
  // chunks of one step each were stored raw.
  const hsize_t min_rows =
      (h5::kMinDeflateChunkElements + std::max<hsize_t>(cols, 1) - 1) / std::max<hsize_t>(cols, 1);
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED},
      chunk{std::max<hsize_t>({1, chunk_rows, min_rows})};
  if (cols > 0) {
    dims.push_back(cols);
    maxdims.push_back(cols);
    chunk.push_back(cols);
  }
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()),
                     "create dataspace for " + name));
  Handle dcpl = h5::checked_creation_list(chunk);
  g.ds =
      Handle(check(H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                   "create dataset " + name));
  return g;
}

void append_rows(Growing& g, hsize_t n_rows, const void* data) {
  if (n_rows == 0) return;
  std::vector<hsize_t> dims{g.rows + n_rows}, start{g.rows}, count{n_rows};
  if (g.cols > 0) {
    dims.push_back(g.cols);
    start.push_back(0);
    count.push_back(g.cols);
  }
  check_status(H5Dset_extent(g.ds, dims.data()), "extend dataset");
  Handle file_space(check(H5Dget_space(g.ds), "get dataspace"));
  check_status(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "select rows");
  Handle mem_space(check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                         "create memory dataspace"));
  check_status(H5Dwrite(g.ds, g.mem_type, mem_space, file_space, H5P_DEFAULT, data), "write rows");
  g.rows += n_rows;
}

/// A fixed dataset written in one go (geometry, static cell data).
template <typename T>
void write_fixed(hid_t loc, const std::string& name, const std::vector<T>& values, hsize_t cols,
                 hid_t file_type, hid_t mem_type) {
  Growing g =
      create_growing(loc, name, cols, std::max<std::size_t>(1, values.size()), file_type, mem_type);
  append_rows(g, cols > 0 ? values.size() / cols : values.size(), values.data());
}

void write_int_array_attribute(hid_t obj, const char* name, const std::vector<long long>& v) {
  hsize_t n = v.size();
  Handle space(check(H5Screate_simple(1, &n, nullptr), "create dataspace"));
  Handle attr(check(H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                    std::string("create attribute ") + name));
  check_status(H5Awrite(attr, H5T_NATIVE_LLONG, v.data()), std::string("write attribute ") + name);
}

/// VTK reads Type as a fixed-length ASCII string.
void write_ascii_attribute(hid_t obj, const char* name, const std::string& value) {
  Handle type(check(H5Tcopy(H5T_C_S1), "copy string type"));
  check_status(H5Tset_size(type, value.size()), "set string size");
  check_status(H5Tset_strpad(type, H5T_STR_NULLPAD), "set string padding");
  Handle space(check(H5Screate(H5S_SCALAR), "create scalar dataspace"));
  Handle attr(check(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT),
                    std::string("create attribute ") + name));
  check_status(H5Awrite(attr, type, value.data()), std::string("write attribute ") + name);
}

}  // namespace

ExportSummary export_vtkhdf(const ResultsReader& reader, const std::string& path) {
  h5::silence_errors();
  const VtkMesh mesh = build_vtk_mesh(reader);
  const std::vector<VtkFrame> frames = vtk_frames(reader);
  const auto n_p = static_cast<hsize_t>(mesh.n_points());
  const auto n_c = static_cast<hsize_t>(mesh.n_cells());
  ExportSummary summary;
  summary.points = mesh.n_points();
  summary.cells = mesh.n_cells();
  summary.skipped_elements = mesh.skipped_elements;
  try {
    Handle fapl = h5::file_access_checksummed();
    // A chunk holds several steps of an array and is written a step at a time: the cache keeps
    // the chunks being filled of every array (64 MB), so none is compressed twice.
    check_status(H5Pset_cache(fapl, 0, 12421, std::size_t{64} << 20, 1.0), "set chunk cache");
    Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl));
    if (!file.valid())
      throw InputError(fmt::format("cannot create '{}': {}", path, h5::error_detail()));
    Handle root = h5::create_group(file, "VTKHDF");
    write_int_array_attribute(root, "Version", {2, 0});
    write_ascii_attribute(root, "Type", "UnstructuredGrid");

    // Geometry, once.
    write_fixed<long long>(root, "NumberOfPoints", {static_cast<long long>(n_p)}, 0, H5T_STD_I64LE,
                           H5T_NATIVE_LLONG);
    write_fixed<long long>(root, "NumberOfCells", {static_cast<long long>(n_c)}, 0, H5T_STD_I64LE,
                           H5T_NATIVE_LLONG);
    write_fixed<long long>(root, "NumberOfConnectivityIds",
                           {static_cast<long long>(mesh.connectivity.size())}, 0, H5T_STD_I64LE,
                           H5T_NATIVE_LLONG);
    std::vector<double> xyz(3 * n_p);
    for (hsize_t i = 0; i < n_p; ++i)
      for (int c = 0; c < 3; ++c)
        xyz[3 * i + static_cast<hsize_t>(c)] = mesh.points(static_cast<Eigen::Index>(i), c);
    write_fixed(root, "Points", xyz, 3, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    write_fixed(root, "Types", mesh.types, 0, H5T_STD_U8LE, H5T_NATIVE_UCHAR);
    write_fixed(root, "Offsets", mesh.offsets, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    write_fixed(root, "Connectivity", mesh.connectivity, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);

    Handle point_data = h5::create_group(root, "PointData");
    Handle cell_data = h5::create_group(root, "CellData");
    h5::create_group(root, "FieldData");
    write_fixed(cell_data, "element_id", mesh.element_ids, 0, H5T_STD_I32LE, H5T_NATIVE_INT);
    write_fixed(cell_data, "type_id", mesh.type_ids, 0, H5T_STD_I32LE, H5T_NATIVE_INT);
    write_fixed(cell_data, "mat_id", mesh.mat_ids, 0, H5T_STD_I32LE, H5T_NATIVE_INT);

    std::vector<Growing> point_arrays, cell_arrays;
    for (const auto& name : vtk_point_array_names())
      point_arrays.push_back(create_growing(point_data, name, 3, std::max<hsize_t>(n_p, 64),
                                            H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE));
    for (const auto& item : mesh.cell_items)
      cell_arrays.push_back(create_growing(cell_data, item, 0, std::max<hsize_t>(n_c, 256),
                                           H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE));

    // Step by step: only one frame is in memory at a time.
    std::vector<double> times;
    for (const VtkFrame& frame : frames) {
      const VtkFrameData data = read_vtk_frame(reader, mesh, frame);
      for (std::size_t i = 0; i < point_arrays.size(); ++i)
        append_rows(point_arrays[i], n_p, data.point_arrays[i].second.data());
      for (std::size_t i = 0; i < cell_arrays.size(); ++i)
        append_rows(cell_arrays[i], n_c, data.cell_arrays[i].second.data());
      times.push_back(frame.time);
    }

    // The Steps group: times and, per step, where its rows start.
    const auto n_s = static_cast<hsize_t>(times.size());
    Handle steps = h5::create_group(root, "Steps");
    write_int_array_attribute(steps, "NSteps", {static_cast<long long>(n_s)});
    const std::vector<long long> zeros(n_s, 0), ones(n_s, 1);
    write_fixed(steps, "Values", times, 0, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    write_fixed(steps, "PartOffsets", zeros, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    write_fixed(steps, "NumberOfParts", ones, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    write_fixed(steps, "PointOffsets", zeros, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    write_fixed(steps, "CellOffsets", zeros, 1, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    write_fixed(steps, "ConnectivityIdOffsets", zeros, 1, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    Handle point_offsets = h5::create_group(steps, "PointDataOffsets");
    Handle cell_offsets = h5::create_group(steps, "CellDataOffsets");
    std::vector<long long> by_point(n_s), by_cell(n_s);
    for (hsize_t s = 0; s < n_s; ++s) {
      by_point[s] = static_cast<long long>(s * n_p);
      by_cell[s] = static_cast<long long>(s * n_c);
    }
    for (const auto& name : vtk_point_array_names())
      write_fixed(point_offsets, name, by_point, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    for (const auto& item : mesh.cell_items)
      write_fixed(cell_offsets, item, by_cell, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    for (const char* name : {"element_id", "type_id", "mat_id"})  // the same rows every step
      write_fixed(cell_offsets, name, zeros, 0, H5T_STD_I64LE, H5T_NATIVE_LLONG);
    check_status(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    throw InputError(fmt::format("cannot write '{}': {}", path, e.what()));
  }
  summary.frames = static_cast<int>(frames.size());
  summary.files.push_back(path);
  std::error_code ec;
  summary.bytes = std::filesystem::file_size(path, ec);
  return summary;
}

}  // namespace impactfe
