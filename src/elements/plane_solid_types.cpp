// The element types of the 2-D structural solids (elements/plane_solid.h): PLANE182 (4-node
// quadrilateral, triangle K = L) and PLANE183 (8-node quadrilateral, 6-node triangle), their
// KEYOPTs, thickness, factories and registrations; the legacy PLANE42 and PLANE82 computed as
// them.
#include <fmt/format.h>

#include <set>
#include <string>

#include "core/errors.h"
#include "elements/element_fields.h"
#include "elements/element_registry.h"
#include "elements/plane_solid.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

namespace {

/// MAPDL's faces of the 2-D solids: 1 J-I, 2 K-J, 3 L-K, 4 I-L (each then its midside node).
std::vector<std::vector<int>> quad_faces(VtkCell cell) {
  const CellTopology& t = cell_topology(cell);
  std::vector<std::vector<int>> out;
  for (int k = 0; k < 4; ++k) {
    const int a = (k + 1) % 4, b = k;
    std::vector<int> face = {a, b};
    if (t.midside_nodes > 0) face.push_back(t.midside_of(a, b));
    out.push_back(face);
  }
  return out;
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

/// KEYOPT(3): behaviour and thickness. KEYOPT(3) = 3 reads the thickness from the element's
/// PLANE section (SECTYPE,,PLANE / SECDATA,THK) or else real constant 1 (THK).
PlaneSolidOptions behaviour_of(const Model& model, const ElementType& type,
                               const ElementRecord& record) {
  PlaneSolidOptions o;
  const int k3 = type.key(3);
  if (k3 == 1) o.behaviour = PlaneBehaviour::Axisymmetric;
  if (k3 == 2) o.behaviour = PlaneBehaviour::PlaneStrain;
  if (k3 != 3) return o;
  const auto section = model.sections.find(record.secnum);
  if (record.secnum > 0 && section != model.sections.end() && section->second.type == "PLANE" &&
      !section->second.data.empty()) {
    o.thickness = section->second.data[0];
    return o;
  }
  const auto real = model.real_sets.find(record.real);
  // Only here is the real set read: every other value given in it must be refused.
  if (real != model.real_sets.end())
    if (const std::string why = real_set_refusal(type, real->second); !why.empty())
      throw InputError(record.where, fmt::format("element {}: {}", record.id, why));
  const double thk = real == model.real_sets.end() ? 0.0 : real->second.get(1);
  if (!(thk > 0.0))
    throw InputError(record.where,
                     fmt::format("element {} ({}): KEYOPT(3) = 3 (plane stress with thickness) "
                                 "needs a positive thickness: real constant 1 THK of set {} or "
                                 "SECTYPE,,PLANE with SECDATA,THK",
                                 record.id, type.ansys_name, record.real));
  o.thickness = thk;
  return o;
}

/// Large deflection (NLGEOM,ON): the finite-strain form of full integration and B-bar
/// (plane_solid_finite.cpp). The enhanced strain and the reduced integration with hourglass
/// control have no finite-strain form here, nor has the creep law: refused.
void check_large_deflection(const ElementBuildContext& ctx, const ElementRecord& record,
                            const char* name, PlaneTechnology technology,
                            const std::optional<J2Plasticity>& plasticity) {
  if (!ctx.large_deflection) return;
  if (technology == PlaneTechnology::IncompatibleModes || technology == PlaneTechnology::Reduced)
    throw InputError(
        record.where,
        fmt::format("element {} ({}): large deflection (NLGEOM,ON) is implemented "
                    "for KEYOPT(1) = 0 (full integration, B-bar in plane strain and "
                    "axisymmetry); KEYOPT(1) = {} is not",
                    record.id, name, technology == PlaneTechnology::Reduced ? "1" : "2 or 3"));
  if (plasticity && plasticity->has_creep())
    throw InputError(record.where, fmt::format("element {} ({}): creep (TB,CREEP) under large "
                                               "deflection (NLGEOM,ON) is not implemented",
                                               record.id, name));
}

/// The 4-node quadrilateral (triangle K = L) of PLANE182 and of the legacy PLANE42 (`name`),
/// with its technology chosen from the type's KEYOPTs by the caller.
std::unique_ptr<Element> make_quad4(const ElementBuildContext& ctx, const ElementRecord& record,
                                    const char* name, PlaneTechnology technology) {
  const Model& model = ctx.model;
  const ElementType& type = model.element_types.at(record.type);
  PlaneSolidOptions o = behaviour_of(model, type, record);
  o.large_deflection = ctx.large_deflection;
  o.nodal_stresses = model.options.nodal_stresses;
  const IsotropicElasticity material =
      read_isotropic_elasticity(model, record.mat, record.id, record.where);
  std::optional<J2Plasticity> plasticity =
      plasticity_of(model, record, material.young, material.poisson);
  const std::vector<int>& n = record.nodes;
  if (n.size() == 4 && n[2] == n[3]) {
    check_large_deflection(ctx, record, name, PlaneTechnology::Standard, plasticity);
    // The triangle K = L: the constant-strain triangle I J K (MAPDL integrates it at one point).
    o.shape = PlaneShape::Tri3;
    const std::vector<int> tri = {n[0], n[1], n[2]};
    return std::make_unique<PlaneSolid>(
        record.id, tri, coordinates(model, record, tri), material, o,
        std::vector<std::vector<int>>{{1, 0}, {2, 1}, {}, {0, 2}}, record.where, plasticity);
  }
  o.shape = PlaneShape::Quad4;
  o.technology = technology;
  check_large_deflection(ctx, record, name, o.technology, plasticity);
  return std::make_unique<PlaneSolid>(record.id, n, coordinates(model, record, n), material, o,
                                      quad_faces(VtkCell::Quad), record.where, plasticity);
}

std::unique_ptr<Element> make_plane182(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  const Model& model = ctx.model;
  const ElementType& type = model.element_types.at(record.type);
  const bool plane_stress = type.key(3) == 0 || type.key(3) == 3;
  const int k1 = type.key(1);
  if (k1 == 2 && !plane_stress)
    throw InputError(record.where,
                     fmt::format("element {} (PLANE182): KEYOPT(1) = 2 (enhanced strain) in "
                                 "plane strain or axisymmetry needs the enhanced volumetric mode, "
                                 "which is not implemented; use 0 (B-bar) or 3",
                                 record.id));
  // KEYOPT(1) = 0: B-bar in plane strain and axisymmetry (in plane stress σzz = 0 leaves no
  // volumetric constraint to relieve: full 2x2). 2 (plane stress) and 3: incompatible modes.
  // 1: uniform reduced integration, the centre point with hourglass stabilisation.
  PlaneTechnology technology = PlaneTechnology::Standard;
  if (k1 == 0 && !plane_stress) technology = PlaneTechnology::BBar;
  if (k1 == 1) technology = PlaneTechnology::Reduced;
  if (k1 == 2 || k1 == 3) technology = PlaneTechnology::IncompatibleModes;
  return make_quad4(ctx, record, "PLANE182", technology);
}

/// PLANE42 (MAPDL's legacy 4-node solid): KEYOPT(2) = 0, its default, includes the extra
/// displacement shapes (incompatible modes, Wilson–Taylor: PLANE182's KEYOPT(1) = 3); 1
/// suppresses them (plain 2x2 Gauss). KEYOPT(3) as PLANE182's.
std::unique_ptr<Element> make_plane42(const ElementBuildContext& ctx, const ElementRecord& record) {
  const ElementType& type = ctx.model.element_types.at(record.type);
  return make_quad4(
      ctx, record, "PLANE42",
      type.key(2) == 1 ? PlaneTechnology::Standard : PlaneTechnology::IncompatibleModes);
}

/// The 8-node quadrilateral (6-node triangle K = L = O) of PLANE183 and of the legacy PLANE82
/// (`name`; the same shape functions, node order and 2x2 rule); only PLANE183 has the 6-node
/// triangle form KEYOPT(1) = 1.
std::unique_ptr<Element> make_quad8(const ElementBuildContext& ctx, const ElementRecord& record,
                                    const char* name) {
  const Model& model = ctx.model;
  const ElementType& type = model.element_types.at(record.type);
  PlaneSolidOptions o = behaviour_of(model, type, record);
  o.large_deflection = ctx.large_deflection;
  o.nodal_stresses = model.options.nodal_stresses;
  const std::vector<int>& n = record.nodes;
  for (std::size_t k = 0; k < n.size(); ++k)
    if (n[k] == 0)
      throw InputError(record.where,
                       fmt::format("element {} ({}): node {} is not given: midside nodes "
                                   "may not be omitted",
                                   record.id, name, k + 1));
  const IsotropicElasticity material =
      read_isotropic_elasticity(model, record.mat, record.id, record.where);
  std::optional<J2Plasticity> plasticity =
      plasticity_of(model, record, material.young, material.poisson);
  check_large_deflection(ctx, record, name, PlaneTechnology::Standard, plasticity);
  const bool triangle_form = std::string(name) == "PLANE183" && type.key(1) == 1;
  if (n[2] == n[3] && n[6] == n[2]) {
    // The triangle K = L = O: the 6-node triangle I J K with midsides M N P. Its I-K side is
    // face 4 (I-L) of the quadrilateral numbering, and face 3 of the 6-node form (KEYOPT(1) = 1).
    o.shape = PlaneShape::Tri6;
    const std::vector<int> tri = {n[0], n[1], n[2], n[4], n[5], n[7]};
    std::vector<std::vector<int>> faces = {{1, 0, 3}, {2, 1, 4}, {}, {0, 2, 5}};
    if (triangle_form) faces[2] = faces[3];
    return std::make_unique<PlaneSolid>(record.id, tri, coordinates(model, record, tri), material,
                                        o, faces, record.where, plasticity);
  }
  if (triangle_form)
    throw InputError(record.where,
                     fmt::format("element {} (PLANE183): KEYOPT(1) = 1 is the 6-node triangle, "
                                 "but the element has four corners (mesh with MSHAPE,1 or use "
                                 "KEYOPT(1) = 0)",
                                 record.id));
  if (std::set<int>(n.begin(), n.begin() + 4).size() != 4)
    throw InputError(record.where,
                     fmt::format("element {} ({}): repeated corners are taken only as the "
                                 "triangle K = L = O",
                                 record.id, name));
  o.shape = PlaneShape::Quad8;
  return std::make_unique<PlaneSolid>(record.id, n, coordinates(model, record, n), material, o,
                                      quad_faces(VtkCell::QuadraticQuad), record.where, plasticity);
}

std::unique_ptr<Element> make_plane183(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  return make_quad8(ctx, record, "PLANE183");
}

/// PLANE82 (MAPDL's legacy 8-node solid) is PLANE183's quadrilateral with its default 2x2 rule.
std::unique_ptr<Element> make_plane82(const ElementBuildContext& ctx, const ElementRecord& record) {
  return make_quad8(ctx, record, "PLANE82");
}

ElementTypeDescriptor plane_solid_type(const char* name, int number, int n_nodes, int min_nodes,
                                       VtkCell cell, ElementFactory create) {
  const auto faces = quad_faces(cell);
  return {.name = name,
          .number = number,
          .family = "PlaneSolid",
          .n_nodes = n_nodes,
          .min_nodes = min_nodes,
          .needs_material = true,
          .section_types = {"PLANE"},
          .vtk_cell = cell,
          .role = ShapeRole::Plane,
          .result_names = plane_solid_result_names(),
          .result_sequences =
              {{"S", "X", "SX"},           {"S", "Y", "SY"},       {"S", "Z", "SZ"},
               {"S", "XY", "SXY"},         {"S", "1", "S1"},       {"S", "2", "S2"},
               {"S", "3", "S3"},           {"S", "INT", "SINT"},   {"S", "EQV", "SEQV"},
               {"EPPL", "X", "EPPLX"},     {"EPPL", "Y", "EPPLY"}, {"EPPL", "Z", "EPPLZ"},
               {"EPPL", "XY", "EPPLXY"},   {"NL", "EPEQ", "EPEQ"}, {"NL", "SEPL", "SEPL"},
               {"NL", "SRAT", "SRAT"},     {"NL", "PLWK", "PLWK"}, {"EPCR", "X", "EPCRX"},
               {"EPCR", "Y", "EPCRY"},     {"EPCR", "Z", "EPCRZ"}, {"EPCR", "XY", "EPCRXY"},
               {"EPCR", "EQV", "EPCREQV"}, {"NL", "CREQ", "CREQ"}, {"EPEL", "X", "EPELX"},
               {"EPEL", "Y", "EPELY"},     {"EPEL", "Z", "EPELZ"}, {"EPEL", "XY", "EPELXY"}},
          .plasticity = true,
          .faces = faces,
          .sf_faces = 4,
          .create = std::move(create)};
}

const ElementRegistration kPlane182{
    plane_solid_type("PLANE182", 182, 4, 3, VtkCell::Quad, make_plane182)};
// The legacy forms: PLANE42 as PLANE182 (incompatible modes by default), PLANE82 as PLANE183.
const ElementRegistration kPlane42{[] {
  ElementTypeDescriptor d = plane_solid_type("PLANE42", 42, 4, 3, VtkCell::Quad, make_plane42);
  d.note =
      "PLANE42 is computed as PLANE182: KEYOPT(2) = 0 (its default) with incompatible modes "
      "(PLANE182 KEYOPT(1) = 3), 1 plain 2x2 Gauss";
  return d;
}()};
const ElementRegistration kPlane82{[] {
  ElementTypeDescriptor d =
      plane_solid_type("PLANE82", 82, 8, 6, VtkCell::QuadraticQuad, make_plane82);
  d.note = "PLANE82 is computed as PLANE183 (the same 8-node shape functions and 2x2 rule)";
  return d;
}()};
const ElementRegistration kPlane183{[] {
  ElementTypeDescriptor d =
      plane_solid_type("PLANE183", 183, 8, 6, VtkCell::QuadraticQuad, make_plane183);
  d.triangle_form_keyopt = 1;
  return d;
}()};

}  // namespace

}  // namespace impactfe
