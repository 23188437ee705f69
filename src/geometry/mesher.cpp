#include "geometry/mesher.h"

#include "core/memory_budget.h"
#include "elements/model_memory.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/log.h"
#include "elements/element_registry.h"
#include "geometry/line_geometry.h"
#include "geometry/mapped_mesh.h"
#include "geometry/spacing.h"

namespace impactfe::geometry {

namespace {

/// Largest division count of one line: beyond any node limit, still far from int overflow.
constexpr double kMaxDivisions = 1e9;

/// ceil(x) that does not round 4.0000000001 up to 5 (lengths from quadrature). A count beyond
/// kMaxDivisions (a SIZE of 1e-30, or NaN) gives kMaxDivisions, which the node limit refuses
/// (a plain cast to int would be undefined behaviour).
int ceil_divisions(double x) {
  const double n = std::ceil(x - 1e-9 * std::max(1.0, x));
  if (!(n <= kMaxDivisions)) return static_cast<int>(kMaxDivisions);
  return std::max(1, static_cast<int>(n));
}

/// Topological dimension of an element type's cell: 0 point, 1 line, 2 area, 3 volume.
int dimension(const ElementTypeDescriptor& d) {
  return d.topology().dimension;
}

const char* dimension_name(int dim) {
  static const char* names[] = {"point", "line", "area", "volume"};
  return dim >= 0 && dim <= 3 ? names[dim] : "superelement";
}

}  // namespace

Mesher::Mesher(Model& model, const MeshPointers& current, const SourceLocation& where)
    : model_(model), solid_(model.solid), current_(current), where_(where) {
  for (const auto& [id, line] : solid_.lines)
    longest_line_ = std::max(longest_line_, line_length(line));
}

void Mesher::fail(const std::string& message) const {
  throw InputError(where_, message);
}

Mesher::Attributes Mesher::resolve(const EntityAttributes& own) const {
  Attributes a;
  a.type = own.type > 0 ? own.type : current_.type;
  a.mat = own.mat > 0 ? own.mat : current_.mat;
  a.real = own.real > 0 ? own.real : current_.real;
  a.secnum = own.secnum > 0 ? own.secnum : current_.secnum;
  a.esys = own.esys > 0 ? own.esys : current_.esys;
  if (model_.element_types.count(a.type) == 0)
    fail(fmt::format("element type {} is not defined (ET before meshing)", a.type));
  return a;
}

const ElementTypeDescriptor& Mesher::descriptor(int type) const {
  return element_type_descriptor(model_.element_types.at(type));
}

void Mesher::check_new_nodes(double n, const std::string& what) const {
  // A double: the product of three division counts may exceed any integer type.
  const double total = static_cast<double>(model_.nodes.size()) + n;
  if (n > 0 && total > static_cast<double>(current_.max_nodes))
    fail(
        fmt::format("meshing {} would make {:.0f} nodes, more than the limit of {} (check "
                    "the divisions: LESIZE, ESIZE, KESIZE, DESIZE)",
                    what, total, current_.max_nodes));
  // A mesh whose model could not be solved in the memory the run may take is refused before
  // it is built (about as many elements as nodes are made). Small entities are not worth the
  // look at /proc.
  if (n >= 1000) {
    try {
      require_model_memory(model_, "meshing " + what, current_.type, n, n);
    } catch (const MemoryLimitError& e) {
      throw MemoryLimitError(where_, e.message());
    }
  }
}

int Mesher::add_node(const Vec3& x) {
  check_new_nodes(1, "this entity");
  const long long last = model_.nodes.empty() ? 0 : model_.nodes.rbegin()->first;
  if (last >= kMaxMeshNumber)
    fail(fmt::format("the next node number would be {}, beyond {}", last + 1, kMaxMeshNumber));
  const int id = std::max(solid_.numstr.node, static_cast<int>(last + 1));
  Node n;
  n.id = id;
  n.x = x;
  model_.nodes[id] = n;
  model_.selection.nodes.forget(id);
  return id;
}

int Mesher::midside_node(int a, int b) {
  if (!midside_index_) {
    // The midside nodes of the elements already in the model, by the corner pair of their
    // edge: a neighbour meshed earlier (another volume) shares its edge's node.
    midside_index_.emplace();
    for (const auto& [id, e] : model_.elements) {
      const auto t = model_.element_types.find(e.type);
      if (t == model_.element_types.end()) continue;
      const CellTopology& cell = element_type_descriptor(t->second).topology();
      for (int k = 0; k < cell.midside_nodes && cell.n_nodes() <= static_cast<int>(e.nodes.size());
           ++k) {
        const auto& edge = cell.edges[static_cast<std::size_t>(k)];
        const int p = e.nodes[static_cast<std::size_t>(edge[0])];
        const int q = e.nodes[static_cast<std::size_t>(edge[1])];
        const int m = e.nodes[static_cast<std::size_t>(cell.corner_nodes + k)];
        if (p != q && m > 0) midside_index_->emplace(std::minmax(p, q), m);
      }
    }
  }
  const auto key = std::minmax(a, b);
  const auto it = midside_index_->find(key);
  if (it != midside_index_->end()) return it->second;
  // On a meshed line: at the middle of the line between the two nodes (on an arc, not on its
  // chord). Inside the region: at mid-edge, the mapped mesh's edges being straight there.
  Vec3 x = 0.5 * (model_.nodes.at(a).x + model_.nodes.at(b).x);
  if (const auto on = line_edges_.find(key); on != line_edges_.end()) {
    const Line& line = solid_.lines.at(on->second);
    x = line_point(line, 0.5 * (line_parameter(line, model_.nodes.at(a).x) +
                                line_parameter(line, model_.nodes.at(b).x)));
  }
  const int id = add_node(x);
  midside_index_->emplace(key, id);
  created_midside_nodes_.push_back(id);
  return id;
}

void Mesher::index_line_edges(int id) {
  const auto it = solid_.lines.find(id);
  if (it == solid_.lines.end()) return;
  const std::vector<int>& nodes = it->second.nodes;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
    line_edges_.emplace(std::minmax(nodes[k], nodes[k + 1]), id);
}

int Mesher::add_element(const Attributes& attr, std::vector<int> nodes) {
  const ElementTypeDescriptor& d = descriptor(attr.type);
  const CellTopology& cell = d.topology();
  if (cell.midside_nodes > 0 && static_cast<int>(nodes.size()) <= cell.corner_nodes) {
    // A quadratic element from the corners of the mapped lattice: a midside node on each edge
    // (the edge's corner node when the edge is collapsed).
    while (static_cast<int>(nodes.size()) < cell.corner_nodes) nodes.push_back(nodes.back());
    for (const auto& edge : cell.edges) {
      const int a = nodes[static_cast<std::size_t>(edge[0])];
      const int b = nodes[static_cast<std::size_t>(edge[1])];
      nodes.push_back(a == b ? a : midside_node(a, b));
    }
  }
  while (static_cast<int>(nodes.size()) < d.n_nodes) nodes.push_back(nodes.back());
  const long long last = model_.elements.empty() ? 0 : model_.elements.rbegin()->first;
  if (last >= kMaxMeshNumber)
    fail(fmt::format("the next element number would be {}, beyond {}", last + 1, kMaxMeshNumber));
  if (model_.elements.size() >= current_.max_elements)
    fail(fmt::format("meshing would make more than the limit of {} elements",
                     current_.max_elements));
  const int id = std::max(solid_.numstr.elem, static_cast<int>(last + 1));
  ElementRecord e;
  e.id = id;
  e.type = attr.type;
  e.mat = attr.mat;
  e.real = attr.real;
  e.secnum = attr.secnum;
  e.esys = attr.esys;
  e.nodes = std::move(nodes);
  e.where = where_;
  model_.elements[id] = std::move(e);
  model_.selection.elements.forget(id);
  created_elements_.push_back(id);
  return id;
}

int Mesher::keypoint_node(int id) {
  Keypoint& k = solid_.keypoints.at(id);
  if (k.node != 0 && model_.nodes.count(k.node) != 0) return k.node;
  k.node = add_node(k.x);
  return k.node;
}

int Mesher::fixed_divisions(const Line& line) const {
  if (!line.nodes.empty()) return static_cast<int>(line.nodes.size()) - 1;
  if (line.ndiv > 0) return line.ndiv;
  if (line.size) return ceil_divisions(line_length(line) / *line.size);
  if (line.angle) {
    const double sweep = line_sweep_angle(line);
    return sweep > 0.0 ? ceil_divisions(sweep / *line.angle) : 1;
  }
  return -1;
}

int Mesher::soft_divisions(const Line& line, std::optional<double> area_size) const {
  const double length = line_length(line);
  const auto s1 = solid_.keypoints.at(line.kp1).size;
  const auto s2 = solid_.keypoints.at(line.kp2).size;
  if (s1 && s2) return ceil_divisions(2.0 * length / (*s1 + *s2));
  if (s1 || s2) return ceil_divisions(length / (s1 ? *s1 : *s2));
  const MeshControls& m = solid_.mesh;
  if (m.esize > 0.0) return ceil_divisions(length / m.esize);
  if (m.esize_ndiv > 0) return m.esize_ndiv;
  if (area_size) return ceil_divisions(length / *area_size);
  // DESIZE defaults (§4.1, M3): by length relative to the longest line, MINL..MXEL elements,
  // and at most ANGL degrees per division on arcs.
  const auto& ds = m.desize;
  int n = ceil_divisions(ds.mxel * length / std::max(longest_line_, length));
  const double sweep = line_sweep_angle(line);
  if (sweep > 0.0) n = std::max(n, ceil_divisions(sweep / ds.angl));
  return std::clamp(n, ds.minl, std::max(ds.minl, ds.mxel));
}

int Mesher::line_divisions(int id) const {
  const Line& line = solid_.lines.at(id);
  const int fixed = fixed_divisions(line);
  return fixed > 0 ? fixed : soft_divisions(line, std::nullopt);
}

void Mesher::plan_divisions(const std::vector<std::vector<int>>& classes, const std::string& what,
                            std::optional<double> area_size) {
  for (const auto& group : classes) {
    int fixed = -1, fixed_line = 0, soft = 1;
    for (int id : group) {
      const Line& line = solid_.lines.at(id);
      const auto planned = planned_.find(id);
      const int f = planned != planned_.end() ? planned->second : fixed_divisions(line);
      if (f > 0) {
        if (fixed > 0 && f != fixed)
          fail(
              fmt::format("{} is not mappable: lines {} and {} must have the same number of "
                          "divisions, they have {} and {} (check LESIZE/ESIZE or mesh them "
                          "alike)",
                          what, fixed_line, id, fixed, f));
        fixed = f;
        fixed_line = id;
      } else {
        soft = std::max(soft, soft_divisions(line, area_size));
      }
    }
    const int n = fixed > 0 ? fixed : soft;
    for (int id : group)
      if (solid_.lines.at(id).nodes.empty()) planned_[id] = n;
  }
}

void Mesher::line_nodes(int id, std::optional<double> area_size,
                        std::map<std::pair<int, int>, int>* midsides) {
  Line& line = solid_.lines.at(id);
  if (!line.nodes.empty()) return;
  const auto planned = planned_.find(id);
  int n = planned != planned_.end() ? planned->second : fixed_divisions(line);
  if (n <= 0) n = soft_divisions(line, area_size);
  check_new_nodes(midsides != nullptr ? 2.0 * n - 1.0 : n - 1.0,
                  fmt::format("line {} into {} divisions", id, n));
  double space = line.space;
  const bool line_sized = line.ndiv > 0 || line.size || line.angle;
  const auto s1 = solid_.keypoints.at(line.kp1).size;
  const auto s2 = solid_.keypoints.at(line.kp2).size;
  if (!line_sized && s1 && s2) space = *s2 / *s1;  // KESIZE graded between the two ends
  const std::vector<double> f = division_fractions(n, space);
  const int a = keypoint_node(line.kp1);
  const int b = keypoint_node(line.kp2);
  std::vector<int> nodes{a};
  std::vector<int> middle;  // midside node of division k (with `midsides`)
  for (int k = 1; k <= n; ++k) {
    if (midsides != nullptr)
      middle.push_back(add_node(line_point(
          line, 0.5 * (f[static_cast<std::size_t>(k - 1)] + f[static_cast<std::size_t>(k)]))));
    if (k < n) nodes.push_back(add_node(line_point(line, f[static_cast<std::size_t>(k)])));
  }
  nodes.push_back(b);
  if (midsides != nullptr)
    for (int k = 0; k < n; ++k) {
      const auto key =
          std::minmax(nodes[static_cast<std::size_t>(k)], nodes[static_cast<std::size_t>(k + 1)]);
      (*midsides)[key] = middle[static_cast<std::size_t>(k)];
      if (midside_index_) midside_index_->emplace(key, middle[static_cast<std::size_t>(k)]);
    }
  solid_.lines.at(id).nodes = std::move(nodes);
}

int Mesher::line_joining(const std::vector<int>& lines, int a, int b) const {
  for (int id : lines) {
    const Line& l = solid_.lines.at(std::abs(id));
    if (l.kp1 == a && l.kp2 == b) return std::abs(id);
    if (l.kp1 == b && l.kp2 == a) return -std::abs(id);
  }
  return 0;
}

void Mesher::area_nodes(int id, bool triangles) {
  Area& area = solid_.areas.at(id);
  if (!area.grid.empty()) return;
  const std::size_t sides = area.lines.size();
  std::vector<int> lines;
  for (int sl : area.lines) lines.push_back(std::abs(sl));
  const std::string what = fmt::format("area {}", id);
  if (sides == 4) {
    plan_divisions({{lines[0], lines[2]}, {lines[1], lines[3]}}, what, area.size);
  } else if (sides == 3) {
    if (!triangles)
      fail(
          fmt::format("area {} has 3 sides: mapped quadrilaterals need 4 (MSHAPE,1,2D meshes it "
                      "with triangles)",
                      id));
    plan_divisions({lines}, what, area.size);
  } else {
    fail(
        fmt::format("area {} has {} sides: mapped meshing needs 3 or 4 (MSHKEY,0 meshes it "
                    "free, or divide it into 3- or 4-sided areas)",
                    id, sides));
  }
  // Nodes line by line in ascending line number, each line's end keypoints first (line_nodes),
  // as MAPDL numbers them: vm42's A,1,3,4,2 puts node 2 at keypoint 3, the far end of line 1.
  std::vector<int> sorted_lines = lines;
  std::sort(sorted_lines.begin(), sorted_lines.end());
  for (int l : sorted_lines) line_nodes(l, area.size);

  // Node chains of the sides in loop direction.
  std::vector<std::vector<int>> chain;
  for (int sl : area.lines) {
    std::vector<int> c = solid_.lines.at(std::abs(sl)).nodes;
    if (sl < 0) std::reverse(c.begin(), c.end());
    chain.push_back(std::move(c));
  }
  auto positions = [&](const std::vector<int>& ids) {
    std::vector<Vec3> p;
    for (int n : ids) p.push_back(model_.nodes.at(n).x);
    return p;
  };
  AreaGrid grid;
  std::vector<int> interior;
  if (sides == 4) {
    const int n1 = static_cast<int>(chain[0].size()) - 1;
    const int n2 = static_cast<int>(chain[1].size()) - 1;
    if (static_cast<int>(chain[2].size()) != n1 + 1 || static_cast<int>(chain[3].size()) != n2 + 1)
      fail(
          fmt::format("area {} is not mappable: opposite lines have different divisions ({}/{} "
                      "and {}/{})",
                      id, n1, chain[2].size() - 1, n2, chain[3].size() - 1));
    check_new_nodes((n1 - 1.0) * (n2 - 1.0),
                    fmt::format("area {} ({} x {} divisions)", id, n1, n2));
    std::vector<int> top(chain[2].rbegin(), chain[2].rend());
    std::vector<int> left(chain[3].rbegin(), chain[3].rend());
    const auto xyz =
        coons_quad(positions(chain[0]), positions(chain[1]), positions(top), positions(left));
    grid.n1 = n1;
    grid.n2 = n2;
    grid.nodes.assign(static_cast<std::size_t>((n1 + 1) * (n2 + 1)), 0);
    for (int j = 0; j <= n2; ++j)
      for (int i = 0; i <= n1; ++i) {
        const std::size_t g = static_cast<std::size_t>(i + j * (n1 + 1));
        if (j == 0)
          grid.nodes[g] = chain[0][static_cast<std::size_t>(i)];
        else if (j == n2)
          grid.nodes[g] = top[static_cast<std::size_t>(i)];
        else if (i == 0)
          grid.nodes[g] = left[static_cast<std::size_t>(j)];
        else if (i == n1)
          grid.nodes[g] = chain[1][static_cast<std::size_t>(j)];
        else
          interior.push_back(grid.nodes[g] = add_node(xyz[g]));
      }
  } else {
    const int n = static_cast<int>(chain[0].size()) - 1;
    check_new_nodes((n - 1.0) * (n - 2.0) / 2, fmt::format("area {} ({} divisions)", id, n));
    const auto xyz =
        triangle_lattice(positions(chain[0]), positions(chain[1]), positions(chain[2]));
    grid.n1 = grid.n2 = n;
    grid.triangular = true;
    std::size_t g = 0;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n - j; ++i, ++g) {
        int node = 0;
        if (j == 0)
          node = chain[0][static_cast<std::size_t>(i)];
        else if (i == 0)
          node = chain[2][static_cast<std::size_t>(n - j)];
        else if (i + j == n)
          node = chain[1][static_cast<std::size_t>(j)];
        else
          interior.push_back(node = add_node(xyz[g]));
        grid.nodes.push_back(node);
      }
  }
  Area& stored = solid_.areas.at(id);
  stored.grid = std::move(grid);
  stored.interior_nodes = std::move(interior);
}

