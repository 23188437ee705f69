/// TARGE170 target facets and pilot nodes, the shared target surface with its bucket grid, and
/// the contact point against a rigid target (elements/target_surface.h).
#include "elements/target_surface.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "elements/element_build_cache.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_element.h"
#include "elements/target_line.h"

namespace impactfe {

TargetSurface::TargetSurface(int pilot, std::vector<Triangle> triangles, bool rotates)
    : pilot_(pilot), rotates_(rotates), triangles_(std::move(triangles)) {
  // Bucket size: the mean facet extent, but at least a quarter of the largest one, so that a
  // facet covers at most 5³ buckets.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
  double mean = 0.0, largest = 0.0;
  for (const Triangle& t : triangles_) {
    const Vec3 tlo = t.a.cwiseMin(t.b).cwiseMin(t.c), thi = t.a.cwiseMax(t.b).cwiseMax(t.c);
    lo = lo.cwiseMin(tlo);
    hi = hi.cwiseMax(thi);
    const double extent = (thi - tlo).maxCoeff();
    mean += extent;
    largest = std::max(largest, extent);
  }
  mean /= static_cast<double>(std::max<std::size_t>(triangles_.size(), 1));
  cell_ = std::max({mean, 0.25 * largest, 1e-12 * std::max(1.0, (hi - lo).norm())});
  origin_ = lo;
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const Triangle& t = triangles_[f];
    Eigen::Vector3i a, b;
    cell_range(t.a.cwiseMin(t.b).cwiseMin(t.c), t.a.cwiseMax(t.b).cwiseMax(t.c), a, b);
    for (int i = a(0); i <= b(0); ++i)
      for (int j = a(1); j <= b(1); ++j)
        for (int k = a(2); k <= b(2); ++k) buckets_[key(i, j, k)].push_back(static_cast<int>(f));
  }
}

long long TargetSurface::key(long long i, long long j, long long k) const {
  constexpr long long off = 1 << 20;
  return ((i + off) << 42) | ((j + off) << 21) | (k + off);
}

void TargetSurface::cell_range(const Vec3& lo, const Vec3& hi, Eigen::Vector3i& a,
                               Eigen::Vector3i& b) const {
  // Clamped to ±2^20 buckets around the surface: farther points find nothing anyway.
  constexpr double limit = 1 << 20;
  for (int d = 0; d < 3; ++d) {
    a(d) = static_cast<int>(std::clamp(std::floor((lo(d) - origin_(d)) / cell_), -limit, limit));
    b(d) = static_cast<int>(std::clamp(std::floor((hi(d) - origin_(d)) / cell_), -limit, limit));
  }
}

std::optional<TargetSurface::Hit> TargetSurface::closest(const Vec3& y, double reach) const {
  Eigen::Vector3i a, b;
  cell_range(y - Vec3::Constant(reach), y + Vec3::Constant(reach), a, b);
  const Eigen::Vector3i span = b - a + Eigen::Vector3i::Ones();
  const double n_cells = static_cast<double>(span(0)) * span(1) * span(2);
  std::optional<Hit> best;
  const auto test = [&](const Triangle& t) {
    const double gap = (y - t.a).dot(t.normal);
    if (std::abs(gap) > reach || (best && std::abs(gap) >= std::abs(best->gap))) return;
    // Barycentric coordinates of the projection (Ericson, Real-Time Collision Detection §3.4).
    const Vec3 p = y - gap * t.normal;
    const Vec3 v0 = t.b - t.a, v1 = t.c - t.a, v2 = p - t.a;
    const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
    const double d20 = v2.dot(v0), d21 = v2.dot(v1);
    const double den = d00 * d11 - d01 * d01;
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    constexpr double eps = 1e-9;
    if (v < -eps || w < -eps || v + w > 1.0 + eps) return;
    best = Hit{t.normal, gap};
  };
  if (n_cells > static_cast<double>(triangles_.size())) {
    for (const Triangle& t : triangles_) test(t);
    return best;
  }
  for (int i = a(0); i <= b(0); ++i)
    for (int j = a(1); j <= b(1); ++j)
      for (int k = a(2); k <= b(2); ++k) {
        const auto it = buckets_.find(key(i, j, k));
        if (it == buckets_.end()) continue;
        for (int f : it->second) test(triangles_[static_cast<std::size_t>(f)]);
      }
  return best;
}

