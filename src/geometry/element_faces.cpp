#include "geometry/element_faces.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "elements/element_registry.h"

namespace impactfe::geometry {

namespace {
const ElementTypeDescriptor* descriptor_of(const Model& model, const ElementRecord& e) {
  const auto it = model.element_types.find(e.type);
  return it == model.element_types.end() ? nullptr : &element_type_descriptor(it->second);
}
bool is_plane_solid(const Model& model, const ElementRecord& e) {
  const ElementTypeDescriptor* d = descriptor_of(model, e);
  return d != nullptr && d->role == ShapeRole::Plane;
}
bool is_shell(const Model& model, const ElementRecord& e) {
  const ElementTypeDescriptor* d = descriptor_of(model, e);
  return d != nullptr && d->role == ShapeRole::Shell;
}
}  // namespace

std::vector<int> element_face_nodes(const Model& model, const ElementRecord& element, int face) {
  const ElementTypeDescriptor* d = descriptor_of(model, element);
  if (d == nullptr || face < 1 || face > static_cast<int>(d->faces.size())) return {};
  std::vector<int> out;
  for (int p : d->faces[static_cast<std::size_t>(face - 1)])
    if (p < static_cast<int>(element.nodes.size()))
      out.push_back(element.nodes[static_cast<std::size_t>(p)]);
  return out;
}

int element_face_count(const Model& model, const ElementRecord& element, bool sf_only) {
  const ElementTypeDescriptor* d = descriptor_of(model, element);
  if (d == nullptr) return 0;
  return sf_only ? d->sf_faces : static_cast<int>(d->faces.size());
}

std::vector<int> area_nodes_with_midsides(const Model& model, const std::vector<int>& corners) {
  const std::set<int> on(corners.begin(), corners.end());
  std::set<int> midsides;
  for (const auto& [id, e] : model.elements) {
    const ElementTypeDescriptor* d = descriptor_of(model, e);
    if (d == nullptr) continue;
    const CellTopology& cell = d->topology();
    if (cell.midside_nodes == 0 || static_cast<int>(e.nodes.size()) < cell.n_nodes()) continue;
    // An area element is a face of itself; a volume element's faces are in `faces`.
    for (const auto& face : cell.faces) {
      bool all = true;
      for (int p : face) all = all && on.count(e.nodes[static_cast<std::size_t>(p)]) != 0;
      if (!all) continue;
      for (std::size_t k = 0; k < face.size(); ++k) {
        const int m = cell.midside_of(face[k], face[(k + 1) % face.size()]);
        if (m >= 0 && e.nodes[static_cast<std::size_t>(m)] > 0)
          midsides.insert(e.nodes[static_cast<std::size_t>(m)]);
      }
    }
  }
  std::vector<int> out = corners;
  for (int m : midsides)
    if (on.count(m) == 0) out.push_back(m);
  return out;
}

std::vector<int> line_nodes_with_midsides(const Model& model, const std::vector<int>& chain) {
  std::set<std::pair<int, int>> edges;
  for (std::size_t k = 0; k + 1 < chain.size(); ++k)
    edges.insert(std::minmax(chain[k], chain[k + 1]));
  std::set<int> midsides;
  for (const auto& [id, e] : model.elements) {
    const ElementTypeDescriptor* d = descriptor_of(model, e);
    if (d == nullptr) continue;
    const CellTopology& cell = d->topology();
    if (cell.midside_nodes == 0 || static_cast<int>(e.nodes.size()) < cell.n_nodes()) continue;
    for (int k = 0; k < cell.midside_nodes; ++k) {
      const auto& edge = cell.edges[static_cast<std::size_t>(k)];
      const int a = e.nodes[static_cast<std::size_t>(edge[0])];
      const int b = e.nodes[static_cast<std::size_t>(edge[1])];
      if (edges.count(std::minmax(a, b)) != 0)
        midsides.insert(e.nodes[static_cast<std::size_t>(cell.corner_nodes + k)]);
    }
  }
  std::vector<int> out = chain;
  const std::set<int> on(chain.begin(), chain.end());
  for (int m : midsides)
    if (on.count(m) == 0) out.push_back(m);
  return out;
}

std::vector<FaceKey> faces_on_nodes(const Model& model, const std::function<bool(int)>& node_ok,
                                    const std::function<bool(int)>& element_ok, bool shell_edges) {
  std::map<std::set<int>, std::vector<FaceKey>> candidates;
  for (const auto& [id, e] : model.elements) {
    if (!element_ok(id)) continue;
    const int n = element_face_count(model, e, true);
    bool loaded = false;
    for (int f = 1; f <= n; ++f) {
      const std::vector<int> nodes = element_face_nodes(model, e, f);
      const std::set<int> key(nodes.begin(), nodes.end());
      // A collapsed face carries no pressure: below 3 nodes (2 on the edge faces of a 2-D solid).
      if (key.size() < (is_plane_solid(model, e) ? 2u : 3u)) continue;
      bool all = true;
      for (int node : key) all = all && node_ok(node);
      if (all) candidates[key].push_back(FaceKey{id, f});
      loaded = loaded || all;
    }
    // A shell whose surface is not selected as a whole takes the load on its edges whose nodes
    // are (MAPDL's in-plane edge pressure, faces 3.. of SHELL63/181: the Verification Manual's
    // NSEL,S,LOC,X,..; SF,ALL,PRES on a shell edge); an edge shared by two shells is not loaded.
    if (shell_edges && !loaded && is_shell(model, e)) {
      const int faces = element_face_count(model, e, false);
      for (int f = 3; f <= faces; ++f) {
        const std::vector<int> nodes = element_face_nodes(model, e, f);
        const std::set<int> key(nodes.begin(), nodes.end());
        if (key.size() < 2u) continue;  // a triangle's collapsed edge
        bool all = true;
        for (int node : key) all = all && node_ok(node);
        if (all) candidates[key].push_back(FaceKey{id, f});
      }
    }
  }
  std::vector<FaceKey> out;
  for (const auto& [key, faces] : candidates)
    if (faces.size() == 1) out.push_back(faces.front());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace impactfe::geometry
