/// TARGE169 (2-D target segments and pilot node), the shared 2-D target of a real set and the
/// law of a contact node against it (elements/target_line.h).
#include "elements/target_line.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "elements/element_build_cache.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_element.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

constexpr const char* kLineTargetFamily = "LineTarget";

bool is_line_target(const Model& model, const ElementRecord& record) {
  const auto type = model.element_types.find(record.type);
  return type != model.element_types.end() && type->second.ansys_name == "TARGE169";
}

/// Distinct nodes of a record in order (E repeats the last node of a short node list).
std::vector<int> target169_nodes(const ElementRecord& record) {
  std::vector<int> out;
  for (int n : record.nodes)
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  return out;
}

/// Neither a target nor a contact element: a body that moves the nodes it holds.
bool holds_body_nodes(const Model& model, const ElementRecord& record) {
  const auto t = model.element_types.find(record.type);
  if (t == model.element_types.end()) return false;
  const std::string& name = t->second.ansys_name;
  return name.rfind("TARGE", 0) != 0 && name.rfind("CONTA", 0) != 0;
}

/// In-plane area of a body element (shoelace over its distinct corner nodes in order).
double planar_area(const Model& model, const ElementRecord& record) {
  const auto t = model.element_types.find(record.type);
  if (t == model.element_types.end()) return 0.0;
  const int corners = element_type_descriptor(t->second).topology().corner_nodes;
  std::vector<Vec3> x;
  for (std::size_t k = 0; k < std::min<std::size_t>(corners, record.nodes.size()); ++k) {
    const auto it = model.nodes.find(record.nodes[k]);
    if (it == model.nodes.end()) return 0.0;
    if (x.empty() || !(it->second.x - x.back()).isZero(0.0)) x.push_back(it->second.x);
  }
  double twice = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Vec3& a = x[k];
    const Vec3& b = x[(k + 1) % x.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice);
}

/// The 2-D depth (√ of the mean in-plane area) and out-of-plane extent (mean volume / in-plane
/// area) of the body elements with a volume attached to `node`; zeros when none.
std::pair<double, double> planar_depth(const ElementBuildContext& ctx, int node) {
  double area = 0.0, extent = 0.0;
  int count = 0;
  for (const int id : elements_at_node(ctx, node)) {
    const AttachedElement* attached = attached_element(ctx, id);
    if (attached == nullptr || !attached->volume || !(*attached->volume > 0.0)) continue;
    const double a = planar_area(ctx.model, ctx.model.elements.at(id));
    if (!(a > 0.0)) continue;
    area += a;
    extent += *attached->volume / a;
    ++count;
  }
  if (count == 0) return {0.0, 0.0};
  return {std::sqrt(area / count), extent / count};
}

}  // namespace

LineTarget::LineTarget(Motion motion, int pilot, const Vec3& pilot_x, bool rotates,
                       std::vector<Segment> segments)
    : motion_(motion),
      pilot_(pilot),
      pilot_x_(pilot_x),
      rotates_(rotates),
      segments_(std::move(segments)) {
  std::map<int, std::vector<int>> at;
  for (std::size_t s = 0; s < segments_.size(); ++s)
    for (int n : segments_[s].nodes) at[n].push_back(static_cast<int>(s));
  for (std::size_t s = 0; s < segments_.size(); ++s)
    for (std::size_t e = 0; e < 2; ++e)
      for (int other : at[segments_[s].nodes[e]])
        if (other != static_cast<int>(s)) segments_[s].neighbour[e] = other;
}

Vec3 LineTarget::normal(const Vec3& a, const Vec3& b) {
  const Vec3 t = (b - a).normalized();
  return {t.y(), -t.x(), 0.0};
}