std::vector<int> TargetSurface::near(const Vec3& y, double reach) const {
  std::vector<int> out;
  const Vec3 lo = y - Vec3::Constant(reach), hi = y + Vec3::Constant(reach);
  const auto test = [&](int f) {
    const Triangle& t = triangles_[static_cast<std::size_t>(f)];
    const Vec3 tlo = t.a.cwiseMin(t.b).cwiseMin(t.c), thi = t.a.cwiseMax(t.b).cwiseMax(t.c);
    if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) return;
    if (std::abs((y - t.a).dot(t.normal)) > reach) return;
    out.push_back(f);
  };
  Eigen::Vector3i a, b;
  cell_range(lo, hi, a, b);
  const Eigen::Vector3i span = b - a + Eigen::Vector3i::Ones();
  if (static_cast<double>(span(0)) * span(1) * span(2) > static_cast<double>(triangles_.size())) {
    for (std::size_t f = 0; f < triangles_.size(); ++f) test(static_cast<int>(f));
    return out;
  }
  std::vector<int> seen;
  for (int i = a(0); i <= b(0); ++i)
    for (int j = a(1); j <= b(1); ++j)
      for (int k = a(2); k <= b(2); ++k) {
        const auto it = buckets_.find(key(i, j, k));
        if (it != buckets_.end()) seen.insert(seen.end(), it->second.begin(), it->second.end());
      }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  for (int f : seen) test(f);
  return out;
}

struct TargetSurface::Current {
  std::unique_ptr<TargetSurface> grid;     // over the facets as they were at the last build
  std::unordered_map<int, Vec3> built_at;  // node positions at the last build
  long long pass = -1;                     // the refresh pass `moved` belongs to
  double moved = 0.0;                      // largest node movement since the build
  int builds = 0;
};

std::vector<int> TargetSurface::near_current(const Vec3& x, double reach,
                                             const NodePositions& at) const {
  if (!current_) current_ = std::make_shared<Current>();
  Current& c = *current_;
  if (c.grid && c.pass != at.pass) {
    c.moved = 0.0;
    for (const auto& [n, p] : c.built_at) c.moved = std::max(c.moved, (at.at(n) - p).norm());
  }
  c.pass = at.pass;
  if (!c.grid || c.moved > 0.25 * reach) {
    std::vector<Triangle> now = triangles_;
    c.built_at.clear();
    for (Triangle& t : now) {
      t.a = at.at(t.nodes[0]);
      t.b = at.at(t.nodes[1]);
      t.c = at.at(t.nodes[2]);
      const Vec3 normal = (t.b - t.a).cross(t.c - t.a);
      if (normal.norm() > 0.0) t.normal = normal.normalized();
      for (std::size_t k = 0; k < 3; ++k)
        c.built_at[t.nodes[k]] = k == 0 ? t.a : k == 1 ? t.b : t.c;
    }
    c.grid = std::make_unique<TargetSurface>(0, std::move(now));
    c.moved = 0.0;
    ++c.builds;
  }
  std::vector<int> out;
  const Vec3 lo = x - Vec3::Constant(reach), hi = x + Vec3::Constant(reach);
  for (int f : c.grid->near(x, reach + c.moved)) {
    const Triangle& t = triangles_[static_cast<std::size_t>(f)];
    const Vec3 a = at.at(t.nodes[0]), b = at.at(t.nodes[1]), d = at.at(t.nodes[2]);
    const Vec3 tlo = a.cwiseMin(b).cwiseMin(d), thi = a.cwiseMax(b).cwiseMax(d);
    if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) continue;
    const Vec3 normal = (b - a).cross(d - a);
    if (normal.norm() > 0.0 && std::abs((x - a).dot(normal.normalized())) > reach) continue;
    out.push_back(f);
  }
  return out;
}

int TargetSurface::current_grid_builds() const {
  return current_ ? current_->builds : 0;
}

