// Registration of SOLID45 and SOLID185 (the Brick8 element, elements/brick8.h): KEYOPT
// mapping to the element technology, material and plasticity reading.
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>

#include "core/errors.h"
#include "core/log.h"
#include "elements/brick8.h"
#include "elements/element_registry.h"

namespace impactfe {

const std::vector<ResultSequence>& solid_result_sequences() {
  // A function-local static: the registrations read it during static initialisation.
  static const std::vector<ResultSequence> sequences = {
      {"S", "X", "SX"},           {"S", "Y", "SY"},         {"S", "Z", "SZ"},
      {"S", "XY", "SXY"},         {"S", "YZ", "SYZ"},       {"S", "XZ", "SXZ"},
      {"S", "1", "S1"},           {"S", "2", "S2"},         {"S", "3", "S3"},
      {"S", "INT", "SINT"},       {"S", "EQV", "SEQV"},     {"EPPL", "X", "EPPLX"},
      {"EPPL", "Y", "EPPLY"},     {"EPPL", "Z", "EPPLZ"},   {"EPPL", "XY", "EPPLXY"},
      {"EPPL", "YZ", "EPPLYZ"},   {"EPPL", "XZ", "EPPLXZ"}, {"NL", "EPEQ", "EPEQ"},
      {"NL", "SEPL", "SEPL"},     {"NL", "SRAT", "SRAT"},   {"NL", "PLWK", "PLWK"},
      {"EPCR", "X", "EPCRX"},     {"EPCR", "Y", "EPCRY"},   {"EPCR", "Z", "EPCRZ"},
      {"EPCR", "XY", "EPCRXY"},   {"EPCR", "YZ", "EPCRYZ"}, {"EPCR", "XZ", "EPCRXZ"},
      {"EPCR", "EQV", "EPCREQV"}, {"NL", "CREQ", "CREQ"}};
  return sequences;
}

namespace {

/// SOLID45, or SOLID185 (`solid185`: its KEYOPT(2) selects the integration).
std::unique_ptr<Element> make_brick8(const ElementBuildContext& ctx, const ElementRecord& record,
                                     bool solid185) {
  const Model& model = ctx.model;
  if (record.nodes.size() != 8)
    throw InputError(record.where, fmt::format("element {}: an 8-node brick needs nodes I..P, "
                                               "got {} nodes",
                                               record.id, record.nodes.size()));
  std::array<int, 8> nodes{};
  std::array<Vec3, 8> x;
  for (int c = 0; c < 8; ++c) {
    nodes[c] = record.nodes[c];
    const auto it = model.nodes.find(nodes[c]);
    if (it == model.nodes.end())
      throw InputError(record.where,
                       fmt::format("element {}: node {} is not defined", record.id, nodes[c]));
    x[c] = it->second.x;
  }
  const auto type_it = model.element_types.find(record.type);
  if (type_it == model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  const ElementType& type = type_it->second;
  // SOLID45: KEYOPT(1) = 1 suppresses the extra shapes; KEYOPT(2) = 1 (1-point + hourglass) is
  // not implemented. SOLID185 KEYOPT(2): 0 B-bar, 2 enhanced strain, 3 simplified enhanced
  // strain (the incompatible modes); 1 (uniform reduced + hourglass) is not implemented
  // (docs/elements/solid45.md).
  const int k2 = type.key(2);
  const bool extra = solid185 ? k2 == 3 : type.key(1) != 1;
  BrickStrain strain = BrickStrain::Standard;
  if (solid185 && k2 == 0) strain = BrickStrain::BBar;
  if (solid185 && k2 == 2) strain = BrickStrain::Enhanced;
  const IsotropicElasticity material =
      read_isotropic_elasticity(model, record.mat, record.id, record.where);
  std::optional<J2Plasticity> plasticity =
      plasticity_of(model, record, material.young, material.poisson);
  std::string approximation;
  if (k2 == 1)
    approximation = fmt::format(
        "uniform reduced integration with hourglass control is not "
        "implemented: computed with full 2x2x2 Gauss{} (stiffer in "
        "bending than the reduced element)",
        extra ? " and incompatible modes" : ", no extra shapes");
  // A plastic brick under large deflection is finite-strain with B-bar (KEYOPT(2) = 0) and
  // refuses 2 and 3 (Brick8); the elastic one is total-Lagrangian without B-bar.
  else if (solid185 && (k2 == 0 || k2 == 2) && ctx.large_deflection && !plasticity)
    approximation = k2 == 0 ? "under large deflection (NLGEOM) B-bar is not implemented: "
                              "computed with full 2x2x2 Gauss (locks for nearly incompressible "
                              "material)"
                            : "under large deflection (NLGEOM) only the 9 incompatible modes "
                              "are used (simplified enhanced strain, KEYOPT(2) = 3)";
  else if (solid185 && k2 != 0 && k2 != 2 && k2 != 3)
    throw InputError(record.where,
                     fmt::format("element {}: SOLID185 KEYOPT(2) = {} is not a valid element "
                                 "technology (0 B-bar, 1 reduced, 2 enhanced strain, 3 "
                                 "simplified enhanced strain)",
                                 record.id, k2));
  if (!approximation.empty()) {
    // Warn once per element type: only for the first element of this type.
    const auto first = std::find_if(model.elements.begin(), model.elements.end(),
                                    [&](const auto& kv) { return kv.second.type == record.type; });
    if (first == model.elements.end() || first->first == record.id)
      Log::warn("element type {} ({} KEYOPT(2) = {}): {} (approximation)", record.type,
                solid185 ? "SOLID185" : "SOLID45", k2, approximation);
  }
  const bool creep = plasticity && plasticity->has_creep();
  const bool plastic = plasticity.has_value();
  auto brick = std::make_unique<Brick8>(record.id, nodes, x, material, extra, record.where,
                                        std::move(plasticity), ctx.large_deflection, strain);
  // Plasticity under large deflection is the finite-strain brick with B-bar (Brick8): no
  // internal strain parameters, no creep.
  if (plastic && ctx.large_deflection && brick->n_internal() > 0)
    throw InputError(record.where,
                     fmt::format("element {} ({}): large deflection (NLGEOM,ON) with a TB "
                                 "plasticity material is implemented for the brick with B-bar "
                                 "(SOLID185 KEYOPT(2) = 0, SOLID45 KEYOPT(1) = 1); the "
                                 "incompatible or enhanced strain modes (SOLID185 KEYOPT(2) = 2 "
                                 "or 3, SOLID45 KEYOPT(1) = 0) are not",
                                 record.id, solid185 ? "SOLID185" : "SOLID45"));
  if (creep && ctx.large_deflection)
    throw InputError(record.where, fmt::format("element {} ({}): creep (TB,CREEP) under large "
                                               "deflection (NLGEOM,ON) is not implemented",
                                               record.id, solid185 ? "SOLID185" : "SOLID45"));
  return brick;
}

ElementTypeDescriptor brick_type(const char* name, int number, bool solid185) {
  return {.name = name,
          .number = number,
          .family = "Brick8",
          .n_nodes = 8,
          .needs_material = true,
          .vtk_cell = VtkCell::Hexahedron,
          .role = ShapeRole::Solid,
          .result_names = brick8_result_names(),
          .result_sequences = solid_result_sequences(),
          .plasticity = true,
          .faces = brick8_faces(),
          .sf_faces = 6,
          .create = [solid185](const ElementBuildContext& ctx, const ElementRecord& record) {
            return make_brick8(ctx, record, solid185);
          }};
}

const ElementRegistration kSolid45{brick_type("SOLID45", 45, false)};
const ElementRegistration kSolid185{brick_type("SOLID185", 185, true)};

}  // namespace

}  // namespace impactfe