double LineTarget::distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double ee = e.squaredNorm();
  const double xi = ee > 0.0 ? std::clamp((x - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (x - (a + xi * e)).norm();
}

bool has_line_target(const Model& model, int real) {
  return std::any_of(model.elements.begin(), model.elements.end(), [&](const auto& entry) {
    return entry.second.real == real && is_line_target(model, entry.second);
  });
}

std::shared_ptr<const LineTarget> line_target(const ElementBuildContext& ctx,
                                              const ElementRecord& record) {
  std::shared_ptr<const LineTarget>& shared = build_cache(ctx).line_targets[record.real];
  if (shared) return shared;
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {}: {}", record.id, what));
  };
  std::vector<LineTarget::Segment> segments;
  int pilot = 0;
  bool given_constraints = false;  // TARGE169 KEYOPT(2) = 1
  for (const auto& [id, rec] : model.elements) {
    if (rec.real != record.real || !is_line_target(model, rec)) continue;
    for (std::size_t k = 0; k < rec.nodes.size(); ++k)
      line_data::node(model, rec, k, rec.nodes.size(), kLineTargetFamily);
    given_constraints = given_constraints || line_data::element_type(model, rec).key(2) == 1;
    const std::vector<int> nodes = target169_nodes(rec);
    if (nodes.size() == 1) {
      if (pilot != 0 && pilot != nodes[0])
        throw InputError(rec.where, fmt::format("element {} (TARGE169): a second pilot node ({}; "
                                                "the first is node {}) in real set {}",
                                                id, nodes[0], pilot, rec.real));
      pilot = nodes[0];
      continue;
    }
    if (nodes.size() != 2)
      throw InputError(rec.where,
                       fmt::format("element {} (TARGE169): a target segment has 2 nodes (TSHAP,"
                                   "LINE), a pilot 1; {} given (parabolic segments are not "
                                   "implemented)",
                                   id, nodes.size()));
    LineTarget::Segment s;
    s.nodes = {nodes[0], nodes[1]};
    s.a = model.nodes.at(nodes[0]).x;
    s.b = model.nodes.at(nodes[1]).x;
    if (s.a.z() != 0.0 || s.b.z() != 0.0)
      throw InputError(rec.where, fmt::format("element {} (TARGE169): a 2-D target segment lies "
                                              "in the X-Y plane; node {} or {} has Z != 0",
                                              id, nodes[0], nodes[1]));
    if (!((s.b - s.a).norm() > 0.0))
      throw InputError(rec.where,
                       fmt::format("element {} (TARGE169): zero-length target segment", id));
    segments.push_back(s);
  }
  if (segments.empty())
    throw fail(
        fmt::format("no TARGE169 target segments share its real constant set {} (a 2-D "
                    "contact pair is a TARGE169 and a CONTA171/172/175 type with the "
                    "same REAL)",
                    record.real));
  LineTarget::Motion motion = LineTarget::Motion::Pilot;
  if (pilot == 0) {
    std::vector<int> body;
    for (const auto& [id, rec] : model.elements)
      if (holds_body_nodes(model, rec)) body.insert(body.end(), rec.nodes.begin(), rec.nodes.end());
    std::sort(body.begin(), body.end());
    int on = 0, off = 0, first_on = 0, first_off = 0;
    for (const auto& s : segments)
      for (int n : s.nodes) {
        const bool b = std::binary_search(body.begin(), body.end(), n);
        (b ? on : off) += 1;
        int& first = b ? first_on : first_off;
        if (first == 0) first = n;
      }
    if (on > 0 && off > 0)
      throw fail(
          fmt::format("the 2-D target of real set {} has no pilot node, and its node {} "
                      "belongs to a body element while node {} belongs to none: a "
                      "deformable target lies on a body, a fixed rigid one on none",
                      record.real, first_on, first_off));
    motion = on > 0 ? LineTarget::Motion::Deformable : LineTarget::Motion::Fixed;
    if (motion == LineTarget::Motion::Fixed && given_constraints)
      throw fail(fmt::format(
          "the 2-D target of real set {} is rigid (on no body) without a pilot node and has "
          "TARGE169 KEYOPT(2) = 1 (constraints given by the user): its nodes would move with "
          "those constraints, which is not implemented; give it a pilot node (TSHAP,PILO) or "
          "KEYOPT(2) = 0 (held fixed)",
          record.real));
  }
  // The pilot turns the target when an element gives it ROTZ (as contact_target() in 3-D).
  bool rotates = false;
  if (pilot != 0)
    for (const int id : elements_at_node(ctx, pilot)) {
      const ElementRecord& rec = model.elements.at(id);
      if (!holds_body_nodes(model, rec)) continue;
      const ElementTypeDescriptor& d = element_type_descriptor(model.element_types.at(rec.type));
      if (d.defined_by_file) continue;
      const std::unique_ptr<Element> element = d.create(ctx, rec);
      for (const DofKey& k : element->dofs()) {
        if (k.node != pilot) continue;
        if (k.dof == Dof::ROTX || k.dof == Dof::ROTY || k.dof == Dof::UZ)
          throw fail(
              fmt::format("the pilot node {} of the 2-D target of real set {} carries "
                          "out-of-plane DOFs (UZ, ROTX or ROTY) from element {}: a 2-D "
                          "target moves in the X-Y plane only",
                          pilot, record.real, id));
        rotates = rotates || k.dof == Dof::ROTZ;
      }
    }
  const Vec3 pilot_x = pilot != 0 ? model.nodes.at(pilot).x : Vec3::Zero();
  shared = std::make_shared<const LineTarget>(motion, pilot, pilot_x, rotates, std::move(segments));
  return shared;
}

