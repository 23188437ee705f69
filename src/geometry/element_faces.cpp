#include "geometry/element_faces.h"

#include <algorithm>
#include <map>
#include <set>

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

std::vector<FaceKey> faces_on_nodes(const Model& model, const std::function<bool(int)>& node_ok,
                                    const std::function<bool(int)>& element_ok) {
  std::map<std::set<int>, std::vector<FaceKey>> candidates;
  for (const auto& [id, e] : model.elements) {
    if (!element_ok(id)) continue;
    const int n = element_face_count(model, e, true);
    for (int f = 1; f <= n; ++f) {
      const std::vector<int> nodes = element_face_nodes(model, e, f);
      const std::set<int> key(nodes.begin(), nodes.end());
      // A collapsed face carries no pressure: below 3 nodes (2 on the edge faces of a 2-D solid).
      if (key.size() < (is_plane_solid(model, e) ? 2u : 3u)) continue;
      bool all = true;
      for (int node : key) all = all && node_ok(node);
      if (all) candidates[key].push_back(FaceKey{id, f});
    }
  }
  std::vector<FaceKey> out;
  for (const auto& [key, faces] : candidates)
    if (faces.size() == 1) out.push_back(faces.front());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace impactfe::geometry
