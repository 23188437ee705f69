#pragma once
/// Element faces for surface loads (APDL_MODELING §5.1, §5.2): the faces an element type
/// registers (elements/element_registry.h) applied to element records.
#include <functional>
#include <vector>

#include "core/model.h"

namespace impactfe::geometry {

/// Node numbers of face `face` (1-based) of `element`, in face-node order; empty when its type
/// has no such face.
std::vector<int> element_face_nodes(const Model& model, const ElementRecord& element, int face);
/// Number of faces of the element's type (`sf_only`: those SF may load by nodes).
int element_face_count(const Model& model, const ElementRecord& element, bool sf_only);

/// The nodes of an area's mesh with the midside nodes of quadratic elements on it: `corners`
/// (the area's corner nodes, AreaGrid::nodes) and the midside node of each side of an element
/// face whose corners all lie in `corners`.
std::vector<int> area_nodes_with_midsides(const Model& model, const std::vector<int>& corners);
/// The nodes of a line's mesh (`chain`, in order) with the midside nodes of quadratic elements
/// on the edges between consecutive nodes.
std::vector<int> line_nodes_with_midsides(const Model& model, const std::vector<int>& chain);

/// The SF face rule: faces (of elements passing `element_ok`, among the first sf_faces faces of
/// each type) whose nodes all pass `node_ok`, except faces shared by two such elements. With
/// `shell_edges` (SF pressures), a shell none of whose SF faces qualifies offers its edge faces
/// (3..) instead, MAPDL's in-plane edge pressure.
std::vector<FaceKey> faces_on_nodes(const Model& model, const std::function<bool(int)>& node_ok,
                                    const std::function<bool(int)>& element_ok,
                                    bool shell_edges = false);

}  // namespace impactfe::geometry
