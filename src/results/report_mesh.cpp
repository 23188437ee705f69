// Mesh of the report's 3-D view: surface triangles, lines, points and the model's parts.
#include "results/report_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <numeric>

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

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// Unique nodes of a face in order (a degenerate brick repeats nodes).
std::vector<int> unique_in_order(const std::vector<int>& face) {
  std::vector<int> out;
  for (int n : face)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

}  // namespace

bool is_gap_type(const std::string& type_name) {
  return type_name == "COMBIN40";
}

ReportMesh build_report_mesh(const ResultsReader& reader) {
  ReportMesh mesh;
  const auto& ids = reader.node_ids();
  auto index_of = [&](int node) { return node_row(ids, node); };
  // Brick faces (ANSYS SOLID45 node order I J K L M N O P), outward for the positive volume.
  static const std::array<std::array<int, 4>, 6> kBrickFaces = {
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
  struct Face {
    std::vector<int> nodes;
    std::size_t element;
  };
  std::map<std::vector<int>, std::vector<Face>> brick_faces;  // sorted nodes -> faces
  std::vector<Face> faces;
  std::vector<char> used(ids.size(), 0);
  Components parts(ids.size());

  const auto& elements = reader.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto& el = elements[e];
    mesh.element_index[el.id] = e;
    mesh.element_ids.push_back(el.id);
    std::vector<int> nodes;
    for (int n : el.nodes)
      if (int i = index_of(n); i >= 0) nodes.push_back(i);
    if (nodes.size() != el.nodes.size() || nodes.empty()) continue;  // node not in the file
    for (int i : nodes) used[static_cast<std::size_t>(i)] = 1;
    const bool gap = is_gap_type(el.type_name);
    if (gap) mesh.gap_nodes.insert(nodes.begin(), nodes.end());
    if (!gap)
      for (std::size_t k = 1; k < nodes.size(); ++k) parts.join(nodes[0], nodes[k]);
    if (starts_with(el.type_name, "MATRIX") || nodes.size() > 8) {
      for (int i : nodes) {
        mesh.points.push_back(i);
        mesh.point_element.push_back(static_cast<int>(e));
      }
    } else if (nodes.size() == 8) {
      for (const auto& f : kBrickFaces) {
        Face face{{nodes[f[0]], nodes[f[1]], nodes[f[2]], nodes[f[3]]}, e};
        face.nodes = unique_in_order(face.nodes);
        if (face.nodes.size() < 3) continue;
        std::vector<int> key = face.nodes;
        std::sort(key.begin(), key.end());
        brick_faces[key].push_back(face);
      }
    } else if (nodes.size() == 3 || nodes.size() == 4) {
      faces.push_back({unique_in_order(nodes), e});
    } else if (nodes.size() == 2) {
      if (nodes[0] == nodes[1]) continue;
      mesh.lines.insert(mesh.lines.end(), {nodes[0], nodes[1]});
      mesh.line_element.push_back(static_cast<int>(e));
    } else {  // 1-node elements (MASS21) and anything else: points
      for (int i : nodes) {
        mesh.points.push_back(i);
        mesh.point_element.push_back(static_cast<int>(e));
      }
    }
  }
  for (const auto& [key, list] : brick_faces)
    if (list.size() == 1) faces.push_back(list.front());  // outer faces only
  std::set<std::pair<int, int>> edges;
  for (const auto& f : faces) {
    for (std::size_t k = 0; k < f.nodes.size() && f.nodes.size() >= 3; ++k) {
      const int a = f.nodes[k], b = f.nodes[(k + 1) % f.nodes.size()];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
    if (f.nodes.size() < 3) {
      if (f.nodes.size() == 2) {
        mesh.lines.insert(mesh.lines.end(), {f.nodes[0], f.nodes[1]});
        mesh.line_element.push_back(static_cast<int>(f.element));
      }
      continue;
    }
    for (std::size_t k = 1; k + 1 < f.nodes.size(); ++k) {  // fan: quads split into two
      mesh.triangles.insert(mesh.triangles.end(), {f.nodes[0], f.nodes[k], f.nodes[k + 1]});
      mesh.triangle_element.push_back(static_cast<int>(f.element));
    }
  }

  for (const auto& [a, b] : edges) mesh.edges.insert(mesh.edges.end(), {a, b});

  // Parts: nodes joined by non-gap elements, named after their most common element type.
  std::map<int, std::vector<int>> by_root;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (used[i]) {
      mesh.used_nodes.push_back(static_cast<int>(i));
      by_root[parts.root(static_cast<int>(i))].push_back(static_cast<int>(i));
    }
  std::map<int, std::map<std::string, int>> types;  // root -> type name -> count
  for (const auto& el : elements) {
    if (is_gap_type(el.type_name) || el.nodes.empty()) continue;
    if (int i = index_of(el.nodes[0]); i >= 0) ++types[parts.root(i)][el.type_name];
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
    std::string type;
    int best = 0;
    for (const auto& [name, count] : types[parts.root(nodes.front())])
      if (count > best) {
        best = count;
        type = name;
      }
    mesh.bodies.push_back({type, nodes});
    ++name_count[type];
  }
  std::map<std::string, int> seen;
  for (auto& b : mesh.bodies) {
    const int k = ++seen[b.name];
    b.name = name_count[b.name] > 1 ? fmt::format("the {} part {}", b.name, k)
                                    : fmt::format("the {} part", b.name);
  }
  if (single.size() == 1)
    mesh.bodies.push_back(
        {fmt::format("node {}", ids[static_cast<std::size_t>(single[0])]), single});
  else if (!single.empty())
    mesh.bodies.push_back({"the single nodes", single});
  return mesh;
}

}  // namespace impactfe
