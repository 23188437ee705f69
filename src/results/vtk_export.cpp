// VTU + PVD export: one binary VTK XML UnstructuredGrid file per frame, data appended raw and
// zlib-compressed in blocks (VTK's vtkZLibDataCompressor layout, UInt64 headers), and a ParaView
// collection listing the frames with their times.
#include "results/vtk_export.h"

#include <fmt/format.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "results/vtk_frames.h"

namespace impactfe {

namespace {

constexpr std::size_t kBlockSize = 32768;  // VTK's default compression block size

/// One DataArray of the appended section: its XML tag and its compressed bytes.
struct Appended {
  std::string xml;      // everything in the DataArray tag but the offset
  std::string payload;  // header (UInt64 counts) + compressed blocks
};

/// VTK's compressed-data layout: [n_blocks, block_size, last_block_size, compressed sizes...]
/// followed by each block compressed with zlib.
std::string compress_blocks(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  const std::size_t n_blocks = (bytes + kBlockSize - 1) / kBlockSize;
  std::vector<std::uint64_t> header{n_blocks, kBlockSize, bytes % kBlockSize};
  std::string body;
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const std::size_t n = std::min(kBlockSize, bytes - b * kBlockSize);
    uLongf out_size = compressBound(static_cast<uLong>(n));
    std::string out(out_size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &out_size, p + b * kBlockSize,
                  static_cast<uLong>(n), 6) != Z_OK)
      throw std::runtime_error("zlib compression failed");
    out.resize(out_size);
    header.push_back(out_size);
    body += out;
  }
  std::string result(reinterpret_cast<const char*>(header.data()), header.size() * 8);
  return result + body;
}

template <typename T>
Appended array(const std::string& vtk_type, const std::string& name, int components,
               const std::vector<T>& values) {
  Appended a;
  a.xml = fmt::format("<DataArray type=\"{}\"{}{} format=\"appended\"", vtk_type,
                      name.empty() ? "" : " Name=\"" + name + "\"",
                      components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "");
  a.payload = compress_blocks(values.data(), values.size() * sizeof(T));
  return a;
}

void write_vtu(const std::filesystem::path& file, const VtkMesh& mesh, const VtkFrameData& data,
               const std::vector<double>& xyz, const std::vector<std::int64_t>& end_offsets) {
  std::vector<Appended> point_data, cell_data, points, cells;
  for (const auto& [name, values] : data.point_arrays)
    point_data.push_back(array("Float64", name, 3, values));
  cell_data.push_back(array("Int32", "element_id", 1, mesh.element_ids));
  cell_data.push_back(array("Int32", "type_id", 1, mesh.type_ids));
  cell_data.push_back(array("Int32", "mat_id", 1, mesh.mat_ids));
  for (const auto& [name, values] : data.cell_arrays)
    cell_data.push_back(array("Float64", name, 1, values));
  points.push_back(array("Float64", "Points", 3, xyz));
  std::vector<std::int64_t> connectivity(mesh.connectivity.begin(), mesh.connectivity.end());
  cells.push_back(array("Int64", "connectivity", 1, connectivity));
  cells.push_back(array("Int64", "offsets", 1, end_offsets));
  cells.push_back(array("UInt8", "types", 1, mesh.types));

  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
      "  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", mesh.n_points(),
                     mesh.n_cells());
  std::string appended;
  auto section = [&](const char* tag, const std::string& attrs, const std::vector<Appended>& v) {
    xml += fmt::format("      <{}{}>\n", tag, attrs);
    for (const auto& a : v) {
      xml += fmt::format("        {} offset=\"{}\"/>\n", a.xml, appended.size());
      appended += a.payload;
    }
    xml += fmt::format("      </{}>\n", tag);
  };
  section("PointData", " Vectors=\"U\"", point_data);
  section("CellData", " Scalars=\"element_id\"", cell_data);
  section("Points", "", points);
  section("Cells", "", cells);
  xml += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  std::ofstream f(file, std::ios::binary);
  f << xml;
  f.write(appended.data(), static_cast<std::streamsize>(appended.size()));
  f << "\n  </AppendedData>\n</VTKFile>\n";
  if (!f) throw InputError(fmt::format("cannot write '{}'", file.string()));
}

}  // namespace

ExportSummary export_vtu_series(const ResultsReader& reader, const std::string& out_dir,
                                const std::string& stem) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw InputError(fmt::format("cannot create directory '{}': {}", out_dir, ec.message()));
  const VtkMesh mesh = build_vtk_mesh(reader);
  std::vector<double> xyz(3 * mesh.n_points());
  for (std::size_t i = 0; i < mesh.n_points(); ++i)
    for (int c = 0; c < 3; ++c)
      xyz[3 * i + static_cast<std::size_t>(c)] = mesh.points(static_cast<Eigen::Index>(i), c);
  const std::vector<std::int64_t> end_offsets(mesh.offsets.begin() + 1, mesh.offsets.end());

  ExportSummary summary;
  summary.points = mesh.n_points();
  summary.cells = mesh.n_cells();
  summary.skipped_elements = mesh.skipped_elements;
  const fs::path pvd_path = fs::path(out_dir) / (stem + ".pvd");
  summary.files.push_back(pvd_path.string());
  std::string pvd =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  int k = 0;
  for (const VtkFrame& frame : vtk_frames(reader)) {  // one frame in memory at a time
    const std::string name = fmt::format("{}_{:05d}.vtu", stem, k++);
    const fs::path path = fs::path(out_dir) / name;
    write_vtu(path, mesh, read_vtk_frame(reader, mesh, frame), xyz, end_offsets);
    pvd += fmt::format("    <DataSet timestep=\"{:.17g}\" part=\"0\" file=\"{}\"/>\n", frame.time,
                       name);
    summary.files.push_back(path.string());
    summary.bytes += fs::file_size(path, ec);
  }
  pvd += "  </Collection>\n</VTKFile>\n";
  std::ofstream f(pvd_path);
  f << pvd;
  if (!f) throw InputError(fmt::format("cannot write '{}'", pvd_path.string()));
  f.close();
  summary.frames = k;
  summary.bytes += fs::file_size(pvd_path, ec);
  return summary;
}

}  // namespace impactfe