void Mesher::mesh_keypoint(int id) {
  Keypoint& k = solid_.keypoints.at(id);
  const Attributes attr = resolve(k.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  if (dimension(d) != 0)
    fail(fmt::format("element type {} ({}) is a {} element: KMESH needs a point element (MASS21)",
                     attr.type, d.name, dimension_name(dimension(d))));
  if (!k.elements.empty()) {
    Log::info("{}:{}: {}: keypoint {} is already meshed", where_.file, where_.line, where_.command,
              id);
    return;
  }
  const int node = keypoint_node(id);
  const int e = add_element(attr, {node});
  solid_.keypoints.at(id).elements.push_back(e);
}

void Mesher::mesh_line(int id) {
  Line& line = solid_.lines.at(id);
  const Attributes attr = resolve(line.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  if (dimension(d) != 1)
    fail(
        fmt::format("element type {} ({}) is a {} element: LMESH needs a line element (LINK, "
                    "BEAM, COMBIN)",
                    attr.type, d.name, dimension_name(dimension(d))));
  if (!line.elements.empty()) {
    Log::info("{}:{}: {}: line {} is already meshed", where_.file, where_.line, where_.command, id);
    return;
  }
  const bool quadratic = d.topology().midside_nodes > 0;
  std::map<std::pair<int, int>, int> midsides;
  line_nodes(id, std::nullopt, quadratic && line.nodes.empty() ? &midsides : nullptr);
  const Line& l = solid_.lines.at(id);
  std::vector<int> elements;
  const int n = static_cast<int>(l.nodes.size()) - 1;
  const bool orient = d.n_optional_nodes > 0 && l.orientation_kb > 0;
  Vec3 v1 = Vec3::Zero(), v2 = Vec3::Zero();
  if (orient) {
    // LATT KB (, KE): orientation vector KP1 → KB at the start, KP2 → KE at the end (§4.4).
    const Vec3 x1 = solid_.keypoints.at(l.kp1).x, x2 = solid_.keypoints.at(l.kp2).x;
    v1 = solid_.keypoints.at(l.orientation_kb).x - x1;
    v2 = l.orientation_ke > 0 ? Vec3(solid_.keypoints.at(l.orientation_ke).x - x2) : v1;
  }
  // A quadratic line element (BEAM189) gets its midside node on the line (on an arc, not on
  // its chord) before the orientation node.
  if (quadratic) index_line_edges(id);
  for (int k = 0; k < n; ++k) {
    std::vector<int> nodes{l.nodes[static_cast<std::size_t>(k)],
                           l.nodes[static_cast<std::size_t>(k + 1)]};
    if (quadratic) {
      const auto made = midsides.find(std::minmax(nodes[0], nodes[1]));
      nodes.push_back(made != midsides.end() ? made->second : midside_node(nodes[0], nodes[1]));
    }
    if (orient) {
      const double s = (k + 0.5) / n;
      const Vec3 mid = 0.5 * (model_.nodes.at(nodes[0]).x + model_.nodes.at(nodes[1]).x);
      nodes.push_back(add_node(mid + (1.0 - s) * v1 + s * v2));
    }
    elements.push_back(add_element(attr, nodes));
  }
  // The midside nodes belong to the line's elements (clear_line deletes them with them).
  (void)take_created_midside_nodes();
  solid_.lines.at(id).elements = std::move(elements);
}

void Mesher::mesh_area(int id) {
  Area& area = solid_.areas.at(id);
  const Attributes attr = resolve(area.attr);
  const ElementTypeDescriptor& d = descriptor(attr.type);
  if (dimension(d) != 2)
    fail(
        fmt::format("element type {} ({}) is a {} element: AMESH needs an area element "
                    "(SHELL, PLANE; set TYPE or AATT)",
                    attr.type, d.name, dimension_name(dimension(d))));
  if (!area.elements.empty()) {
    Log::info("{}:{}: {}: area {} is already meshed", where_.file, where_.line, where_.command, id);
    return;
  }
  MeshControls& m = solid_.mesh;
  const bool triangles = m.shape_2d == 1;
  if (triangles && d.least_nodes() > 3 && d.topology().midside_nodes == 0)
    fail(fmt::format("element type {} ({}) has no triangular form (MSHAPE,1)", attr.type, d.name));
  if (area_needs_free_mesh(id)) {
    mesh_area_free(id);
    return;
  }
  if (m.key == 0 && !m.free_warning_given) {
    Log::warn(
        "{}:{}: {}: MSHKEY,0 (free meshing): impactfe meshes 3- and 4-sided regions with "
        "the mapped mesher; MAPDL's free mesher may produce a different mesh",
        where_.file, where_.line, where_.command);
    m.free_warning_given = true;
  }
  area_nodes(id, triangles);
  if (d.topology().midside_nodes > 0)
    for (int line : solid_.areas.at(id).lines) index_line_edges(std::abs(line));
  const AreaGrid& g = solid_.areas.at(id).grid;
  std::vector<int> elements;
  if (!g.triangular) {
    for (int j = 0; j < g.n2; ++j)
      for (int i = 0; i < g.n1; ++i) {
        const int a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), e = g.at(i, j + 1);
        if (triangles) {
          elements.push_back(add_element(attr, {a, b, c}));
          elements.push_back(add_element(attr, {a, c, e}));
        } else {
          elements.push_back(add_element(attr, {a, b, c, e}));
        }
      }
  } else {
    const int n = g.n1;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n - j; ++i) {
        elements.push_back(add_element(attr, {g.at(i, j), g.at(i + 1, j), g.at(i, j + 1)}));
        if (i < n - j - 1)
          elements.push_back(
              add_element(attr, {g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1)}));
      }
  }
  Area& meshed = solid_.areas.at(id);
  meshed.elements = std::move(elements);
  for (int n : take_created_midside_nodes()) meshed.interior_nodes.push_back(n);
}

