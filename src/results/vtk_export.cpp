#include "results/vtk_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

constexpr int kVtkPolyVertex = static_cast<int>(VtkCell::PolyVertex);
constexpr int kVtkTriangle = static_cast<int>(VtkCell::Triangle);

struct Cell {
  int type = kVtkPolyVertex;
  std::vector<int> points;  // 0-based point indices
  int element_id = 0, type_id = 0, mat_id = 0;
};

/// VTK cell type of an element: the registered cell of its type, a quadrilateral with K = L
/// drawn as a triangle; a poly-vertex for a type this program does not know.
int cell_type(const std::string& name, const std::vector<int>& nodes) {
  const ElementTypeDescriptor* d = find_element_type(name);
  if (d == nullptr) return kVtkPolyVertex;
  if (d->vtk_cell == VtkCell::Quad && nodes.size() == 4 && nodes[2] == nodes[3])
    return kVtkTriangle;
  return static_cast<int>(d->vtk_cell);
}

std::vector<Cell> build_cells(const ResultsReader& reader) {
  const auto& ids = reader.node_ids();
  std::vector<Cell> cells;
  for (const auto& e : reader.elements()) {
    Cell c;
    c.type = cell_type(e.type_name, e.nodes);
    std::vector<int> nodes = e.nodes;
    if (c.type == kVtkTriangle && nodes.size() == 4) nodes.resize(3);  // K = L: drop L
    bool ok = !nodes.empty();
    for (int n : nodes) {
      auto it = std::lower_bound(ids.begin(), ids.end(), n);
      if (it == ids.end() || *it != n) {
        ok = false;  // node not in the model section: cannot draw this element
        break;
      }
      c.points.push_back(static_cast<int>(it - ids.begin()));
    }
    if (!ok) continue;
    c.element_id = e.id;
    c.type_id = e.type;
    c.mat_id = e.mat;
    cells.push_back(std::move(c));
  }
  return cells;
}

double finite_or_zero(double v) {
  return std::isfinite(v) ? v : 0.0;
}

void write_vectors(std::ofstream& f, const char* name, const Eigen::MatrixXd& m, int first_col) {
  f << "        <DataArray type=\"Float64\" Name=\"" << name
    << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    f << fmt::format("          {:.10e} {:.10e} {:.10e}\n", finite_or_zero(m(i, first_col)),
                     finite_or_zero(m(i, first_col + 1)), finite_or_zero(m(i, first_col + 2)));
  f << "        </DataArray>\n";
}

template <typename Get>
void write_int_array(std::ofstream& f, const char* name, const char* type, std::size_t n, Get get) {
  f << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i)
    f << (i % 16 == 0 ? "          " : " ") << get(i) << (i % 16 == 15 || i + 1 == n ? "\n" : "");
  f << "        </DataArray>\n";
}

void write_vtu(const std::filesystem::path& file, const Eigen::MatrixXd& xyz,
               const std::vector<Cell>& cells, const TimePoint& p) {
  std::ofstream f(file);
  if (!f) throw InputError(fmt::format("cannot write '{}'", file.string()));
  f << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       "  <UnstructuredGrid>\n";
  f << fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", xyz.rows(),
                   cells.size());
  f << "      <Points>\n"
       "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < xyz.rows(); ++i)
    f << fmt::format("          {:.10e} {:.10e} {:.10e}\n", xyz(i, 0), xyz(i, 1), xyz(i, 2));
  f << "        </DataArray>\n      </Points>\n";

  f << "      <Cells>\n";
  std::vector<int> connectivity, offsets;
  for (const auto& c : cells) {
    connectivity.insert(connectivity.end(), c.points.begin(), c.points.end());
    offsets.push_back(static_cast<int>(connectivity.size()));
  }
  write_int_array(f, "connectivity", "Int32", connectivity.size(),
                  [&](std::size_t i) { return connectivity[i]; });
  write_int_array(f, "offsets", "Int32", offsets.size(), [&](std::size_t i) { return offsets[i]; });
  write_int_array(f, "types", "UInt8", cells.size(), [&](std::size_t i) { return cells[i].type; });
  f << "      </Cells>\n";

  f << "      <PointData Vectors=\"U\">\n";
  write_vectors(f, "U", p.displacement, 0);
  write_vectors(f, "ROT", p.displacement, 3);
  write_vectors(f, "V", p.velocity, 0);
  write_vectors(f, "A", p.acceleration, 0);
  write_vectors(f, "RF", p.reaction, 0);
  f << "      </PointData>\n";

  f << "      <CellData Scalars=\"element_id\">\n";
  write_int_array(f, "element_id", "Int32", cells.size(),
                  [&](std::size_t i) { return cells[i].element_id; });
  write_int_array(f, "type_id", "Int32", cells.size(),
                  [&](std::size_t i) { return cells[i].type_id; });
  write_int_array(f, "mat_id", "Int32", cells.size(),
                  [&](std::size_t i) { return cells[i].mat_id; });
  f << "      </CellData>\n";
  f << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  if (!f) throw InputError(fmt::format("cannot write '{}'", file.string()));
}

}  // namespace

int export_vtu_series(const ResultsReader& reader, const std::string& out_dir,
                      const std::string& stem) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw InputError(fmt::format("cannot create directory '{}': {}", out_dir, ec.message()));
  const Eigen::MatrixXd xyz = reader.node_coordinates();
  const std::vector<Cell> cells = build_cells(reader);

  std::string pvd =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  int written = 0;
  for (const auto& a : reader.analyses()) {
    for (int k = 0; k < a.n_time_points; ++k) {
      const TimePoint p = reader.time_point(a.index, k);
      const std::string name = fmt::format("{}_a{}_{:05d}.vtu", stem, a.index, k);
      write_vtu(fs::path(out_dir) / name, xyz, cells, p);
      pvd += fmt::format(
          "    <DataSet timestep=\"{:.10e}\" group=\"analysis_{}\" part=\"{}\" file=\"{}\"/>\n",
          p.time, a.index, a.index - 1, name);
      ++written;
    }
  }
  pvd += "  </Collection>\n</VTKFile>\n";
  const fs::path pvd_path = fs::path(out_dir) / (stem + ".pvd");
  std::ofstream f(pvd_path);
  f << pvd;
  if (!f) throw InputError(fmt::format("cannot write '{}'", pvd_path.string()));
  return written;
}

}  // namespace impactfe
