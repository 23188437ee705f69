#include "results/vtk_frames.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/numbers.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

/// An element nodal value (ITEM@k, node position k: PLANE182/183), not a cell quantity.
bool is_element_nodal_item(const std::string& item) {
  return item.find('@') != std::string::npos;
}

/// VTK cell type of an element: the registered cell of its type (a quadrilateral with K = L is a
/// triangle); a poly-vertex over its nodes for a type this program does not know. A
/// superelement is registered as a poly-vertex: its master nodes.
VtkCell cell_type(const std::string& name, const std::vector<int>& nodes) {
  const ElementTypeDescriptor* d = find_element_type(name);
  if (d == nullptr) return VtkCell::PolyVertex;
  if (d->vtk_cell == VtkCell::Quad && nodes.size() == 4 && nodes[2] == nodes[3])
    return VtkCell::Triangle;
  if (d->vtk_cell == VtkCell::QuadraticQuad && nodes.size() == 8 && nodes[2] == nodes[3] &&
      nodes[2] == nodes[6])
    return VtkCell::QuadraticTriangle;
  return d->vtk_cell;
}

/// Nodes a cell of this type takes, in VTK order (its corners and midside nodes, the order of
/// the element's nodes; all nodes of a poly-vertex), or empty when the node list does not fit.
std::vector<int> cell_nodes(VtkCell type, const std::vector<int>& nodes) {
  // The 8-node quadrilateral with K = L = O: the 6-node triangle I J K, midsides M N P.
  if (type == VtkCell::QuadraticTriangle && nodes.size() == 8)
    return {nodes[0], nodes[1], nodes[2], nodes[4], nodes[5], nodes[7]};
  const int cell_nodes = cell_topology(type).n_nodes();
  const std::size_t n = cell_nodes > 0 ? static_cast<std::size_t>(cell_nodes) : nodes.size();
  if (nodes.size() < n || n == 0) return {};
  return std::vector<int>(nodes.begin(), nodes.begin() + static_cast<long>(n));
}

}  // namespace

int VtkMesh::cell_of(int id) const {
  auto it = std::lower_bound(element_ids.begin(), element_ids.end(), id);
  return it != element_ids.end() && *it == id ? static_cast<int>(it - element_ids.begin()) : -1;
}

VtkMesh build_vtk_mesh(const ResultsReader& reader) {
  VtkMesh mesh;
  mesh.points = reader.node_coordinates();
  const auto& ids = reader.node_ids();
  mesh.offsets.push_back(0);
  for (const auto& e : reader.elements()) {  // ascending element id
    const VtkCell type = cell_type(e.type_name, e.nodes);
    std::vector<long long> points;
    for (int n : cell_nodes(type, e.nodes)) {
      auto it = std::lower_bound(ids.begin(), ids.end(), n);
      if (it == ids.end() || *it != n) {
        points.clear();
        break;
      }
      points.push_back(it - ids.begin());
    }
    if (points.empty()) {
      mesh.skipped_elements.push_back(e.id);
      continue;
    }
    mesh.types.push_back(static_cast<unsigned char>(type));
    mesh.connectivity.insert(mesh.connectivity.end(), points.begin(), points.end());
    mesh.offsets.push_back(static_cast<long long>(mesh.connectivity.size()));
    mesh.element_ids.push_back(e.id);
    mesh.type_ids.push_back(e.type);
    mesh.mat_ids.push_back(e.mat);
  }
  // Element result items of every family of every analysis (first point of each analysis).
  for (const auto& a : reader.analyses()) {
    if (a.n_time_points == 0 || a.element_families.empty()) continue;
    const TimePoint p = reader.time_point(a.index, 0);
    for (const auto& [family, table] : p.element_results)
      for (const auto& item : table.item_names)
        if (!is_element_nodal_item(item) &&
            std::find(mesh.cell_items.begin(), mesh.cell_items.end(), item) ==
                mesh.cell_items.end())
          mesh.cell_items.push_back(item);
  }
  return mesh;
}

std::vector<VtkFrame> vtk_frames(const ResultsReader& reader) {
  std::vector<std::tuple<double, int, int>> all;
  for (const auto& a : reader.analyses()) {
    if (!is_time_history(a.kind)) continue;
    const auto times = reader.times(a.index);
    for (std::size_t k = 0; k < times.size(); ++k)
      all.emplace_back(times[k], a.index, static_cast<int>(k));
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
  std::vector<VtkFrame> frames;
  for (const auto& [t, a, k] : all) {
    if (frames.empty() || !same_time(frames.back().time, t)) frames.push_back({t, {}});
    frames.back().sources.emplace_back(a, k);
  }
  for (auto& f : frames)
    std::stable_sort(f.sources.begin(), f.sources.end());  // analysis order: later ones win
  return frames;
}

const std::vector<std::string>& vtk_point_array_names() {
  static const std::vector<std::string> names = {"U", "ROT", "V", "A", "RF", "RM"};
  return names;
}

VtkFrameData read_vtk_frame(const ResultsReader& reader, const VtkMesh& mesh,
                            const VtkFrame& frame) {
  const std::size_t n_p = mesh.n_points(), n_c = mesh.n_cells();
  VtkFrameData out;
  for (const auto& name : vtk_point_array_names())
    out.point_arrays.emplace_back(name, std::vector<double>(3 * n_p, kNaN));
  for (const auto& item : mesh.cell_items)
    out.cell_arrays.emplace_back(item, std::vector<double>(n_c, kNaN));
  std::map<std::string, std::size_t> item_index;
  for (std::size_t i = 0; i < mesh.cell_items.size(); ++i) item_index[mesh.cell_items[i]] = i;

  auto merge_vectors = [&](std::size_t array, const Eigen::MatrixXd& m, int first_col) {
    if (m.rows() != static_cast<Eigen::Index>(n_p)) return;
    std::vector<double>& v = out.point_arrays[array].second;
    for (std::size_t i = 0; i < n_p; ++i)
      for (int c = 0; c < 3; ++c) {
        const double x = m(static_cast<Eigen::Index>(i), first_col + c);
        if (std::isfinite(x)) v[3 * i + static_cast<std::size_t>(c)] = x;
      }
  };
  for (const auto& [a, k] : frame.sources) {
    const TimePoint p = reader.time_point(a, k);
    merge_vectors(0, p.displacement, 0);
    merge_vectors(1, p.displacement, 3);
    merge_vectors(2, p.velocity, 0);
    merge_vectors(3, p.acceleration, 0);
    merge_vectors(4, p.reaction, 0);
    merge_vectors(5, p.reaction, 3);
    for (const auto& [family, table] : p.element_results) {
      for (std::size_t r = 0; r < table.element_ids.size(); ++r) {
        const int cell = mesh.cell_of(table.element_ids[r]);
        if (cell < 0) continue;
        for (std::size_t i = 0; i < table.item_names.size(); ++i) {
          const double x = table.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i));
          if (std::isfinite(x) && !is_element_nodal_item(table.item_names[i]))
            out.cell_arrays[item_index.at(table.item_names[i])]
                .second[static_cast<std::size_t>(cell)] = x;
        }
      }
    }
  }
  return out;
}

}  // namespace impactfe