// ---- clearing ----------------------------------------------------------------------------------

void Mesher::delete_elements(std::vector<int>& elements) {
  for (int e : elements) {
    model_.elements.erase(e);
    model_.selection.elements.forget(e);
  }
  elements.clear();
}

void Mesher::delete_nodes(std::vector<int> nodes) {
  std::set<int> used;
  for (const auto& [id, e] : model_.elements) used.insert(e.nodes.begin(), e.nodes.end());
  for (int n : nodes) {
    if (used.count(n) != 0) continue;
    model_.nodes.erase(n);
    model_.selection.nodes.forget(n);
  }
}

bool Mesher::keypoint_needed(int kp) const {
  if (!solid_.keypoints.at(kp).elements.empty()) return true;
  for (const auto& [id, l] : solid_.lines)
    if ((l.kp1 == kp || l.kp2 == kp) && !l.nodes.empty()) return true;
  return false;
}

bool Mesher::line_needed(int line) const {
  if (!solid_.lines.at(line).elements.empty()) return true;
  for (const auto& [id, a] : solid_.areas) {
    if (a.grid.empty()) continue;
    for (int sl : a.lines)
      if (std::abs(sl) == line) return true;
  }
  return false;
}

bool Mesher::area_needed(int area) const {
  if (!solid_.areas.at(area).elements.empty()) return true;
  for (const auto& [id, v] : solid_.volumes)
    if (!v.elements.empty() && std::find(v.areas.begin(), v.areas.end(), area) != v.areas.end())
      return true;
  return false;
}

