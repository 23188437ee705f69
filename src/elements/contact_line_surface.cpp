/// CONTA171 (2-node line) and CONTA172 (3-node line) 2-D surface contact against a TARGE169
/// target (APDL_MODELING §8.4, docs/elements/targe169.md), on the boundary of 2-D bodies. As
/// CONTA174 with nodal detection (elements/contact_surface.cpp), each distinct node of the line
/// is a contact point of CONTA175's 2-D law (elements/target_line.h LineTargetPoint: penalty /
/// augmented Lagrange, Coulomb friction, KEYOPT(12)) against the target of the element's real
/// set, and the element's DOFs are the union of the points' (UX, UY only).
///
/// Stiffness per node: the line's tributary length of the node, ℓ = L/2 (the lumped nodal weights
/// of a linear edge). A positive FKN scales the stiffness attached to the node by ℓ / Σℓ, the sum
/// over the contact lines of the same TYPE and REAL at that node, so a node shared by two lines
/// carries in total the stiffness a CONTA175 at that node would; a negative FKN is MAPDL's
/// absolute force/length³ (pressure per penetration), times the node's contact area ℓ × the
/// out-of-plane extent of the body under it (its plane-stress thickness; 1 in plane strain), so
/// that the force is in the units of the body's nodal forces. KEYOPT(4) (detection) is nodal for
/// every value: the Gauss-point integration of CONTA174 (segment to segment) is not carried out
/// in 2-D [A]. Midside nodes are refused as CONTA174 refuses them: a CONTA172 with its midside
/// node K blank (E,I,J: MAPDL's "dropped midside node") is a 2-node line.
#include <fmt/format.h>

#include <algorithm>

#include "elements/contact_point_set.h"
#include "elements/element_build_cache.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_line.h"

namespace impactfe {

namespace {

constexpr const char* kLineContactFamily = "LineContact";

/// The distinct end nodes I, J (E repeats J as a blank K).
std::vector<int> line_ends(const ElementRecord& record) {
  std::vector<int> out;
  for (std::size_t k = 0; k < std::min<std::size_t>(2, record.nodes.size()); ++k)
    if (std::find(out.begin(), out.end(), record.nodes[k]) == out.end())
      out.push_back(record.nodes[k]);
  return out;
}

double line_length(const Model& model, const std::vector<int>& ends) {
  return (model.nodes.at(ends[1]).x - model.nodes.at(ends[0]).x).norm();
}

std::unique_ptr<Element> make_line_contact(const ElementBuildContext& ctx,
                                           const ElementRecord& record, const char* name) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, what));
  };
  for (std::size_t k = 0; k < record.nodes.size(); ++k)
    line_data::node(model, record, k, record.nodes.size(), kLineContactFamily);
  const std::vector<int> ends = line_ends(record);
  for (std::size_t k = 2; k < record.nodes.size(); ++k)
    if (std::find(ends.begin(), ends.end(), record.nodes[k]) == ends.end())
      throw fail(
          "midside nodes are not supported (as for CONTA174): give the two end nodes (E,I,J) or "
          "generate the elements with ESURF on linear elements (PLANE182)");
  if (ends.size() < 2) throw fail("a contact line needs 2 distinct nodes");
  if (!has_line_target(model, record.real))
    throw fail(
        fmt::format("no TARGE169 target segments share its real constant set {} (a 2-D "
                    "contact pair is a TARGE169 and a CONTA171/172/175 with the same REAL)",
                    record.real));
  const double length = line_length(model, ends);
  if (!(length > 0.0)) throw fail("zero-length contact line");
  const double tributary = 0.5 * length;

  std::vector<std::unique_ptr<ContactPoint>> points;
  for (int n : ends) {
    // Σ of the tributary lengths at n over the contact lines of this TYPE and REAL.
    double total = 0.0;
    for (const int id : elements_at_node(ctx, n)) {
      const ElementRecord& other = model.elements.at(id);
      if (other.type != record.type || other.real != record.real) continue;
      const std::vector<int> e = line_ends(other);
      if (e.size() < 2 || std::find(e.begin(), e.end(), n) == e.end()) continue;
      total += 0.5 * line_length(model, e);
    }
    points.push_back(line_target_point(ctx, record, model.nodes.at(n), kLineContactFamily, name,
                                       tributary / std::max(total, tributary), tributary));
  }
  return std::make_unique<ContactPointSet>(record.id, kLineContactFamily, name, std::move(points));
}

std::unique_ptr<Element> make_conta171(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  return make_line_contact(ctx, record, "CONTA171");
}

std::unique_ptr<Element> make_conta172(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  return make_line_contact(ctx, record, "CONTA172");
}

const ElementRegistration kConta171{{.name = "CONTA171",
                                     .number = 171,
                                     .family = kLineContactFamily,
                                     .n_nodes = 2,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Line,
                                     .role = ShapeRole::Contact,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_conta171}};

const ElementRegistration kConta172{{.name = "CONTA172",
                                     .number = 172,
                                     .family = kLineContactFamily,
                                     .n_nodes = 2,
                                     // The midside node K: optional, and refused when given.
                                     .n_optional_nodes = 1,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Line,
                                     .role = ShapeRole::Contact,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_conta172}};

}  // namespace

}  // namespace impactfe