namespace {

constexpr const char* kRigidTargetFamily = "RigidTarget";

/// Distinct nodes of a record in order (E repeats the last node of a short node list).
std::vector<int> distinct_nodes(const ElementRecord& record) {
  std::vector<int> out;
  for (int n : record.nodes)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

bool is_target(const Model& model, const ElementRecord& record) {
  const auto type = model.element_types.find(record.type);
  return type != model.element_types.end() && type->second.ansys_name == "TARGE170";
}

}  // namespace

std::shared_ptr<const TargetSurface> contact_target(const ElementBuildContext& ctx,
                                                    const ElementRecord& record) {
  // Built once per set and build pass: every contact element of the set shares it.
  std::shared_ptr<const TargetSurface>& shared = build_cache(ctx).targets[record.real];
  if (shared) return shared;
  const Model& model = ctx.model;
  std::vector<TargetSurface::Triangle> triangles;
  int pilot = 0;
  for (const auto& [id, rec] : model.elements) {
    if (rec.real != record.real || !is_target(model, rec)) continue;
    for (std::size_t k = 0; k < rec.nodes.size(); ++k)  // every node defined (InputError)
      line_data::node(model, rec, k, rec.nodes.size(), kRigidTargetFamily);
    const std::vector<int> nodes = distinct_nodes(rec);
    if (nodes.size() == 1) {
      if (pilot != 0 && pilot != nodes[0])
        throw InputError(rec.where, fmt::format("element {} (TARGE170): a second pilot node ({}; "
                                                "the first is node {}) in real set {}",
                                                id, nodes[0], pilot, rec.real));
      pilot = nodes[0];
      continue;
    }
    if (nodes.size() < 3)  // two distinct nodes: neither a pilot nor a facet
      throw InputError(rec.where,
                       fmt::format("element {} (TARGE170): a target facet needs 3 or 4 distinct "
                                   "nodes (a pilot node 1); {} given",
                                   id, nodes.size()));
    // Named copies: clang 14 (the sanitizer build) cannot capture structured bindings.
    const auto add = [&, where = rec.where, element = id](int i, int j, int k) {
      const Vec3 &a = model.nodes.at(i).x, &b = model.nodes.at(j).x, &c = model.nodes.at(k).x;
      const Vec3 normal = (b - a).cross(c - a);
      if (!(normal.norm() > 0.0))
        throw InputError(where,
                         fmt::format("element {} (TARGE170): degenerate target facet", element));
      triangles.push_back({a, b, c, normal.normalized(), {i, j, k}});
    };
    add(nodes[0], nodes[1], nodes[2]);
    if (nodes.size() == 4) add(nodes[0], nodes[2], nodes[3]);
  }
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {}: {}", record.id, what));
  };
  if (triangles.empty() && has_line_target(model, record.real))
    throw fail(
        fmt::format("real constant set {} holds 2-D TARGE169 target segments: a 3-D "
                    "contact element cannot meet them (use CONTA171/172 or CONTA175)",
                    record.real));
  if (triangles.empty())
    throw fail(
        fmt::format("no TARGE170 target facets share its real constant set {} (a contact "
                    "pair is a target and a contact type with the same REAL)",
                    record.real));
  if (pilot == 0) {
    // Deformable target: its facet nodes must move with a body (else they would be constrained
    // automatically and the "deformable" target would silently be a fixed one).
    std::vector<int> body;
    for (const auto& [id, rec] : model.elements) {
      const auto t = model.element_types.find(rec.type);
      if (t == model.element_types.end()) continue;
      const std::string& name = t->second.ansys_name;
      if (name.rfind("TARGE", 0) == 0 || name.rfind("CONTA", 0) == 0) continue;
      body.insert(body.end(), rec.nodes.begin(), rec.nodes.end());
    }
    std::sort(body.begin(), body.end());
    for (const auto& t : triangles)
      for (int n : t.nodes)
        if (!std::binary_search(body.begin(), body.end(), n))
          throw fail(
              fmt::format("the target of real set {} has no pilot node, so it is deformable, "
                          "but its facet node {} belongs to no body element: mesh the target "
                          "on a deformable body, or give a rigid target a pilot (a TARGE170 "
                          "element with one node, E,pilot, in the same REAL)",
                          record.real, n));
  }
  // MAPDL activates the pilot's rotations only when something acts on them [A: here an
  // element with rotational DOFs at the pilot, e.g. MASS21 with rotary inertia, a beam or a
  // shell]; then the target turns with them.
  bool rotates = false;
  if (pilot != 0)
    for (const int id : elements_at_node(ctx, pilot)) {
      const ElementRecord& rec = model.elements.at(id);
      const auto t = model.element_types.find(rec.type);
      if (t == model.element_types.end()) continue;
      const std::string& name = t->second.ansys_name;
      if (name.rfind("TARGE", 0) == 0 || name.rfind("CONTA", 0) == 0) continue;
      const ElementTypeDescriptor& d = element_type_descriptor(t->second);
      if (d.defined_by_file) continue;
      // Keep the element alive for the loop: dofs() refers into it (a temporary in the range
      // expression would be destroyed before the loop runs; AddressSanitizer found it).
      const std::unique_ptr<Element> element = d.create(ctx, rec);
      for (const DofKey& k : element->dofs())
        rotates = rotates || (k.node == pilot && static_cast<int>(k.dof) >= 3);
    }
  shared = std::make_shared<const TargetSurface>(pilot, std::move(triangles), rotates);
  return shared;
}