void Mesher::release_keypoint(int id) {
  Keypoint& k = solid_.keypoints.at(id);
  if (k.node == 0) return;
  delete_nodes({k.node});
  if (model_.nodes.count(k.node) == 0) k.node = 0;
}

void Mesher::release_line(int id) {
  Line& l = solid_.lines.at(id);
  if (l.nodes.empty()) return;
  delete_nodes(std::vector<int>(l.nodes.begin() + 1, l.nodes.end() - 1));
  l.nodes.clear();
  for (int k : {l.kp1, l.kp2})
    if (!keypoint_needed(k)) release_keypoint(k);
}

void Mesher::release_area(int id) {
  Area& a = solid_.areas.at(id);
  if (a.grid.empty()) return;
  delete_nodes(a.interior_nodes);
  a.interior_nodes.clear();
  a.grid = AreaGrid{};
  for (int sl : a.lines)
    if (!line_needed(std::abs(sl))) release_line(std::abs(sl));
}

void Mesher::clear_keypoint(int id) {
  delete_elements(solid_.keypoints.at(id).elements);
  if (!keypoint_needed(id)) release_keypoint(id);
}

void Mesher::clear_line(int id) {
  Line& l = solid_.lines.at(id);
  // Orientation nodes of beam elements belong to the line's elements.
  std::vector<int> orientation;
  for (int e : l.elements) {
    const auto& nodes = model_.elements.at(e).nodes;
    if (nodes.size() > 2) orientation.insert(orientation.end(), nodes.begin() + 2, nodes.end());
  }
  delete_elements(l.elements);
  delete_nodes(orientation);
  if (!line_needed(id)) release_line(id);
}

void Mesher::clear_area(int id) {
  delete_elements(solid_.areas.at(id).elements);
  if (!area_needed(id)) release_area(id);
}

void Mesher::clear_volume(int id) {
  Volume& v = solid_.volumes.at(id);
  delete_elements(v.elements);
  delete_nodes(v.interior_nodes);
  v.interior_nodes.clear();
  for (int a : v.areas)
    if (!area_needed(a)) release_area(a);
}

}  // namespace impactfe::geometry