std::unique_ptr<ContactPoint> line_target_point(const ElementBuildContext& ctx,
                                                const ElementRecord& record, const Node& node,
                                                const char* family, const char* name, double share,
                                                double length) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, what));
  };
  const RealSet& real = line_data::real_set(model, record, family);
  check_surface_contact_fields(record, name, type, real);
  std::shared_ptr<const LineTarget> target = line_target(ctx, record);
  if (target->pilot() == node.id) throw fail("the contact node is the target's pilot node");
  if (node.x.z() != 0.0)
    throw fail(fmt::format("node {} has Z != 0: 2-D contact lies in the X-Y plane", node.id));

  const auto [depth, extent] = planar_depth(ctx, node.id);
  const auto distance = [&, d = depth](double value, double fallback, const char* what) {
    const double v = value != 0.0 ? value : fallback;
    if (v < 0.0) return -v;
    if (!(d > 0.0))
      throw fail(
          fmt::format("{} is a factor on the depth of the underlying elements, and none "
                      "with an area is attached to node {}: give it as a negative "
                      "(absolute) value",
                      what, node.id));
    return v * d;
  };
  const double reach = distance(real.get(6), 2.0, "PINB (real constant 6)");
  const double toln = real.get(4) < 0.0 || depth > 0.0 ? distance(real.get(4), 0.1, "FTOLN") : 0.0;

  // The initial normal: of the segment nearest to the node (its stiffness direction).
  const auto& segments = target->segments();
  const auto initial = [](int, const Vec3& x) { return x; };
  int nearest = 0;
  double least = -1.0;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const double d = LineTarget::distance(node.x, segments[s].a, segments[s].b);
    if (least < 0.0 || d < least) {
      least = d;
      nearest = static_cast<int>(s);
    }
  }
  const Vec3 n0 = LineTarget::normal(segments[static_cast<std::size_t>(nearest)].a,
                                     segments[static_cast<std::size_t>(nearest)].b);
  const bool large = type.key(18) == 0;
  std::vector<int> candidates;
  if (target->motion() == LineTarget::Motion::Deformable)
    for (int s : target->near(node.x, large ? LineTargetPoint::kLargeSlidingMargin * reach : reach,
                              initial)) {
      const auto& n = segments[static_cast<std::size_t>(s)].nodes;
      if (n[0] != node.id && n[1] != node.id) candidates.push_back(s);
    }

  // Absolute stiffnesses: force/length for a point contact; force/length³ over the node's
  // contact area (tributary length × out-of-plane extent) for a line contact.
  const double per = length > 0.0 ? length * (extent > 0.0 ? extent : 1.0) : 1.0;
  ContactLawData data = surface_contact_law(ctx, record, name, real, node.id, n0, share, per);
  data.toln = toln;
  return std::make_unique<LineTargetPoint>(family, record.id, node.id, node.x, std::move(target),
                                           std::move(candidates), reach, real.get(10), data, large);
}

namespace {

std::unique_ptr<Element> make_line_target(const ElementBuildContext& ctx,
                                          const ElementRecord& record) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  check_target_keyopts(type, record, "TARGE169");
  line_data::real_set(model, record, kLineTargetFamily);
  const std::vector<int> nodes = target169_nodes(record);
  // Builds the target once to report a bad target at its first element.
  line_target(ctx, record);
  return std::make_unique<TargetElement>(record.id, kLineTargetFamily, nodes,
                                         std::initializer_list<Dof>{Dof::UX, Dof::UY});
}

const ElementRegistration kTarge169{{.name = "TARGE169",
                                     .number = 169,
                                     .family = kLineTargetFamily,
                                     .n_nodes = 2,
                                     .min_nodes = 1,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Line,
                                     .role = ShapeRole::Target,
                                     .result_names = TargetElement::names(),
                                     .create = make_line_target}};

}  // namespace

}  // namespace impactfe
