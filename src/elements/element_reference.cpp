#include "elements/element_reference.h"

#include <fmt/format.h>

#include "elements/element_fields.h"

namespace impactfe {

namespace {

const char* role_name(ShapeRole role) {
  switch (role) {
    case ShapeRole::Solid:
      return "solid (a volume of material)";
    case ShapeRole::Plane:
      return "plane (an area of material in the X-Y plane: plane stress, plane strain or "
             "axisymmetric)";
    case ShapeRole::Shell:
      return "shell (a surface with a thickness)";
    case ShapeRole::Line:
      return "line (spar, beam or spring between two nodes)";
    case ShapeRole::Point:
      return "point (a mass at a node)";
    case ShapeRole::Gap:
      return "gap (acts between two bodies at a node pair)";
    case ShapeRole::Contact:
      return "contact side of a contact pair";
    case ShapeRole::Target:
      return "target side of a contact pair";
    case ShapeRole::Superelement:
      return "superelement (a reduced matrix on master nodes)";
  }
  return "?";
}

const char* real_constant_use(RealConstantUse use) {
  switch (use) {
    case RealConstantUse::None:
      return "none read";
    case RealConstantUse::Required:
      return "required (R)";
    case RealConstantUse::UnlessSection:
      return "required unless SECNUM names a section";
    case RealConstantUse::Optional:
      return "optional (R)";
  }
  return "?";
}

std::string joined(const std::vector<std::string>& items, const char* separator = " ") {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

std::string node_count(const ElementTypeDescriptor& t) {
  if (t.defined_by_file) return "given by the superelement file (SE)";
  std::string out = t.least_nodes() == t.n_nodes
                        ? fmt::format("{}", t.n_nodes)
                        : fmt::format("{} to {}", t.least_nodes(), t.n_nodes);
  if (t.n_optional_nodes > 0) out += fmt::format(", plus {} optional", t.n_optional_nodes);
  return out;
}

}  // namespace

std::string element_help(const ElementTypeDescriptor& t) {
  std::string out = fmt::format("### {}\n\n", t.name);
  out += fmt::format("- family: {}{}\n", t.family,
                     t.number > 0 ? fmt::format(" (ANSYS 4.2 type {})", t.number) : "");
  // A point role on a set of points (MESH200): a cell that joins nothing, drawn as its nodes.
  const bool mesh_only = t.role == ShapeRole::Point && t.vtk_cell == VtkCell::PolyVertex;
  out += fmt::format("- nodes: {}; role: {}\n", node_count(t),
                     mesh_only ? "mesh-only cell (drawn as its nodes; contributes nothing to the "
                                 "solution)"
                               : role_name(t.role));
  out += fmt::format("- real constants: {}; material: {}\n", real_constant_use(t.real_constants),
                     t.needs_material ? "required (MAT)" : "not read");
  if (!t.section_types.empty())
    out += fmt::format("- sections (SECTYPE): {}\n", joined(t.section_types, ", "));
  if (t.plasticity) out += "- plasticity: TB BISO, BKIN, MISO of its material\n";
  if (!t.faces.empty())
    out += fmt::format("- surface loads: {} face(s) by SFE, the first {} by SF\n", t.faces.size(),
                       t.sf_faces);
  if (t.has_status) out += "- status: open/closed or sticking/sliding, kept per substep\n";
  if (const ElementFields* f = element_fields(t.name)) {
    if (f->real_set_of_pair)
      out += "- real set: the contact pair's (read by the contact element)\n";
    if (!f->real_constants.empty()) {
      out += "- real constants read (a nonzero value at any other position is refused):";
      for (const auto& r : f->real_constants)
        out += fmt::format(" {} {}{}", r.position, r.name, r.refused ? " (refused)" : "");
      out += "\n";
    }
    out += "- KEYOPTs carried out (0, the default, always; other values are refused):";
    if (f->keyopts.empty()) out += " none";
    for (const auto& k : f->keyopts) {
      std::vector<std::string> values;
      for (int v : k.values) values.push_back(std::to_string(v));
      out += fmt::format("\n  - KEYOPT({}) = {} — {}", k.number, joined(values, ", "), k.meaning);
    }
    out += "\n";
  }
  if (!t.result_names.empty()) {
    // The element nodal values ITEM@k (node position k) are listed once, by their pattern.
    std::vector<std::string> items, nodal;
    for (const std::string& n : t.result_names) {
      const auto at = n.find('@');
      if (at == std::string::npos) {
        items.push_back(n);
      } else if (n.substr(at + 1) == "1") {
        nodal.push_back(n.substr(0, at));
      }
    }
    out += fmt::format("- result items: {}\n", joined(items));
    if (!nodal.empty())
      out += fmt::format("- element nodal values (ESOL with a NODE), per node position k: {}@k\n",
                         joined(nodal, "@k "));
  }
  if (!t.note.empty()) out += fmt::format("- note: {}\n", t.note);
  return out;
}

std::string element_reference_markdown() {
  std::string out =
      "## Elements\n\n"
      "Generated from the element registry and the declared element fields. An element type "
      "that is not listed stops the deck at its ET command.\n";
  for (const ElementTypeDescriptor* t : registered_element_types()) out += "\n" + element_help(*t);
  return out;
}

}  // namespace impactfe
