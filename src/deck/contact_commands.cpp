// Contact-pair generation (APDL_MODELING §4.5 ESURF, §8.4 contact pairs): ESURF overlays target
// facets (TARGE170), contact faces (CONTA174), 2-D target segments (TARGE169) and contact lines
// (CONTA171/172) on plane elements' edges, or contact nodes (CONTA175) of the current
// TYPE/REAL/MAT on the exterior
// faces of the selected elements; TSHAP sets the shape of the TARGE170 elements E defines next.
#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "deck/deck_context.h"
#include "elements/element_registry.h"
#include "geometry/element_faces.h"

namespace impactfe::deck {

namespace {

int next_element_number(const DeckReader& r) {
  return r.model.elements.empty() ? 1 : r.model.elements.rbegin()->first + 1;
}

const std::string& current_type_name(DeckReader& r, const Command& c) {
  const auto it = r.model.element_types.find(r.modeling.current_type);
  if (it == r.model.element_types.end())
    r.fail(c, fmt::format("element type {} is not defined (ET missing before TYPE)",
                          r.modeling.current_type));
  return it->second.ansys_name;
}

/// ESURF,XNODE,Tlab,Shape (APDL_MODELING §4.5): the exterior faces of the selected elements whose
/// nodes are all selected (the SF,ALL face rule: a face shared by two selected elements is
/// interior) get elements of the current TYPE/REAL/MAT/SECNUM:
/// * TARGE170: one target facet per face, in the face-node order of the underlying element, whose
///   right-hand-rule normal points out of a solid (brick faces) — towards the contact bodies of a
///   target meshed on the top of a ground body [A]; Tlab = BOTTOM reverses it;
/// * CONTA174: one contact face per face, nodes as for TARGE170;
/// * TARGE169, CONTA171/172 (2-D): one segment / line per exterior edge of the selected plane
///   elements, its nodes I, J counter-clockwise around the element, so that the 2-D target
///   normal points out of the body (Tlab = BOTTOM reverses it); quadratic edges are refused;
/// * CONTA175: one contact element per node of those faces, each node once, skipping nodes that
///   already carry a CONTA175 element of the current TYPE and REAL (a repeated ESURF adds none).
void cmd_esurf(DeckReader& r, const Command& c) {
  if (!c.blank(1)) r.fail(c, "XNODE (field 1) is not supported: leave it blank");
  if (!c.blank(3)) r.fail(c, "Shape (field 3) is not supported: leave it blank");
  const std::string tlab = r.label(c, 2);
  if (!tlab.empty() && tlab != "TOP" && tlab != "BOTTOM")
    r.fail(c, fmt::format("Tlab must be TOP (default) or BOTTOM, not {}", c.text(2)));
  const std::string name = current_type_name(r, c);
  // By shape role and cell (elements/element_registry.h): target facets, contact faces or
  // contact nodes.
  const ElementTypeDescriptor* type = find_element_type(name);
  const ShapeRole role = type != nullptr ? type->role : ShapeRole::Point;
  const int dimension = type != nullptr ? type->topology().dimension : -1;
  const bool target = role == ShapeRole::Target;
  const bool surface = role == ShapeRole::Contact && dimension >= 1;
  if (!target && !surface && !(role == ShapeRole::Contact && dimension == 0))
    r.fail(c, fmt::format("the current TYPE {} is {}: ESURF generates TARGE170 target facets, "
                          "CONTA174 contact faces, TARGE169 target segments, CONTA171/172 "
                          "contact lines or CONTA175 contact nodes",
                          r.modeling.current_type, name));
  // A 2-D type (a line cell: TARGE169, CONTA171/172) goes on the edges of plane elements, a
  // 3-D one on the faces of solids and shells; CONTA175 on either.
  const bool planar = dimension == 1;
  const auto on_plane = [&](int element) {
    const auto t = r.model.element_types.find(r.model.elements.at(element).type);
    return t != r.model.element_types.end() &&
           element_type_descriptor(t->second).role == ShapeRole::Plane;
  };
  const ModelSelection& sel = r.model.selection;
  auto faces = geometry::faces_on_nodes(
      r.model, [&](int n) { return sel.nodes.selected(n); },
      [&](int e) { return sel.elements.selected(e); });
  if (target || surface)
    faces.erase(std::remove_if(faces.begin(), faces.end(),
                               [&](const FaceKey& f) { return on_plane(f.element) != planar; }),
                faces.end());
  if (faces.empty())
    r.fail(c, fmt::format("no exterior {} of the selected elements has all its nodes selected "
                          "(select the nodes of the surface and the elements under it, e.g. NSEL "
                          "then ESLN,S,0){}",
                          planar ? "edge" : "face",
                          !target && !surface ? ""
                          : planar            ? ": a 2-D TYPE takes the edges of plane elements"
                                   : ": a 3-D TYPE takes the faces of solids and shells"));

  std::vector<std::vector<int>> created;
  if (target || surface) {
    for (const FaceKey& f : faces) {
      std::vector<int> nodes;
      for (int n : geometry::element_face_nodes(r.model, r.model.elements.at(f.element), f.face))
        if (std::find(nodes.begin(), nodes.end(), n) == nodes.end()) nodes.push_back(n);
      if (planar) {
        // A plane element's edge is stored J, I (then its midside node): I, J runs
        // counter-clockwise around the body, whose 2-D target normal (t_y, −t_x) points out.
        if (nodes.size() > 2)
          r.fail(c, fmt::format("element {} has a midside node on the edge: {} on quadratic "
                                "edges (parabolic segments, midside contact nodes) is not "
                                "implemented; use linear elements (PLANE182) under the contact",
                                f.element, name));
        if (tlab != "BOTTOM") std::reverse(nodes.begin(), nodes.end());
      } else if (tlab == "BOTTOM") {
        std::reverse(nodes.begin(), nodes.end());
      }
      created.push_back(std::move(nodes));
    }
  } else {
    std::set<int> nodes;
    for (const FaceKey& f : faces)
      for (int n : geometry::element_face_nodes(r.model, r.model.elements.at(f.element), f.face))
        nodes.insert(n);
    for (const auto& [id, e] : r.model.elements)
      if (e.type == r.modeling.current_type && e.real == r.modeling.current_real &&
          e.nodes.size() == 1)
        nodes.erase(e.nodes.front());
    for (int n : nodes) created.push_back({n});
  }
  if (created.empty()) {
    r.warn(c, fmt::format("every node of the {} selected faces already carries a {} of TYPE {} "
                          "and REAL {}: no element generated",
                          faces.size(), name, r.modeling.current_type, r.modeling.current_real));
    return;
  }
  check_model_size(r, c, 0, static_cast<long long>(created.size()));
  const int first = next_element_number(r);
  checked_number(r, c, static_cast<long long>(first) + static_cast<long long>(created.size()) - 1,
                 "element");
  for (std::size_t k = 0; k < created.size(); ++k)
    r.add_element(c, first + static_cast<int>(k), created[k]);
  Log::info("{}:{}: ESURF: {} {} elements {} to {} (TYPE {}, REAL {}, MAT {}) on {} faces",
            c.where.file, c.where.line, created.size(), name, first,
            first + static_cast<int>(created.size()) - 1, r.modeling.current_type,
            r.modeling.current_real, r.modeling.current_mat, faces.size());
}

/// TSHAP,Shape (APDL_MODELING §8.4): the shape of the TARGE170/TARGE169 elements that E/EN
/// define next. impactfe's targets are faceted: TRIA (3 nodes) and QUAD (4) for TARGE170, LINE
/// (2, a straight 2-D segment) for TARGE169, and PILO (the pilot node, 1) for both [A: the spec
/// rejects PILO; impactfe targets move with their pilot node, so accepting it is what MAPDL
/// decks need]. MAPDL reads the first four characters (TSHAP,PILOT is PILO). Blank: back to the
/// shape from the node count.
void cmd_tshap(DeckReader& r, const Command& c) {
  const std::string shape = r.label(c, 1).substr(0, 4);
  if (shape.empty() || shape == "TRIA" || shape == "QUAD" || shape == "PILO" || shape == "LINE") {
    r.modeling.target_shape = shape;
    return;
  }
  if (shape == "PARA" || shape == "ARC" || shape == "CARC" || shape == "CIRC")
    r.fail(c, fmt::format("{}: curved 2-D (TARGE169) target segments are not implemented (mesh "
                          "the target with straight TSHAP,LINE segments)",
                          shape));
  if (shape == "TRI6" || shape == "QUA8")
    r.fail(c, fmt::format("{}: higher-order target facets are not implemented (use TRIA or QUAD)",
                          shape));
  if (shape == "CYLI" || shape == "CONE" || shape == "SPHE" || shape == "POIN")
    r.fail(c, fmt::format("{}: analytic rigid primitives are not implemented (mesh the target "
                          "with TRIA or QUAD facets, or LINE segments in 2-D, and a PILO node)",
                          shape));
  r.fail(c, fmt::format("unknown target shape {} (TRIA, QUAD, LINE or PILO)", c.text(1)));
}

}  // namespace

void check_target_shape(DeckReader& r, const Command& c, const std::vector<int>& nodes) {
  const std::string& shape = r.modeling.target_shape;
  if (shape.empty()) return;
  const auto it = r.model.element_types.find(r.modeling.current_type);
  if (it == r.model.element_types.end() ||
      element_type_descriptor(it->second).role != ShapeRole::Target)
    return;
  std::size_t given = nodes.size();
  while (given > 0 && nodes[given - 1] == 0) --given;
  const std::size_t wanted = shape == "PILO" ? 1 : shape == "LINE" ? 2 : shape == "TRIA" ? 3 : 4;
  const bool line = element_type_descriptor(it->second).topology().dimension == 1;
  if (line != (shape == "LINE") && shape != "PILO")
    r.fail(c, fmt::format("TSHAP,{} is a {} target shape and the current TYPE {} is {}", shape,
                          shape == "LINE" ? "2-D (TARGE169)" : "3-D (TARGE170)",
                          r.modeling.current_type, it->second.ansys_name));
  if (given != wanted)
    r.fail(c, fmt::format("TSHAP,{} makes a {} of {} node{}, {} given", shape,
                          it->second.ansys_name, wanted, wanted == 1 ? "" : "s", given));
}

void register_contact_commands(std::vector<CommandSpec>& t) {
  t.push_back({"ESURF", cmd_esurf, kPrep7});
  t.push_back({"TSHAP", cmd_tshap, kPrep7});
}

}  // namespace impactfe::deck