void check_surface_contact_fields(const ElementRecord& record, const char* name,
                                  const ElementType& type, const RealSet& real) {
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, what));
  };
  const int real_id = record.real;
  for (int k = 1; k < static_cast<int>(type.keyopt.size()); ++k) {
    const int v = type.key(k);
    const bool ok = v == 0 || (k == 2 && v == 1) || (k == 4 && v <= 3) || (k == 7 && v == 1) ||
                    (k == 10 && v <= 2) || (k == 12 && v <= 6) || (k == 18 && v == 1);
    if (!ok || v < 0)
      throw fail(
          fmt::format("KEYOPT({}) = {} is not supported (KEYOPT(2) 0 augmented "
                      "Lagrange / 1 penalty, KEYOPT(4) 0-3 (detection), KEYOPT(7) 0 / 1 "
                      "(bisection on penetration > FTOLN x depth under AUTOTS), KEYOPT(10) "
                      "0-2 (constant stiffness), KEYOPT(12) 0-6, KEYOPT(18) 0 large / 1 small "
                      "sliding on a deformable target; the others 0)",
                      k, v));
  }
  // 3 FKN, 4 FTOLN, 6 PINB, 10 CNOF, 12 FKT are read; 14 and beyond are thermal (ignored).
  for (int i : {1, 2, 5, 7, 8, 9, 11, 13})
    if (real.get(i) != 0.0)
      throw fail(
          fmt::format("real constant {} of set {} is not supported (impactfe reads 3 FKN, "
                      "4 FTOLN, 6 PINB, 10 CNOF, 12 FKT)",
                      i, real_id));
}

ContactLawData surface_contact_law(const ElementBuildContext& ctx, const ElementRecord& record,
                                   const char* name, const RealSet& real, int node, const Vec3& n0,
                                   double share, double per) {
  const Model& model = ctx.model;
  const ElementType& type = model.element_types.at(record.type);
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, what));
  };
  ContactLawData data;
  data.augmented = type.key(2) == 0;
  data.behaviour = static_cast<ContactBehaviour>(type.key(12));
  data.bisect_on_penetration = type.key(7) == 1;
  const double fkn = real.get(3) != 0.0 ? real.get(3) : 1.0;
  if (fkn < 0.0) {
    data.kn = -fkn * per;
  } else {
    const double base = attached_stiffness(ctx, node, n0);
    if (!(base > 0.0))
      throw fail(
          fmt::format("FKN > 0 is a factor on the stiffness at node {}, and no element "
                      "with stiffness is attached: give a negative (absolute) FKN",
                      node));
    data.kn = fkn * base * share;
  }
  const double fkt = real.get(12) != 0.0 ? real.get(12) : 1.0;
  data.kt = fkt < 0.0 ? -fkt * per : fkt * data.kn;
  const auto mat = model.materials.find(record.mat);
  data.mu = mat == model.materials.end() ? 0.0 : mat->second.get("MU", 0.0);
  if (data.mu < 0.0) throw fail(fmt::format("MU of material {} is negative", record.mat));
  return data;
}

