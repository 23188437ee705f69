// Mesh of the report's 3-D view: surface triangles, lines, points and the model's parts.
#include "results/report_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "elements/element_registry.h"

namespace impactfe {

namespace {

/// Union-find over node indices (the parts of the model).
struct Components {
  std::vector<int> parent;
  explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(root(a))] = root(b); }
};

const ElementTypeDescriptor* type_of(const std::string& type_name) {
  return find_element_type(type_name);
}

/// The cell an element is drawn as: its type's (a poly-vertex, i.e. points, when the type is
/// not known to this program).
VtkCell drawn_cell(const ElementTypeDescriptor* type) {
  return type != nullptr ? type->vtk_cell : VtkCell::PolyVertex;
}

/// A drawn polygon and the element (index) it belongs to.
struct Face {
  std::vector<int> nodes;
  std::size_t element;
};

/// Triangles (a fan over each polygon) and the edges of the polygons.
void add_surfaces(const std::vector<Face>& faces, ReportMesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (const auto& f : faces) {
    for (std::size_t k = 0; k < f.nodes.size(); ++k) {
      const int a = f.nodes[k], b = f.nodes[(k + 1) % f.nodes.size()];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
    for (std::size_t k = 1; k + 1 < f.nodes.size(); ++k) {  // fan: quads split into two
      mesh.triangles.insert(mesh.triangles.end(), {f.nodes[0], f.nodes[k], f.nodes[k + 1]});
      mesh.triangle_element.push_back(static_cast<int>(f.element));
    }
  }
  for (const auto& [a, b] : edges) mesh.edges.insert(mesh.edges.end(), {a, b});
}

/// True for the roles drawn as overlays or not at all (contact and target elements lie on or
/// beside the structure: they neither name a part nor set the view's extent).
bool is_contact_role(const ElementTypeDescriptor* type) {
  return type != nullptr && (type->role == ShapeRole::Contact || type->role == ShapeRole::Target);
}

/// A part's name: its most common structural element type with its ET number, material and
/// real set, as the Python reader names parts ("SHELL181 type 1 mat 1 real 2"); for nodes
/// joined only by target elements, "rigid target (TARGE170)".
std::string part_label(const std::map<std::string, int>& structural,
                       const std::map<std::string, int>& other) {
  const auto& counts = structural.empty() ? other : structural;
  std::string best;
  int most = 0;
  for (const auto& [name, count] : counts)
    if (count > most) {
      most = count;
      best = name;
    }
  return structural.empty() && !best.empty() ? "rigid target (" + best + ")" : best;
}

/// Parts: nodes joined by non-gap elements, named after their most common structural element
/// type, material and real set; the nodes joined to no other form one group.
void add_bodies(const ResultsReader& reader, const std::vector<char>& used, Components& parts,
                ReportMesh& mesh) {
  const auto& ids = reader.node_ids();
  std::map<int, std::vector<int>> by_root;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (used[i]) {
      mesh.used_nodes.push_back(static_cast<int>(i));
      by_root[parts.root(static_cast<int>(i))].push_back(static_cast<int>(i));
    }
  // root -> "TYPE, MAT m, REAL r" -> count (structural elements), and TYPE -> count (others)
  std::map<int, std::map<std::string, int>> types, other_types;
  for (const auto& el : reader.elements()) {
    if (is_gap_type(el.type_name) || el.nodes.empty()) continue;
    const int i = node_row(ids, el.nodes[0]);
    if (i < 0) continue;
    if (is_contact_role(type_of(el.type_name)))
      ++other_types[parts.root(i)][el.type_name];
    else
      ++types[parts.root(i)]
             [fmt::format("{} type {} mat {} real {}", el.type_name, el.type, el.mat, el.real)];
  }
  // Nodes not joined to any other (held by gaps only, lone masses, superelement masters whose
  // superelement is not in the file) form one group, not one part each.
  std::vector<std::vector<int>> groups;
  std::vector<int> single;
  for (auto& [root, nodes] : by_root) {
    if (nodes.size() == 1)
      single.push_back(nodes.front());
    else
      groups.push_back(nodes);
  }
  std::sort(groups.begin(), groups.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
  std::map<std::string, int> name_count;
  for (const auto& nodes : groups) {
    const int root = parts.root(nodes.front());
    const std::string type = part_label(types[root], other_types[root]);
    mesh.bodies.push_back({type, nodes});
    ++name_count[type];
  }
  std::map<std::string, int> seen;
  for (auto& b : mesh.bodies) {
    const int k = ++seen[b.name];
    const bool target = b.name.rfind("rigid target", 0) == 0;
    const std::string number = name_count[b.name] > 1 ? fmt::format(" {}", k) : "";
    b.name = target ? fmt::format("the {}{}", b.name, number)
                    : fmt::format("the {} part{}", b.name, number);
  }
  if (single.size() == 1)
    mesh.bodies.push_back(
        {fmt::format("node {}", ids[static_cast<std::size_t>(single[0])]), single});
  else if (!single.empty())
    mesh.bodies.push_back({"the single nodes", single});
}

/// The polygons of a target element as overlay triangles (a fan over each).
void add_overlay(VtkCell cell, const std::vector<int>& nodes, std::size_t element,
                 ReportMesh& mesh) {
  for (const auto& piece : cell_pieces(cell, nodes)) {
    if (piece.kind != CellPiece::Kind::Polygon) continue;  // a pilot node is not drawn
    for (std::size_t k = 1; k + 1 < piece.nodes.size(); ++k) {
      mesh.overlay_triangles.insert(mesh.overlay_triangles.end(),
                                    {piece.nodes[0], piece.nodes[k], piece.nodes[k + 1]});
      mesh.overlay_element.push_back(static_cast<int>(element));
    }
  }
}

}  // namespace

bool is_gap_type(const std::string& type_name) {
  const ElementTypeDescriptor* d = type_of(type_name);
  return d != nullptr && d->role == ShapeRole::Gap;
}

ReportMesh build_report_mesh(const ResultsReader& reader) {
  ReportMesh mesh;
  const auto& ids = reader.node_ids();
  // Faces of volume cells by their sorted nodes: a face two of them share is inside.
  std::map<std::vector<int>, std::vector<Face>> volume_faces;
  std::vector<Face> faces;
  std::vector<char> used(ids.size(), 0), framed(ids.size(), 0);
  Components parts(ids.size());
  const auto& elements = reader.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto& el = elements[e];
    mesh.element_index[el.id] = e;
    mesh.element_ids.push_back(el.id);
    std::vector<int> nodes;
    for (int n : el.nodes)
      if (int i = node_row(ids, n); i >= 0) nodes.push_back(i);
    if (nodes.size() != el.nodes.size() || nodes.empty()) continue;  // node not in the file
    for (int i : nodes) used[static_cast<std::size_t>(i)] = 1;
    const ElementTypeDescriptor* type = type_of(el.type_name);
    const bool gap = type != nullptr && type->role == ShapeRole::Gap;
    if (gap) mesh.gap_nodes.insert(nodes.begin(), nodes.end());
    if (!gap)
      for (std::size_t k = 1; k < nodes.size(); ++k) parts.join(nodes[0], nodes[k]);
    const VtkCell cell = drawn_cell(type);
    if (is_contact_role(type)) {
      // Contact faces lie on the structure's own faces: not drawn, they would hide its colours.
      // Target facets are drawn as a see-through overlay; neither sets the view's extent.
      if (type->role == ShapeRole::Target) add_overlay(cell, nodes, e, mesh);
      continue;
    }
    for (int i : nodes) framed[static_cast<std::size_t>(i)] = 1;
    const bool volume = cell_topology(cell).dimension == 3;
    for (auto& piece : cell_pieces(cell, nodes)) {
      switch (piece.kind) {
        case CellPiece::Kind::Polygon:
          if (volume) {
            std::vector<int> key = piece.nodes;
            std::sort(key.begin(), key.end());
            volume_faces[key].push_back({std::move(piece.nodes), e});
          } else {
            faces.push_back({std::move(piece.nodes), e});
          }
          break;
        case CellPiece::Kind::Line:
          mesh.lines.insert(mesh.lines.end(), {piece.nodes[0], piece.nodes[1]});
          mesh.line_element.push_back(static_cast<int>(e));
          break;
        case CellPiece::Kind::Point:
          mesh.points.push_back(piece.nodes[0]);
          mesh.point_element.push_back(static_cast<int>(e));
          break;
      }
    }
  }
  for (const auto& [key, list] : volume_faces)
    if (list.size() == 1) faces.push_back(list.front());  // outer faces only
  add_surfaces(faces, mesh);
  add_bodies(reader, used, parts, mesh);
  for (std::size_t i = 0; i < framed.size(); ++i)
    if (framed[i]) mesh.framed_nodes.push_back(static_cast<int>(i));
  return mesh;
}

}  // namespace impactfe
