/// CONTA174 surface contact against a TARGE170 target (APDL_MODELING §8.4), rigid (pilot) or
/// deformable (large or small sliding, docs/elements/targe170.md). KEYOPT(4) selects the
/// detection as MAPDL does: 0 (the default, Gauss points) and 3 (surface projection) integrate
/// the contact pressure over the face, segment to segment (elements/contact_segment.h); 1 and 2
/// detect at the corner nodes: each distinct corner node is a contact point of CONTA175's law
/// (elements/target_surface.h target_point: penalty / augmented Lagrange, Coulomb friction,
/// KEYOPT(12)) against the target of the element's real set. Either way the element is a set of
/// ContactPoints and its DOFs are the union of theirs.
///
/// Stiffness per node: the face's tributary area of the node, a = A/n (A the face area, n its
/// corner count — the lumped nodal weights of a bilinear face). A positive FKN scales the
/// stiffness attached to the node by a / Σa, the sum over the CONTA174 elements of the same TYPE
/// and REAL at that node, so a node shared by several faces carries in total exactly the
/// stiffness a CONTA175 at that node would (the same answer as CONTA175 on the same nodes); a
/// negative FKN is MAPDL's absolute force/length³, times a. Segment to segment, the face's
/// stiffness per area is Σ k_node / A, times each integration point's weight. Midside nodes
/// (8-node faces) are not supported.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "elements/contact_point_set.h"
#include "elements/contact_segment.h"
#include "elements/element_build_cache.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

constexpr const char* kSurfaceContactFamily = "SurfaceContact";

/// Distinct corner nodes (the first four positions; E repeats the last node of a short list).
std::vector<int> corners(const ElementRecord& record) {
  std::vector<int> out;
  for (std::size_t k = 0; k < std::min<std::size_t>(4, record.nodes.size()); ++k)
    if (std::find(out.begin(), out.end(), record.nodes[k]) == out.end())
      out.push_back(record.nodes[k]);
  return out;
}

/// Area of the face through `nodes` (a triangle, or a quadrilateral from its diagonals).
double face_area(const Model& model, const std::vector<int>& nodes) {
  std::vector<Vec3> x;
  for (int n : nodes) x.push_back(model.nodes.at(n).x);
  if (x.size() == 3) return 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
  return 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm();
}

std::unique_ptr<Element> make_surface_contact(const ElementBuildContext& ctx,
                                              const ElementRecord& record) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} (CONTA174): {}", record.id, what));
  };
  for (std::size_t k = 0; k < record.nodes.size(); ++k)
    line_data::node(model, record, k, record.nodes.size(), kSurfaceContactFamily);
  const std::vector<int> nodes = corners(record);
  for (std::size_t k = 4; k < record.nodes.size(); ++k)
    if (std::find(nodes.begin(), nodes.end(), record.nodes[k]) == nodes.end())
      throw fail(
          "midside nodes (8-node faces) are not supported: give the 3 or 4 corner nodes "
          "(E,I,J,K,L) or generate the elements with ESURF on linear elements");
  if (nodes.size() < 3) throw fail("a contact face needs 3 or 4 distinct corner nodes");
  const double area = face_area(model, nodes);
  if (!(area > 0.0)) throw fail("degenerate contact face (zero area)");
  const double tributary = area / static_cast<double>(nodes.size());

  std::vector<std::unique_ptr<ContactPoint>> points;
  for (int n : nodes) {
    // Σ of the tributary areas at n over the CONTA174 faces of this TYPE and REAL.
    double total = 0.0;
    for (const int id : elements_at_node(ctx, n)) {
      const ElementRecord& other = model.elements.at(id);
      if (other.type != record.type || other.real != record.real) continue;
      const std::vector<int> c = corners(other);
      if (c.size() < 3 || std::find(c.begin(), c.end(), n) == c.end()) continue;
      total += face_area(model, c) / static_cast<double>(c.size());
    }
    const Node& node = model.nodes.at(n);
    points.push_back(target_point(ctx, record, node, kSurfaceContactFamily, "CONTA174",
                                  tributary / std::max(total, tributary), tributary));
  }
  // KEYOPT(4) = 0 (MAPDL's default, Gauss-point detection) and 3 (surface-projection based):
  // segment-to-segment integration over the face (elements/contact_segment.h); 1 and 2: nodal.
  const int detection = line_data::element_type(model, record).key(4);
  if (detection == 0 || detection == 3)
    points = segment_points(ctx, record, nodes, points, kSurfaceContactFamily);
  return std::make_unique<ContactPointSet>(record.id, kSurfaceContactFamily, "CONTA174",
                                           std::move(points));
}

const ElementRegistration kConta174{{.name = "CONTA174",
                                     .number = 174,
                                     .family = kSurfaceContactFamily,
                                     .n_nodes = 8,
                                     .min_nodes = 3,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Quad,
                                     .role = ShapeRole::Contact,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_surface_contact}};

}  // namespace

}  // namespace impactfe