std::unique_ptr<ContactPoint> target_point(const ElementBuildContext& ctx,
                                           const ElementRecord& record, const Node& node,
                                           const char* family, const char* name, double share,
                                           double area) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, what));
  };
  const RealSet& real = line_data::real_set(model, record, family);
  check_surface_contact_fields(record, name, type, real);
  std::shared_ptr<const TargetSurface> target = contact_target(ctx, record);
  if (target->pilot() == node.id) throw fail("the contact node is the target's pilot node");
  std::vector<int> candidates;

  const double depth = attached_depth(ctx, node.id);
  const auto length = [&](double value, double fallback, const char* what) {
    const double v = value != 0.0 ? value : fallback;
    if (v < 0.0) return -v;
    if (!(depth > 0.0))
      throw fail(
          fmt::format("{} is a factor on the depth of the underlying elements, and none "
                      "with a volume is attached to node {}: give it as a negative "
                      "(absolute) value",
                      what, node.id));
    return v * depth;
  };
  const double reach = length(real.get(6), 2.0, "PINB (real constant 6)");
  const double toln = real.get(4) < 0.0 || depth > 0.0 ? length(real.get(4), 0.1, "FTOLN") : 0.0;

  // The initial normal: the nearest facet within the pinball, else the first facet.
  const auto hit = target->closest(node.x, reach);
  Vec3 n0 = hit ? hit->normal : target->triangles().front().normal;
  if (target->deformable()) {
    // The candidates within the pinball (large sliding: over its margin), never a facet on the
    // node itself.
    const bool large = type.key(18) == 0;
    for (int f :
         target->near(node.x, large ? DeformableTargetPoint::kLargeSlidingMargin * reach : reach)) {
      const auto& t = target->triangles()[static_cast<std::size_t>(f)];
      if (std::find(t.nodes.begin(), t.nodes.end(), node.id) == t.nodes.end())
        candidates.push_back(f);
    }
    if (!hit && !candidates.empty())
      n0 = target->triangles()[static_cast<std::size_t>(candidates.front())].normal;
  }
  // Absolute stiffnesses: force/length per node, or force/length³ over the tributary area.
  ContactLawData data =
      surface_contact_law(ctx, record, name, real, node.id, n0, share, area > 0.0 ? area : 1.0);
  data.toln = toln;
  if (!target->deformable())
    return std::make_unique<RigidTargetPoint>(family, record.id, node.id, node.x,
                                              model.nodes.at(target->pilot()).x, std::move(target),
                                              reach, real.get(10), data);
  std::vector<int> nodes = {node.id};
  for (int f : candidates)
    for (int n : target->triangles()[static_cast<std::size_t>(f)].nodes)
      if (std::find(nodes.begin(), nodes.end(), n) == nodes.end()) nodes.push_back(n);
  std::vector<Vec3> x;
  for (int n : nodes) x.push_back(model.nodes.at(n).x);
  return std::make_unique<DeformableTargetPoint>(family, record.id, std::move(nodes), std::move(x),
                                                 std::move(target), std::move(candidates), reach,
                                                 real.get(10), data, type.key(18) == 0);
}

namespace {

std::unique_ptr<Element> make_rigid_target(const ElementBuildContext& ctx,
                                           const ElementRecord& record) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  check_target_keyopts(type, record, "TARGE170");
  const std::vector<int> nodes = distinct_nodes(record);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    line_data::node(model, record, k, 1, kRigidTargetFamily);
  if (nodes.size() == 2)
    throw InputError(record.where,
                     fmt::format("element {} (TARGE170): two distinct nodes: give a pilot (one "
                                 "node), a triangle (three) or a quadrilateral (four)",
                                 record.id));
  line_data::real_set(model, record, kRigidTargetFamily);
  // Builds the target once to report a bad target at its first element.
  contact_target(ctx, record);
  return std::make_unique<TargetElement>(record.id, kRigidTargetFamily, nodes,
                                         std::initializer_list<Dof>{Dof::UX, Dof::UY, Dof::UZ});
}

const ElementRegistration kTarge170{{.name = "TARGE170",
                                     .number = 170,
                                     .family = kRigidTargetFamily,
                                     .n_nodes = 4,
                                     .min_nodes = 1,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Quad,
                                     .role = ShapeRole::Target,
                                     .result_names = TargetElement::names(),
                                     .create = make_rigid_target}};

}  // namespace

}  // namespace impactfe
