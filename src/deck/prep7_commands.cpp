// PREP7 model commands: element types, real constants, sections, nodes, elements,
// attribute pointers, master DOFs, gap conditions, superelements and the 4x KAN/KAY keys.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "core/dof.h"
#include "core/log.h"
#include "deck/deck_context.h"
#include "deck/modeling_helpers.h"
#include "elements/element_registry.h"
#include "elements/section_types.h"

namespace impactfe::deck {

namespace {

// ---- element types ---------------------------------------------------------------------------

void cmd_et(DeckReader& r, const Command& c) {
  int id = 0;
  if (c.blank(1)) {
    id = r.model.element_types.empty() ? 1 : r.model.element_types.rbegin()->first + 1;
  } else {
    id = r.integer(c, 1, 1);
  }
  if (id <= 0) r.fail(c, fmt::format("element type number {} must be positive", id));
  if (c.blank(2)) r.fail(c, "element name or number missing");
  std::string name = trim(c.text(2));
  const ElementTypeDescriptor* info = find_element_type(name);
  if (info == nullptr) {
    // A parameter gives the name or the number (ET,1,ETYP with ETYP = 182 or 'PLANE182').
    const Param* p = r.params.find(to_upper(name));
    if (p != nullptr && p->type == ParamType::Number)
      name = fmt::format("{}", std::lround(p->number));
    else if (p != nullptr && p->type == ParamType::Text)
      name = r.text_field(c, 2);
    if (p != nullptr) info = find_element_type(name);
  }
  if (info == nullptr)
    r.fail(c, fmt::format("unknown element type '{}' (supported: {})", name,
                          supported_element_type_names()));
  ElementType et;
  et.id = id;
  et.ansys_name = info->name;
  et.where = c.where;
  for (int k = 1; k <= 6; ++k) et.keyopt[static_cast<std::size_t>(k)] = r.integer(c, k + 2, 0);
  // Field 9 is INOPR (print suppression): ignored. Fields 10..12 (4x OCR, §3.4) → KEYOPT(7..9).
  for (int f = 10; f <= c.n_fields(); ++f) {
    if (c.blank(f)) continue;
    if (r.dialect == Dialect::Classic4x && f <= 12) {
      et.keyopt[static_cast<std::size_t>(f - 3)] = r.integer(c, f, 0);
      r.warn(c, fmt::format("field {} stored as KEYOPT({}) = {} (4x position, uncertain)", f, f - 3,
                            r.integer(c, f, 0)));
    } else {
      r.warn(c, fmt::format("field {} ('{}') ignored", f, c.text(f)));
    }
  }
  if (!info->note.empty()) r.warn(c, info->note);
  r.model.element_types[id] = et;
}

void cmd_keyopt(DeckReader& r, const Command& c) {
  const int id = r.integer(c, 1, 0);
  auto it = r.model.element_types.find(id);
  if (it == r.model.element_types.end())
    r.fail(c, fmt::format("element type {} is not defined", id));
  const int k = r.integer(c, 2, 0);
  if (k < 1 || k > 18) r.fail(c, fmt::format("KEYOPT number {} out of range 1..18", k));
  it->second.keyopt[static_cast<std::size_t>(k)] = r.integer(c, 3, 0);
}

// ---- real constants ----------------------------------------------------------------------------

void cmd_r(DeckReader& r, const Command& c) {
  const auto id = r.opt_int(c, 1);
  if (!id || *id <= 0) r.fail(c, "real constant set number missing or not positive");
  RealSet set;
  set.id = *id;
  for (int f = 2; f <= c.last_given(); ++f) set.values.push_back(r.real(c, f, 0.0));
  r.model.real_sets[*id] = set;
  r.modeling.last_real_set = *id;
}

void cmd_rmore(DeckReader& r, const Command& c) {
  auto it = r.model.real_sets.find(r.modeling.last_real_set);
  if (it == r.model.real_sets.end()) r.fail(c, "RMORE without a preceding R");
  auto& v = it->second.values;
  const std::size_t start = ((v.size() + 5) / 6) * 6;  // next block of six (R7.., R13.., ...)
  if (c.last_given() == 0) return;
  v.resize(start, 0.0);
  for (int f = 1; f <= c.last_given(); ++f) v.push_back(r.real(c, f, 0.0));
}

void cmd_rmodif(DeckReader& r, const Command& c) {
  const int id = r.integer(c, 1, 0);
  auto it = r.model.real_sets.find(id);
  if (it == r.model.real_sets.end())
    r.fail(c, fmt::format("real constant set {} is not defined", id));
  const int start = r.integer(c, 2, 0);
  if (start <= 0) r.fail(c, "STLOC must be positive");
  auto& v = it->second.values;
  for (int f = 3; f <= c.last_given(); ++f) {
    if (c.blank(f)) continue;
    const std::size_t pos = static_cast<std::size_t>(start + f - 4);
    if (v.size() <= pos) v.resize(pos + 1, 0.0);
    v[pos] = r.real(c, f, 0.0);
  }
}

// ---- sections ---------------------------------------------------------------------------------

void cmd_sectype(DeckReader& r, const Command& c) {
  // SECID blank or 0: one above the highest section id defined (SECTYPE notes).
  int id = r.integer(c, 1, 0);
  if (id < 0) r.fail(c, fmt::format("section id {}: a section id is positive", id));
  if (id == 0) id = r.model.sections.empty() ? 1 : r.model.sections.rbegin()->first + 1;
  const std::string type = r.label(c, 2);
  const SectionTypeDescriptor* d = find_section_type(type);
  if (d == nullptr)
    r.fail(c, fmt::format("section type '{}' not supported ({})", c.text(2),
                          supported_section_type_names()));
  Section s;
  s.id = id;
  s.type = type;
  if (!d->subtypes.empty()) {
    s.subtype = c.blank(3) ? d->subtypes.front() : r.label(c, 3);
    if (!d->accepts_subtype(s.subtype))
      r.fail(c, fmt::format("{} subtype {} not supported ({})", to_lower(type), s.subtype,
                            d->subtype_names()));
  }
  r.model.sections[id] = s;
  r.modeling.last_section = id;
}

void cmd_secdata(DeckReader& r, const Command& c) {
  auto it = r.model.sections.find(r.modeling.last_section);
  if (it == r.model.sections.end()) r.fail(c, "SECDATA without a preceding SECTYPE");
  Section& s = it->second;
  const SectionTypeDescriptor& d = *find_section_type(s.type);
  if (d.single_secdata && !s.data.empty())
    r.fail(c, "only one SECDATA (a single homogeneous layer) is supported");
  const int given =
      d.max_values > 0 ? std::min(c.last_given(), d.max_values) : std::max(1, c.last_given());
  std::vector<double> values;
  for (int f = 1; f <= given; ++f) values.push_back(r.real(c, f, 0.0));
  if (d.layered) {
    // SECDATA,TK,MAT,THETA,NUMPT,LayerName: a layer on top of the previous ones. The layer
    // name (field 5) only labels the layer; the program refers to layers by number.
    if (c.last_given() > 5) r.fail(c, "fields after LayerName (field 5) are not shell layer data");
    s.layers.push_back(values);
    if (s.layers.size() == 1) s.data = values;
  } else {
    s.data = values;
  }
  try {
    const std::string note = d.check_data(s);
    if (!note.empty()) Log::info("{}:{}: SECDATA: {}", c.where.file, c.where.line, note);
  } catch (const std::invalid_argument& e) {
    r.fail(c, e.what());
  }
}

// SECOFFSET,Location: the locations the section type accepts (beams CENT, the node on the
// centroid; shells MID, BOT, TOP). Other locations would move the nodes off the section's reference
// and are refused (APDL_MODELING §7.4).
void cmd_secoffset(DeckReader& r, const Command& c) {
  auto it = r.model.sections.find(r.modeling.last_section);
  if (it == r.model.sections.end()) r.fail(c, "SECOFFSET without a preceding SECTYPE");
  std::string loc = c.blank(1) ? "" : r.label(c, 1);
  // Workbench writes the whole words (secoff,bottom); MAPDL reads them as BOT and MID.
  if (loc == "BOTTOM") loc = "BOT";
  if (loc == "MIDDLE") loc = "MID";
  const std::string& type = it->second.type;
  const SectionTypeDescriptor& d = *find_section_type(type);
  if (!d.offsets.empty() &&
      (loc.empty() || std::find(d.offsets.begin(), d.offsets.end(), loc) != d.offsets.end())) {
    it->second.offset = loc;
    return;
  }
  r.fail(c, fmt::format("location '{}' is not supported for a {} section ({} only)", c.text(1),
                        type, d.offset_names()));
}

// SECCONTROL: overrides of the last section's computed properties. BEAM: VAL1 TXZ and VAL3 TXY
// the transverse shear stiffnesses kGA (force) of the x-z and x-y planes, VAL4 ADDMAS the mass
// per length; blank or 0 keeps the computed value (VAL2 is unused). Other section types (shell
// transverse shear E11 E22 E12, link ADDMAS and TENSKEY): all fields blank keeps the computed
// section, which is carried out; a value given is refused.
void cmd_seccontrol(DeckReader& r, const Command& c) {
  const auto sec = r.model.sections.find(r.modeling.last_section);
  if (sec == r.model.sections.end()) r.fail(c, "SECCONTROL without a preceding SECTYPE");
  if (sec->second.type == "BEAM") {
    if (c.last_given() > 4) r.fail(c, "a BEAM section takes TXZ, -, TXY and ADDMAS (4 fields)");
    if (!c.blank(2))
      r.fail(c, fmt::format("field 2 ('{}') is unused for a BEAM section", c.text(2)));
    std::vector<double> v(4, 0.0);
    for (int f : {1, 3, 4}) {
      v[static_cast<std::size_t>(f - 1)] = r.real(c, f, 0.0);
      if (v[static_cast<std::size_t>(f - 1)] < 0.0)
        r.fail(c, fmt::format("field {} ({}): must not be negative", f,
                              f == 1   ? "TXZ"
                              : f == 3 ? "TXY"
                                       : "ADDMAS"));
    }
    sec->second.controls = v;
    return;
  }
  for (int f = 1; f <= c.last_given(); ++f)
    if (!c.blank(f))
      r.fail(c, fmt::format("field {} ('{}'): {} section overrides are not carried out (all "
                            "fields blank: the computed section; BEAM sections take TXZ, TXY, "
                            "ADDMAS)",
                            f, c.text(f), sec->second.type));
}

void cmd_secnum(DeckReader& r, const Command& c) {
  r.modeling.current_secnum = r.integer(c, 1, 1);
}

// ---- nodes and elements ------------------------------------------------------------------------

/// N on an existing node redefines it, as in MAPDL, and the elements on it follow. A deck that
/// numbers a new node inside a mesh it did not expect to be that fine (vme2: N,1000 after a VMESH
/// of 2304 nodes) moves a meshed node without a word otherwise.
void warn_moved_node(DeckReader& r, const Command& c, const Node& old, const Vec3& x) {
  // Only the first ten moves are looked up (a scan of the elements each), so that a deck moving
  // many nodes of a large mesh on purpose stays linear.
  if ((old.x - x).norm() == 0.0 || ++r.modeling.moved_nodes_checked > 10) return;
  int attached = 0, first = 0;
  for (const auto& [id, e] : r.model.elements)
    if (std::find(e.nodes.begin(), e.nodes.end(), old.id) != e.nodes.end() && attached++ == 0)
      first = id;
  if (attached == 0) return;
  r.warn(c, fmt::format("node {} is redefined: moved from ({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}) "
                        "with the {} element(s) on it (first: element {})",
                        old.id, old.x.x(), old.x.y(), old.x.z(), x.x(), x.y(), x.z(), attached,
                        first));
}

void cmd_n(DeckReader& r, const Command& c) {
  // N,R5.3,LOC,-1 (R5.1 alike) ends an NBLOCK in a CDB archive; other R5 records are not read.
  if (const std::string form = r.label(c, 1); form.rfind("R5.", 0) == 0) {
    if (r.label(c, 2) == "LOC" && r.integer(c, 3, 0) == -1) return;
    r.fail(c, fmt::format("the CDB node record form {} is not supported (NBLOCK is)", form));
  }
  int id = 0;
  if (c.blank(1))
    id = r.model.nodes.empty() ? 1 : r.model.nodes.rbegin()->first + 1;
  else
    id = r.integer(c, 1, 0);
  if (id <= 0) r.fail(c, fmt::format("node number {} must be positive", id));
  if (r.model.nodes.count(id) == 0) check_model_size(r, c, 1, 0);
  Node n;
  n.id = id;
  // X, Y, Z in the active coordinate system (APDL_MODELING §2.2); angles relative to global.
  n.x = r.model.coordinate_systems.active_system().to_global(
      Vec3(r.real(c, 2, 0.0), r.real(c, 3, 0.0), r.real(c, 4, 0.0)));
  n.angles_deg = Vec3(r.real(c, 5, 0.0), r.real(c, 6, 0.0), r.real(c, 7, 0.0));
  if (const auto old = r.model.nodes.find(id); old != r.model.nodes.end())
    warn_moved_node(r, c, old->second, n.x);
  r.model.nodes[id] = n;
  r.modeling.defined_by_n.push_back(id);
}

void cmd_nmodif(DeckReader& r, const Command& c) {
  // NMODIF,NODE,X,Y,Z,THXY,THYZ,THZX: moves existing nodes (a number, ALL for the selected ones,
  // or a node component) and sets their rotation angles; X, Y, Z in the active coordinate
  // system, a blank field keeps the node's value (APDL_MODELING §2.2, as N).
  if (c.blank(1)) r.fail(c, "NODE missing (a node number, ALL or a component)");
  const std::vector<int> ids = component_or_entity_list(r, c, 1, 0, 0, "NODE", r.model.nodes,
                                                        r.model.selection.nodes, "node");
  const CoordinateSystem& cs = r.model.coordinate_systems.active_system();
  for (int id : ids) {
    const auto it = r.model.nodes.find(id);
    if (it == r.model.nodes.end()) r.fail(c, fmt::format("node {} is not defined", id));
    Node& n = it->second;
    Vec3 local = cs.from_global(n.x);
    for (int k = 0; k < 3; ++k) local(k) = r.real(c, 2 + k, local(k));
    n.x = cs.to_global(local);
    for (int k = 0; k < 3; ++k) n.angles_deg(k) = r.real(c, 5 + k, n.angles_deg(k));
  }
}

void cmd_ndele(DeckReader& r, const Command& c) {
  // NDELE,NODE1,NODE2,NINC: deletes nodes no element uses (NODE1 = ALL: the selected ones, or a
  // node component). A node an element uses stays, with a warning that counts them, as MAPDL
  // deletes only free nodes. A node that carries a constraint, load, initial condition,
  // temperature, coupling, constraint equation or master DOF, or belongs to a meshed
  // solid-model entity, is refused: deleting it would leave those pointing at nothing.
  if (c.blank(1)) r.fail(c, "NODE1 missing (a node number, ALL or a component)");
  const std::vector<int> ids = component_or_entity_list(r, c, 1, 2, 3, "NODE", r.model.nodes,
                                                        r.model.selection.nodes, "node");
  std::set<int> used;
  for (const auto& [id, e] : r.model.elements) used.insert(e.nodes.begin(), e.nodes.end());
  std::set<int> referenced;
  const LoadStep& loads = r.model.current;
  for (const auto* dofs : {&loads.constraints, &loads.forces})
    for (const auto& [k, v] : *dofs) referenced.insert(k.node);
  for (const auto& [k, v] : r.model.initial_conditions) referenced.insert(k.node);
  for (const auto& [n, t] : loads.node_temperatures) referenced.insert(n);
  for (const auto& k : r.model.masters) referenced.insert(k.node);
  for (const auto& [id, set] : r.model.coupled_sets)
    referenced.insert(set.nodes.begin(), set.nodes.end());
  for (const auto& [id, eq] : r.model.constraint_equations)
    for (const auto& t : eq.terms) referenced.insert(t.dof.node);
  const SolidModel& solid = r.model.solid;
  for (const auto& [id, k] : solid.keypoints) referenced.insert(k.node);
  for (const auto& [id, l] : solid.lines) referenced.insert(l.nodes.begin(), l.nodes.end());
  for (const auto& [id, a] : solid.areas) {
    referenced.insert(a.grid.nodes.begin(), a.grid.nodes.end());
    referenced.insert(a.interior_nodes.begin(), a.interior_nodes.end());
  }
  for (const auto& [id, v] : solid.volumes)
    referenced.insert(v.interior_nodes.begin(), v.interior_nodes.end());
  int kept = 0;
  for (int id : ids) {
    if (used.count(id) != 0) {
      ++kept;
      continue;
    }
    if (referenced.count(id) != 0)
      r.fail(c, fmt::format("node {} carries loads, constraints, couplings or a solid-model "
                            "mesh; delete those first (DDELE, FDELE, ...)",
                            id));
    r.model.nodes.erase(id);
    r.model.selection.nodes.forget(id);
  }
  if (kept > 0)
    r.warn(c,
           fmt::format("{} of the {} nodes are used by elements and were kept", kept, ids.size()));
}

void cmd_edele(DeckReader& r, const Command& c) {
  // EDELE,IEL1,IEL2,INC: deletes elements (IEL1 = ALL: the selected ones, or an element
  // component), their face pressures with them; they leave the solid-model entities that
  // meshed them. Their nodes stay (NDELE deletes free nodes).
  if (c.blank(1)) r.fail(c, "IEL1 missing (an element number, ALL or a component)");
  const std::vector<int> ids = component_or_entity_list(r, c, 1, 2, 3, "ELEM", r.model.elements,
                                                        r.model.selection.elements, "element");
  const std::set<int> gone(ids.begin(), ids.end());
  for (int id : ids) {
    r.model.elements.erase(id);
    r.model.selection.elements.forget(id);
  }
  auto& pressures = r.model.current.pressures;
  for (auto it = pressures.begin(); it != pressures.end();)
    it = gone.count(it->first.element) != 0 ? pressures.erase(it) : std::next(it);
  const auto drop = [&](std::vector<int>& elements) {
    std::erase_if(elements, [&](int e) { return gone.count(e) != 0; });
  };
  SolidModel& solid = r.model.solid;
  for (auto& [id, k] : solid.keypoints) drop(k.elements);
  for (auto& [id, l] : solid.lines) drop(l.elements);
  for (auto& [id, a] : solid.areas) drop(a.elements);
  for (auto& [id, v] : solid.volumes) drop(v.elements);
}

std::vector<int> node_fields(DeckReader& r, const Command& c, int first) {
  std::vector<int> nodes;
  const int last = c.last_given();
  for (int f = first; f <= last; ++f) nodes.push_back(r.integer(c, f, 0));
  return nodes;
}

int next_element_id(const DeckReader& r) {
  return r.model.elements.empty() ? 1 : r.model.elements.rbegin()->first + 1;
}

bool active_type_is_matrix50(const DeckReader& r) {
  auto it = r.model.element_types.find(r.modeling.current_type);
  return it != r.model.element_types.end() && element_type_descriptor(it->second).defined_by_file;
}

void add_superelement(DeckReader& r, const Command& c, int id, const std::string& file) {
  ElementRecord rec;
  rec.id = id;
  rec.type = r.modeling.current_type;
  rec.real = r.modeling.current_real;
  rec.mat = r.modeling.current_mat;
  rec.secnum = r.modeling.current_secnum;
  rec.esys = r.modeling.esys;
  rec.superelement_file = file;
  rec.where = c.where;
  if (r.model.elements.count(id) == 0) r.modeling.element_order.push_back(id);
  r.model.elements[id] = rec;
}

void cmd_e(DeckReader& r, const Command& c) {
  if (active_type_is_matrix50(r)) {
    if (r.dialect != Dialect::Classic4x)
      r.fail(c, "the active type is MATRIX50: define the superelement with SE,File");
    // 4x (§3.10): E,id,unit reads the superelement written to Fortran unit `unit`.
    const int id = r.integer(c, 1, next_element_id(r));
    const auto unit = r.opt_int(c, 2);
    if (!unit) r.fail(c, "MATRIX50: superelement file unit (field 2) missing");
    r.warn(c, fmt::format("MATRIX50 element {} reads superelement file unit {} (4x E,id,unit)", id,
                          *unit));
    add_superelement(r, c, id, fmt::format("unit:{}", *unit));
    return;
  }
  if (c.last_given() == 0) r.fail(c, "node list missing");
  check_model_size(r, c, 0, 1);
  std::vector<int> nodes = node_fields(r, c, 1);
  check_target_shape(r, c, nodes);
  r.add_element(c, next_element_id(r), std::move(nodes));
}

void cmd_en(DeckReader& r, const Command& c) {
  // EN,R5.5,ATTR,-1 ends the element records of a CDB archive after its EBLOCK (as
  // N,R5.3,LOC,-1 ends the nodes); other R5 records are not read.
  if (const std::string form = r.label(c, 1); form.rfind("R5.", 0) == 0) {
    if (r.label(c, 2) == "ATTR" && r.integer(c, 3, 0) == -1) return;
    r.fail(c, fmt::format("the CDB element record form {} is not supported (EBLOCK is)", form));
  }
  const auto id = r.opt_int(c, 1);
  if (!id) r.fail(c, "element number missing");
  if (c.last_given() < 2) r.fail(c, "node list missing");
  if (r.model.elements.count(*id) == 0) check_model_size(r, c, 0, 1);
  std::vector<int> nodes = node_fields(r, c, 2);
  check_target_shape(r, c, nodes);
  r.add_element(c, *id, std::move(nodes));
}

void cmd_emore(DeckReader& r, const Command& c) {
  // EMORE,Q,R,S,T,U,V,W,X: the next nodes of the element last defined by E / EN.
  const auto e = r.model.elements.find(r.modeling.emore_element);
  if (e == r.model.elements.end()) r.fail(c, "no element defined by E or EN before EMORE");
  std::vector<int>& nodes = e->second.nodes;
  for (int f = 1; f <= c.last_given(); ++f, ++r.modeling.emore_position) {
    const int node = r.integer(c, f, 0);
    if (r.modeling.emore_position >= static_cast<int>(nodes.size())) {
      // A type whose node count varies (MESH200: 2 to 20 by KEYOPT(1)) takes them up to its most.
      const auto type = r.model.element_types.find(e->second.type);
      const int most = type == r.model.element_types.end()
                           ? 0
                           : element_type_descriptor(type->second).max_nodes();
      if (r.modeling.emore_position >= most)
        r.fail(c, fmt::format("element {} has {} nodes: EMORE gives more", e->first, nodes.size()));
      nodes.resize(static_cast<std::size_t>(r.modeling.emore_position) + 1, 0);
    }
    if (node < 0) r.fail(c, fmt::format("node {} is not positive", node));
    if (node > 0) r.require_node(c, node);
    nodes[static_cast<std::size_t>(r.modeling.emore_position)] = node;
  }
}

void cmd_se(DeckReader& r, const Command& c) {
  if (!active_type_is_matrix50(r)) r.fail(c, "the active element TYPE must be MATRIX50");
  if (c.blank(1)) r.fail(c, "superelement file name missing");
  add_superelement(r, c, next_element_id(r), c.text(1));
}

void cmd_type(DeckReader& r, const Command& c) {
  r.modeling.current_type = r.integer(c, 1, 1);
}
void cmd_real(DeckReader& r, const Command& c) {
  r.modeling.current_real = r.integer(c, 1, 1);
}
void cmd_mat(DeckReader& r, const Command& c) {
  r.modeling.current_mat = r.integer(c, 1, 1);
}

/// MPCHG,MAT,ELEM: gives element ELEM (a number, or ALL: the selected elements) material MAT.
/// The material is checked when the elements are solved. In /SOLU between the load steps of one
/// analysis the change is refused by that analysis's next SOLVE (an analysis keeps the model of
/// its first SOLVE); between analyses (FINISH, /PREP7, MPCHG, /SOLU) it acts on the next one.
void cmd_mpchg(DeckReader& r, const Command& c) {
  const auto mat = r.opt_int(c, 1);
  if (!mat) r.fail(c, "MAT (the material number) missing");
  if (*mat <= 0) r.fail(c, fmt::format("material number {} must be positive", *mat));
  if (c.blank(2)) r.fail(c, "ELEM missing (an element number, or ALL for the selected elements)");
  const std::vector<int> ids =
      entity_list(r, c, 2, 0, 0, r.model.elements, r.model.selection.elements, "element");
  for (int id : ids) r.model.elements.at(id).mat = *mat;
  Log::info("{}:{}: MPCHG: {} element{} now of material {}", c.where.file, c.where.line, ids.size(),
            ids.size() == 1 ? "" : "s", *mat);
}

void cmd_emodif(DeckReader& r, const Command& c) {
  // EMODIF,IEL,STLOC,I1: sets attributes of elements (a number, ALL for the selected ones, or a
  // component), as Workbench input files assign their layered sections. STLOC MAT, TYPE, REAL,
  // SECNUM or ESYS (0, or a local system > 10) sets that one to I1 (MAT, TYPE, REAL, SECNUM:
  // 1 when I1 is 0 or blank, MAPDL's default); STLOC 0 or blank sets all five to the current
  // pointers (TYPE, MAT, REAL, SECNUM, ESYS). Node replacement (STLOC a node position) is refused.
  if (c.blank(1)) r.fail(c, "IEL missing (an element number, ALL or a component)");
  const std::string what = c.blank(2) ? "0" : r.label(c, 2);
  const bool all_attributes = what == "0";
  int value = r.integer(c, 3, 0);
  if (value < 0) r.fail(c, fmt::format("I1 {} must not be negative", value));
  if (what == "ESYS") {
    check_esys_number(r, c, value);
  } else if (what == "MAT" || what == "TYPE" || what == "REAL" || what == "SECNUM") {
    if (value == 0) value = 1;
  } else if (!all_attributes) {
    r.fail(c, fmt::format("STLOC '{}': MAT, TYPE, REAL, SECNUM, ESYS or 0 (changing the nodes of "
                          "an element is not supported)",
                          c.text(2)));
  }
  const int type = all_attributes ? r.modeling.current_type : value;
  if ((what == "TYPE" || all_attributes) && r.model.element_types.count(type) == 0)
    r.fail(c, fmt::format("element type {} is not defined", type));
  const std::vector<int> ids = component_or_entity_list(r, c, 1, 0, 0, "ELEM", r.model.elements,
                                                        r.model.selection.elements, "element");
  for (int id : ids) {
    if (r.model.elements.count(id) == 0) continue;  // a component's element deleted since
    ElementRecord& e = r.model.elements.at(id);
    if (all_attributes) {
      e.type = r.modeling.current_type;
      e.mat = r.modeling.current_mat;
      e.real = r.modeling.current_real;
      e.secnum = r.modeling.current_secnum;
      e.esys = r.modeling.esys;
      continue;
    }
    if (what == "MAT") e.mat = value;
    if (what == "TYPE") e.type = value;
    if (what == "REAL") e.real = value;
    if (what == "SECNUM") e.secnum = value;
    if (what == "ESYS") e.esys = value;
  }
  if (what == "SECNUM") r.modeling.secnum_given = true;
}

// ---- masters and gaps ------------------------------------------------------------------------

void cmd_m(DeckReader& r, const Command& c) {
  // M,NODE,Lab1,NEND,NINC,Lab2..Lab6,SUPPORT
  int end_field = 3;
  int inc_field = 4;
  const std::vector<Dof> dofs = parse_dof_labels(r, c, 2, end_field, inc_field, 5, 9);
  for (int node : r.node_range(c, 1, end_field, inc_field)) {
    for (Dof d : dofs) {
      const DofKey key{node, d};
      if (std::find(r.model.masters.begin(), r.model.masters.end(), key) == r.model.masters.end())
        r.model.masters.push_back(key);
      r.model.master_where[key] = c.where;
    }
  }
}

void cmd_total(DeckReader& r, const Command& c) {
  const auto n = r.opt_int(c, 1);
  if (!n || *n < 0) r.fail(c, "NTOT missing or negative");
  r.model.options.total_masters = *n;
  r.model.options.total_masters_exclude_rotations = r.integer(c, 2, 0) == 1;
}

void cmd_gp(DeckReader& r, const Command& c) {
  GapCondition g;
  g.node_i = r.integer(c, 1, 0);
  g.node_j = r.integer(c, 2, 0);
  if (g.node_i <= 0 || g.node_j <= 0) r.fail(c, "NODE1 and NODE2 must be positive node numbers");
  if (g.node_i == g.node_j) r.fail(c, fmt::format("NODE1 and NODE2 are both node {}", g.node_i));
  // A gap node that is not defined is a ground point (MAPDL GP: "grounded gap nodes need not
  // appear elsewhere in the model"); it is stored as node 0, which renumbering leaves alone.
  const bool ground_i = r.model.nodes.count(g.node_i) == 0;
  const bool ground_j = r.model.nodes.count(g.node_j) == 0;
  if (ground_i && ground_j)
    r.fail(c, fmt::format("neither node {} nor node {} is defined (one end may be a ground point, "
                          "not both)",
                          g.node_i, g.node_j));
  if (ground_i || ground_j)
    Log::info("{}:{}: GP: node {} is not defined: a ground point", c.where.file, c.where.line,
              ground_i ? g.node_i : g.node_j);
  if (ground_i) g.node_i = 0;
  if (ground_j) g.node_j = 0;
  const std::string lab = r.label(c, 3);
  auto d = parse_force_label(lab);
  if (!d) d = parse_dof_label(lab);
  if (!d) r.fail(c, fmt::format("bad gap direction label '{}' (FX FY FZ MX MY MZ)", c.text(3)));
  g.dof = *d;
  const auto stif = r.opt_real(c, 4);
  if (!stif) r.fail(c, "gap stiffness STIF missing");
  g.stiffness = *stif;
  g.gap = r.real(c, 5, 0.0);
  g.damping = r.real(c, 6, 0.0);
  g.where = c.where;
  r.model.gap_conditions.push_back(g);
}

// ---- 4x analysis keys -------------------------------------------------------------------------

/// Applies the stored KAY values with the meaning they have under the current KAN (§3.3).
void apply_kay(DeckReader& r, const Command& c, int key, int value, bool log) {
  AnalysisOptions& o = r.model.options;
  switch (key) {
    case 1:
      o.lumped_mass = value == 1;
      return;
    case 5:
      r.model.current.time_integration = value != 0;
      return;
    case 6:
      if (r.solution.kan == 7)
        o.superelement_matrices = value;
      else
        o.large_deflection = value == 1;
      return;
    case 8:
      o.stress_stiffening = value == 1;
      return;
    default:
      if (log)
        r.warn(c, fmt::format("KAY({}) = {} has no known meaning; stored and ignored", key, value));
  }
}

void cmd_kan(DeckReader& r, const Command& c) {
  const int kan = r.integer(c, 1, 0);
  AnalysisOptions& o = r.model.options;
  switch (kan) {
    case 0:
      o.type = AnalysisType::Static;
      break;
    case 2:
      o.type = AnalysisType::Modal;
      break;
    case 4:
      o.type = AnalysisType::Transient;
      o.method = TransientMethod::Full;
      break;
    case 5:
      o.type = AnalysisType::Transient;
      o.method = TransientMethod::Reduced;
      break;
    case 7:
      o.type = AnalysisType::Substructure;
      break;
    case 1:
    case 3:
    case 6:
    case 8:
      r.fail(c, fmt::format("KAN={} ({}) is not supported; supported: 0 static, 2 modal, 4 full "
                            "transient, 5 reduced transient, 7 substructure",
                            kan,
                            kan == 1   ? "buckling"
                            : kan == 3 ? "harmonic"
                            : kan == 6 ? "reduced harmonic"
                                       : "spectrum"));
    default:
      r.fail(c, fmt::format("unknown analysis type KAN={}", kan));
  }
  o.integrator = IntegratorKind::Houbolt;
  r.solution.kan = kan;
  for (const auto& [key, value] : o.kay) apply_kay(r, c, std::stoi(key), value, false);
}

void cmd_kay(DeckReader& r, const Command& c) {
  const auto key = r.opt_int(c, 1);
  if (!key || *key <= 0) r.fail(c, "key number missing");
  const int value = r.integer(c, 2, 0);
  r.model.options.kay[std::to_string(*key)] = value;
  apply_kay(r, c, *key, value, true);
  Log::info("{}:{}: KAY({}) = {}", c.where.file, c.where.line, *key, value);
}

}  // namespace

void register_prep7_commands(std::vector<CommandSpec>& t) {
  t.push_back({"ET", cmd_et, kPrep7});
  t.push_back({"KEYOPT", cmd_keyopt, kPrep7});
  t.push_back({"R", cmd_r, kPrep7});
  t.push_back({"RMORE", cmd_rmore, kPrep7});
  t.push_back({"RMODIF", cmd_rmodif, kPrep7 | kSolu});
  t.push_back({"SECTYPE", cmd_sectype, kPrep7});
  t.push_back({"SECDATA", cmd_secdata, kPrep7});
  t.push_back({"SECNUM", cmd_secnum, kPrep7});
  t.push_back({"SECOFFSET", cmd_secoffset, kPrep7});
  t.push_back({"SECCONTROL", cmd_seccontrol, kPrep7});
  t.push_back({"N", cmd_n, kPrep7});
  t.push_back({"NMODIF", cmd_nmodif, kPrep7});
  t.push_back({"NDELE", cmd_ndele, kPrep7});
  t.push_back({"E", cmd_e, kPrep7});
  t.push_back({"EN", cmd_en, kPrep7});
  t.push_back({"EMORE", cmd_emore, kPrep7});
  t.push_back({"SE", cmd_se, kPrep7});
  t.push_back({"TYPE", cmd_type, kPrep7});
  t.push_back({"REAL", cmd_real, kPrep7});
  t.push_back({"MAT", cmd_mat, kPrep7});
  t.push_back({"MPCHG", cmd_mpchg, kPrep7 | kSolu});
  t.push_back({"EMODIF", cmd_emodif, kPrep7});
  t.push_back({"EDELE", cmd_edele, kPrep7});
  t.push_back({"M", cmd_m, kPrep7 | kSolu});
  t.push_back({"TOTAL", cmd_total, kPrep7 | kSolu});
  t.push_back({"GP", cmd_gp, kPrep7 | kSolu});
  t.push_back({"KAN", cmd_kan, kPrep7});
  t.push_back({"KAY", cmd_kay, kPrep7});
}

}  // namespace impactfe::deck
