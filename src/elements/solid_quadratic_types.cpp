// The element types of the quadratic solids (elements/solid_quadratic.h): SOLID186 (20-node
// hexahedron and its degenerate tetrahedron) and SOLID187 (10-node tetrahedron), with the legacy
// SOLID95 and SOLID92 computed as them, their factories and registrations.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <set>

#include "core/errors.h"
#include "elements/brick8.h"
#include "elements/element_registry.h"
#include "elements/solid_quadratic.h"

namespace impactfe {

namespace {

/// MAPDL's face numbering of the bricks (SOLID185/186: 1 J-I-L-K, 2 I-J-N-M, 3 J-K-O-N,
/// 4 K-L-P-O, 5 L-I-M-P, 6 M-N-O-P) as corner positions of the hexahedron's outward faces
/// (elements/cell_topology.h: bottom, top, sides), the bottom read from J and the top last.
std::vector<std::vector<int>> brick_face_corners() {
  const auto& f = cell_topology(VtkCell::QuadraticHexahedron).faces;
  return {{f[0][3], f[0][0], f[0][1], f[0][2]}, f[2], f[3], f[4], f[5], f[1]};
}

/// Faces with their midside nodes (the face-node order of SFE: corners, then the midsides).
std::vector<std::vector<int>> with_midsides(VtkCell cell,
                                            const std::vector<std::vector<int>>& corners) {
  std::vector<std::vector<int>> out;
  for (const auto& c : corners) out.push_back(face_with_midsides(cell_topology(cell), c));
  return out;
}

const std::vector<std::vector<int>>& hex20_faces() {
  static const auto faces = with_midsides(VtkCell::QuadraticHexahedron, brick_face_corners());
  return faces;
}

/// SOLID187: 1 J-I-K, 2 I-J-L, 3 J-K-L, 4 K-I-L (the tetrahedron's faces).
const std::vector<std::vector<int>>& tet10_faces() {
  static const auto faces =
      with_midsides(VtkCell::QuadraticTetra, cell_topology(VtkCell::QuadraticTetra).faces);
  return faces;
}

std::vector<Vec3> coordinates(const Model& model, const ElementRecord& record,
                              const std::vector<int>& nodes) {
  std::vector<Vec3> x;
  for (int n : nodes) {
    const auto it = model.nodes.find(n);
    if (it == model.nodes.end())
      throw InputError(record.where,
                       fmt::format("element {}: node {} is not defined", record.id, n));
    x.push_back(it->second.x);
  }
  return x;
}

const ElementType& type_of(const Model& model, const ElementRecord& record) {
  const auto it = model.element_types.find(record.type);
  if (it == model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  return it->second;
}

/// A midside node left 0 (not given by EMORE, or MAPDL's straight edge without a node) is
/// refused: the element has no form with a missing midside node.
void require_all_nodes(const ElementRecord& record, const char* name, int n_nodes) {
  for (std::size_t k = 0; k < record.nodes.size(); ++k)
    if (record.nodes[k] == 0)
      throw InputError(record.where,
                       fmt::format("element {} ({}): midside node {} (of {}) is not given: "
                                   "omitted midside nodes (straight edges without a node) are "
                                   "not supported; give every node (E takes the first 8, "
                                   "EMORE the rest)",
                                   record.id, name, k + 1, n_nodes));
}

/// Large deflection (NLGEOM,ON) is the finite-strain form (solid_finite_strain.h), which has no
/// creep clock: creep under NLGEOM is refused.
void refuse_large_deflection_creep(const ElementBuildContext& ctx, const ElementRecord& record,
                                   const char* name, const std::optional<J2Plasticity>& law) {
  if (ctx.large_deflection && law && law->has_creep())
    throw InputError(record.where, fmt::format("element {} ({}): creep (TB,CREEP) under large "
                                               "deflection (NLGEOM,ON) is not implemented",
                                               record.id, name));
}

/// The degenerate tetrahedron of SOLID186 (K = L = S, M = N = O = P = U = V = W = X, A = B) as
/// the 10-node tetrahedron I J K M with midsides Q R T Y Z A; its brick faces mapped onto the
/// tetrahedron's (a face collapsed to an edge carries no load). Empty when the pattern differs.
std::optional<std::pair<std::vector<int>, std::vector<std::vector<int>>>> solid186_tetrahedron(
    const std::vector<int>& n) {
  const bool corners = n[2] == n[3] && n[4] == n[5] && n[4] == n[6] && n[4] == n[7] &&
                       std::set<int>{n[0], n[1], n[2], n[4]}.size() == 4;
  const bool midsides = n[10] == n[2] && n[12] == n[4] && n[13] == n[4] && n[14] == n[4] &&
                        n[15] == n[4] && n[19] == n[18];
  if (!corners || !midsides) return std::nullopt;
  const std::vector<int> tet = {n[0], n[1], n[2], n[4], n[8], n[9], n[11], n[16], n[17], n[18]};
  std::vector<std::vector<int>> faces;
  for (const auto& face : brick_face_corners()) {
    std::vector<int> positions;  // tetrahedron corners of the face, in the brick face's order
    for (int c : face) {
      const int p = static_cast<int>(
          std::find(tet.begin(), tet.begin() + 4, n[static_cast<std::size_t>(c)]) - tet.begin());
      if (std::find(positions.begin(), positions.end(), p) == positions.end())
        positions.push_back(p);
    }
    faces.push_back(positions.size() == 3
                        ? face_with_midsides(cell_topology(VtkCell::QuadraticTetra), positions)
                        : std::vector<int>{});
  }
  return std::make_pair(tet, faces);
}

/// The 20-node brick of SOLID186 (`name`) and of the legacy SOLID95, which has the same
/// serendipity shape functions and node order; `order` is the Gauss rule per direction.
std::unique_ptr<Element> make_brick20(const ElementBuildContext& ctx, const ElementRecord& record,
                                      const char* name, int order) {
  const Model& model = ctx.model;
  if (record.nodes.size() != 20)
    throw InputError(record.where, fmt::format("element {}: {} needs 20 nodes I..P, Q..B, got {}",
                                               record.id, name, record.nodes.size()));
  require_all_nodes(record, name, 20);
  const IsotropicElasticity material =
      read_isotropic_elasticity(model, record.mat, record.id, record.where);
  std::optional<J2Plasticity> law = plasticity_of(model, record, material.young, material.poisson);
  refuse_large_deflection_creep(ctx, record, name, law);
  const std::vector<int>& n = record.nodes;
  if (std::set<int>(n.begin(), n.begin() + 8).size() == 8) {
    return std::make_unique<QuadraticSolid>(
        record.id, QuadraticShape::Hex20, n, coordinates(model, record, n), material,
        gauss_cube(order), hex20_faces(), record.where, std::move(law), ctx.large_deflection);
  }
  if (const auto tet = solid186_tetrahedron(n))
    return std::make_unique<QuadraticSolid>(record.id, QuadraticShape::Tet10, tet->first,
                                            coordinates(model, record, tet->first), material,
                                            tetrahedron_4_point(), tet->second, record.where,
                                            std::move(law), ctx.large_deflection);
  throw InputError(
      record.where,
      fmt::format("element {}: {} with repeated corner nodes is taken only as the "
                  "tetrahedron (K = L = S, M = N = O = P = U = V = W = X, A = B); its wedge "
                  "(K = L, O = P) and pyramid (M = N = O = P) forms are not implemented "
                  "(mesh those regions with bricks or with SOLID187 tetrahedra)",
                  record.id, name));
}

std::unique_ptr<Element> make_solid186(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  // KEYOPT(2) = 0: uniform reduced integration (2x2x2), MAPDL's default; 1: full (3x3x3).
  return make_brick20(ctx, record, "SOLID186", type_of(ctx.model, record).key(2) == 1 ? 3 : 2);
}

/// SOLID95 with KEYOPT(11) = 0 (its default, 2x2x2 reduced integration) is SOLID186 with its
/// default KEYOPT(2) = 0; the 14-point rule (KEYOPT(11) = 1) is refused (element_fields.cpp).
std::unique_ptr<Element> make_solid95(const ElementBuildContext& ctx, const ElementRecord& record) {
  return make_brick20(ctx, record, "SOLID95", 2);
}

/// The 10-node tetrahedron of SOLID187 and of the legacy SOLID92 (same shape functions, node
/// order and 4-point rule).
std::unique_ptr<Element> make_tet10(const ElementBuildContext& ctx, const ElementRecord& record,
                                    const char* name) {
  if (record.nodes.size() != 10)
    throw InputError(record.where, fmt::format("element {}: {} needs 10 nodes I..R, got {}",
                                               record.id, name, record.nodes.size()));
  require_all_nodes(record, name, 10);
  const IsotropicElasticity material =
      read_isotropic_elasticity(ctx.model, record.mat, record.id, record.where);
  std::optional<J2Plasticity> law =
      plasticity_of(ctx.model, record, material.young, material.poisson);
  refuse_large_deflection_creep(ctx, record, name, law);
  return std::make_unique<QuadraticSolid>(record.id, QuadraticShape::Tet10, record.nodes,
                                          coordinates(ctx.model, record, record.nodes), material,
                                          tetrahedron_4_point(), tet10_faces(), record.where,
                                          std::move(law), ctx.large_deflection);
}

std::unique_ptr<Element> make_solid187(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  return make_tet10(ctx, record, "SOLID187");
}

std::unique_ptr<Element> make_solid92(const ElementBuildContext& ctx, const ElementRecord& record) {
  return make_tet10(ctx, record, "SOLID92");
}

ElementTypeDescriptor quadratic_solid_type(const char* name, int number, int n_nodes, VtkCell cell,
                                           const std::vector<std::vector<int>>& faces,
                                           ElementFactory create) {
  return {.name = name,
          .number = number,
          .family = "QuadraticSolid",
          .n_nodes = n_nodes,
          .needs_material = true,
          .vtk_cell = cell,
          .role = ShapeRole::Solid,
          .result_names = quadratic_solid_result_names(),
          .result_sequences = solid_result_sequences(),
          .plasticity = true,
          .faces = faces,
          .sf_faces = static_cast<int>(faces.size()),
          .create = std::move(create)};
}

const ElementRegistration kSolid186{quadratic_solid_type(
    "SOLID186", 186, 20, VtkCell::QuadraticHexahedron, hex20_faces(), make_solid186)};
const ElementRegistration kSolid187{quadratic_solid_type(
    "SOLID187", 187, 10, VtkCell::QuadraticTetra, tet10_faces(), make_solid187)};

/// The legacy quadratic solids of MAPDL (SOLID95 20-node brick, SOLID92 10-node tetrahedron),
/// written by old archives: the same elements as SOLID186 / SOLID187 (MAPDL's own migration
/// table maps them so), computed by the same kernel.
ElementTypeDescriptor legacy_quadratic_solid_type(ElementTypeDescriptor d, const char* note) {
  d.note = note;
  return d;
}

const ElementRegistration kSolid95{legacy_quadratic_solid_type(
    quadratic_solid_type("SOLID95", 95, 20, VtkCell::QuadraticHexahedron, hex20_faces(),
                         make_solid95),
    "SOLID95 is computed as SOLID186 with its default 2x2x2 reduced integration (SOLID95 "
    "KEYOPT(11) = 0)")};
const ElementRegistration kSolid92{legacy_quadratic_solid_type(
    quadratic_solid_type("SOLID92", 92, 10, VtkCell::QuadraticTetra, tet10_faces(), make_solid92),
    "SOLID92 is computed as SOLID187 (the same 10-node tetrahedron)")};

}  // namespace

}  // namespace impactfe
