#include "elements/element_registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "core/text.h"

namespace impactfe {

namespace {

/// Registered types by name. A function-local static: registrations run during static
/// initialisation of other translation units, in no fixed order.
std::map<std::string, ElementTypeDescriptor>& registry() {
  static std::map<std::string, ElementTypeDescriptor> types;
  return types;
}

/// A role's cell: material and masses have the dimension of their role; a gap acts between
/// two nodes; contact and target elements are points, lines (2-D) or faces.
bool role_fits_cell(ShapeRole role, int dimension) {
  switch (role) {
    case ShapeRole::Solid:
      return dimension == 3;
    case ShapeRole::Shell:
    case ShapeRole::Plane:
      return dimension == 2;
    case ShapeRole::Line:
    case ShapeRole::Gap:
      return dimension == 1;
    case ShapeRole::Point:
      // A mass at a node; or MESH200's cell, whose shape varies with KEYOPT(1): a set of points
      // (PolyVertex) to the pictures, joined to no degree of freedom.
      return dimension == 0 || dimension == -1;
    case ShapeRole::Contact:
    case ShapeRole::Target:
      return dimension >= 0 && dimension <= 2;
    case ShapeRole::Superelement:
      return dimension == -1;
  }
  return false;
}

}  // namespace

bool ElementTypeDescriptor::accepts_section(const std::string& type) const {
  return std::find(section_types.begin(), section_types.end(), type) != section_types.end();
}

void register_element_type(ElementTypeDescriptor d) {
  d.name = to_upper(d.name);
  IMPACTFE_CHECK(!d.name.empty() && d.create, "element type registered without name or factory");
  IMPACTFE_CHECK(d.defined_by_file || (d.n_nodes > 0 && d.least_nodes() <= d.n_nodes),
                 "element type " + d.name + " registered with an inconsistent node count");
  IMPACTFE_CHECK(role_fits_cell(d.role, d.topology().dimension),
                 "element type " + d.name + " registered with a shape role its cell does not have");
  for (const auto& face : d.faces)
    for (int p : face)
      IMPACTFE_CHECK(p >= 0 && p < d.n_nodes,
                     "element type " + d.name + " registered with a face node it does not have");
  for (const auto& [name, other] : registry()) {
    IMPACTFE_CHECK(name != d.name, "element type " + d.name + " registered twice");
    IMPACTFE_CHECK(d.number == 0 || other.number != d.number,
                   fmt::format("element types {} and {} share number {}", name, d.name, d.number));
  }
  registry().emplace(d.name, std::move(d));
}

ElementRegistration::ElementRegistration(ElementTypeDescriptor descriptor) {
  register_element_type(std::move(descriptor));
}

const ElementTypeDescriptor* find_element_type(const std::string& name_or_number) {
  const std::string key = to_upper(name_or_number);
  const auto it = registry().find(key);
  if (it != registry().end()) return &it->second;
  for (const auto& [name, d] : registry())
    if (d.number != 0 && key == std::to_string(d.number)) return &d;
  return nullptr;
}

const ElementTypeDescriptor& element_type_descriptor(const ElementType& type) {
  const ElementTypeDescriptor* d = find_element_type(type.ansys_name);
  IMPACTFE_CHECK(d != nullptr, "element type " + type.ansys_name + " is not registered");
  return *d;
}

std::vector<const ElementTypeDescriptor*> registered_element_types() {
  std::vector<const ElementTypeDescriptor*> out;
  for (const auto& [name, d] : registry()) out.push_back(&d);
  return out;
}

std::optional<ResultSequence> find_result_sequence(const ElementTypeDescriptor& type,
                                                   const std::string& item,
                                                   const std::string& comp) {
  const std::string i = to_upper(item), c = to_upper(comp);
  for (const auto& s : type.result_sequences)
    if (s.item == i && s.comp == c) return s;
  // A stored result name given directly (program extension: ETABLE,F,FORC).
  if (c.empty())
    for (const auto& n : type.result_names)
      if (n == i) return ResultSequence{i, "", n, 0.0};
  return std::nullopt;
}

std::string esys_refusal(const Model& model, const ElementRecord& record) {
  if (record.esys == 0) return {};
  const ElementTypeDescriptor& d = element_type_descriptor(model.element_type(record.type));
  if (!d.esys_axes) {
    std::string carried;
    for (const auto& [name, other] : registry())
      if (other.esys_axes) carried += (carried.empty() ? "" : ", ") + name;
    return fmt::format(
        "ESYS {}: {} takes its axes from its nodes (an element coordinate system "
        "is carried out for {} only)",
        record.esys, d.name, carried);
  }
  if (record.esys <= 10 || !model.coordinate_systems.has(record.esys))
    return fmt::format("ESYS {} is not a defined local coordinate system (LOCAL,{})", record.esys,
                       record.esys);
  return {};
}

Eigen::Matrix3d esys_axes_at(const Model& model, int esys, const Eigen::Vector3d& x) {
  Eigen::Matrix3d axes;
  model.coordinate_systems.get(esys).axes_at(x, axes);  // on a cylinder's axis: its own axes
  return axes;
}

std::string supported_element_type_names() {
  std::string out;
  for (const auto& [name, d] : registry()) out += (out.empty() ? "" : " ") + name;
  return out;
}

}  // namespace impactfe
