/// CONTA175 node-to-surface contact against a TARGE170 target (APDL_MODELING §8.4), or in 2-D
/// against a TARGE169 target (elements/target_line.h, chosen when its real set holds TARGE169
/// segments: UX, UY per node, no UZ). 3-D: one contact
/// node paired, through the shared real-constant set, with the target of that set
/// (elements/target_surface.h). Rigid target: the element's DOFs are the pilot node's and the
/// contact node's UX, UY, UZ (and the pilot's ROTX..ROTZ when it carries rotations). Deformable
/// target (no pilot): the contact node's, then those of the nodes of its candidate facets —
/// re-found between steps as it slides (large sliding, the default) or fixed at setup (small
/// sliding, KEYOPT(18) = 1). Within a step the list is fixed, so the pattern is static while
/// Newton iterates. Before each status
/// update the contact search finds the nearest target facet the node projects into (bucket
/// grid, within the pinball) and sets the normal and gap of the point law
/// (elements/contact_point.h: penalty / augmented Lagrange, Coulomb friction, KEYOPT(12)).
/// Detection is at the contact node (KEYOPT(4) = 0..3 all give nodal detection).
#include "elements/contact_point.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_line.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

constexpr const char* kNodeToSurfaceFamily = "NodeToSurfaceContact";

std::unique_ptr<Element> make_node_to_surface_contact(const ElementBuildContext& ctx,
                                                      const ElementRecord& record) {
  const Node& node = line_data::node(ctx.model, record, 0, 1, kNodeToSurfaceFamily);
  // 2-D when its real set's target is a TARGE169 (elements/target_line.h): UX, UY only.
  if (has_line_target(ctx.model, record.real))
    return line_target_point(ctx, record, node, kNodeToSurfaceFamily, "CONTA175", 1.0, 0.0);
  return target_point(ctx, record, node, kNodeToSurfaceFamily, "CONTA175", 1.0, 0.0);
}

const ElementRegistration kConta175{{.name = "CONTA175",
                                     .number = 175,
                                     .family = kNodeToSurfaceFamily,
                                     .n_nodes = 1,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Vertex,
                                     .role = ShapeRole::Contact,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_node_to_surface_contact}};

}  // namespace

}  // namespace impactfe
