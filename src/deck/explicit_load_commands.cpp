// Loads by curve and contact of explicit dynamics (MAPDL Command Reference release 18.2, the
// ANSYS LS-DYNA interface; docs/explicit_dynamics.md): EDCURVE, EDLOAD, EDCGEN, EDCMORE, EDDC,
// EDCLIST. They fill Model::explicit_dynamics; the explicit run (src/explicit) carries them out.
// What is not carried out (other load labels, other contact options) is refused here.
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "core/log.h"
#include "deck/deck_context.h"
#include "deck/lexer.h"
#include "deck/parameters.h"

namespace impactfe::deck {

namespace {

/// A curve's points: strictly increasing abscissae, the shorter length of the two arrays.
void check_curve(DeckReader& r, const Command& c, std::vector<double>& x, std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  x.resize(n);
  y.resize(n);
  if (n == 0) r.fail(c, "the curve has no points");
  for (std::size_t i = 1; i < n; ++i)
    if (!(x[i] > x[i - 1]))
      r.fail(c, fmt::format("abscissa {} ({:g}) is not above the one before ({:g}): the times of "
                            "a curve increase",
                            i + 1, x[i], x[i - 1]));
}

void cmd_edcurve(DeckReader& r, const Command& c) {
  // EDCURVE,Option,LCID,Par1,Par2
  const std::string option = r.label(c, 1).empty() ? "ADD" : r.label(c, 1);
  auto& curves = r.model.explicit_dynamics.curves;
  const auto lcid = r.opt_int(c, 2);
  if (option == "LIST") {
    for (const auto& [id, curve] : curves)
      if (!lcid || *lcid == id)
        Log::info("EDCURVE: curve {}: {} points, x {:g} .. {:g}", id, curve.x.size(),
                  curve.x.front(), curve.x.back());
    return;
  }
  if (option == "DELE") {
    if (lcid)
      curves.erase(*lcid);
    else
      curves.clear();
    return;
  }
  if (option != "ADD") r.fail(c, fmt::format("Option '{}': ADD, DELE or LIST", c.text(1)));
  if (!lcid || *lcid <= 0) r.fail(c, "LCID: the curve number is a positive integer");
  ExplicitCurve curve;
  curve.x = array_column(r, c, 3, "Par1");
  curve.y = array_column(r, c, 4, "Par2");
  check_curve(r, c, curve.x, curve.y);
  curve.where = c.where;
  curves[*lcid] = std::move(curve);
}

const std::set<std::string> kLoadLabels = {
    "FX",   "FY",   "FZ",   "VX",   "VY",   "VZ",   "UX",   "UY",   "UZ",   "ROTX", "ROTY",
    "ROTZ", "OMGX", "OMGY", "OMGZ", "ACLX", "ACLY", "ACLZ", "RBFX", "RBFY", "RBFZ", "RBMX",
    "RBMY", "RBMZ", "RBVX", "RBVY", "RBVZ", "RBUX", "RBUY", "RBUZ", "PRESS"};
const std::set<std::string> kRefusedLabels = {"MX",   "MY",   "MZ",   "AX",   "AY",   "AZ",  "TEMP",
                                              "RBRX", "RBRY", "RBRZ", "RBOX", "RBOY", "RBOZ"};

/// MAPDL's face numbering of SOLID164 (as SOLID185: 1 J-I-L-K, 2 I-J-N-M, 3 J-K-O-N, 4 K-L-P-O,
/// 5 L-I-M-P, 6 M-N-O-P, each counterclockwise seen from outside), read backwards: a positive
/// pressure pushes into the element, along the right-hand normal of the reversed order.
constexpr int kBrickFacesInward[6][4] = {{2, 3, 0, 1}, {4, 5, 1, 0}, {5, 6, 2, 1},
                                         {6, 7, 3, 2}, {7, 4, 0, 3}, {7, 6, 5, 4}};

/// EDLOAD PRESS: the loaded faces of an element component, 4 node numbers per face ordered so
/// that a positive pressure acts along their right-hand normal. SOLID164: KEY 1..6 (into the
/// element); SHELL163: KEY 1 (bottom, along +N, the I-J-K-L normal) or 2 (top, along −N), the
/// faces of MAPDL's element reference. A triangle repeats its third node.
std::vector<int> pressure_faces(DeckReader& r, const Command& c, const std::string& name,
                                const Component& comp, int key) {
  std::vector<int> faces;
  for (int id : comp.ids) {
    const auto e = r.model.elements.find(id);
    if (e == r.model.elements.end())
      r.fail(c, fmt::format("element {} of component {} no longer exists", id, name));
    const auto t = r.model.element_types.find(e->second.type);
    const std::string type = t == r.model.element_types.end() ? "" : t->second.ansys_name;
    const std::vector<int>& n = e->second.nodes;
    if (type == "SOLID164") {
      if (key < 1 || key > 6)
        r.fail(c,
               fmt::format("KEY {}: SOLID164 (element {}) has the pressure faces 1 to 6", key, id));
      for (int a : kBrickFacesInward[key - 1]) faces.push_back(n.at(static_cast<std::size_t>(a)));
    } else if (type == "SHELL163") {
      if (key != 1 && key != 2)
        r.fail(c, fmt::format("KEY {}: the pressure on SHELL163 (element {}) acts on face 1 "
                              "(bottom, along +N) or 2 (top, along -N); its edge faces are not "
                              "implemented",
                              key, id));
      const int l = n.size() > 3 ? n[3] : n[2];  // a triangle (K = L)
      if (key == 1)
        faces.insert(faces.end(), {n[0], n[1], n[2], l});
      else
        faces.insert(faces.end(), {l, n[2], n[1], n[0]});
    } else {
      r.fail(c, fmt::format("element {} of component {} is a {}: EDLOAD PRESS loads SOLID164 "
                            "and SHELL163",
                            id, name, type.empty() ? "element of no type" : type));
    }
  }
  if (faces.empty()) r.fail(c, fmt::format("component {} has no elements", name));
  return faces;
}

/// The rigid body a rigid-body load (RBFX ...) acts on: Cname is a part number (EDPART) whose
/// material is rigid (EDMP,RIGID); the nodes of the part's elements (ascending), and the
/// part's material in `material`.
std::vector<int> rigid_part_nodes(DeckReader& r, const Command& c, const std::string& lab,
                                  int& material) {
  const ExplicitPart part = explicit_part(r, c, 4, "Cname");
  if (r.model.explicit_dynamics.rigid_materials.count(part.mat) == 0)
    r.fail(c, fmt::format("PART {} (material {}) is not rigid: {} acts on a rigid body "
                          "(EDMP,RIGID,{})",
                          part.number, part.mat, lab, part.mat));
  material = part.mat;
  std::set<int> nodes;
  for (int id : part.elements)
    for (int n : r.model.elements.at(id).nodes)
      if (n > 0) nodes.insert(n);
  return {nodes.begin(), nodes.end()};
}

void list_loads(const std::vector<ExplicitCurveLoad>& loads, const std::string& lab,
                const std::string& cname) {
  int number = 0;
  for (const auto& l : loads) {
    ++number;
    if ((!lab.empty() && l.label != lab) || (!cname.empty() && l.component != cname)) continue;
    Log::info("EDLOAD: load {}: {} on {} ({} nodes), {} points, scale {:g}, birth {:g}, death {:g}",
              number, l.label, l.component, l.nodes.size(), l.times.size(), l.scale, l.birth,
              l.death);
  }
}

void cmd_edload(DeckReader& r, const Command& c) {
  // EDLOAD,Option,Lab,KEY,Cname,Par1,Par2,PHASE,LCID,SCALE,BTIME,DTIME
  const std::string option = r.label(c, 1).empty() ? "ADD" : r.label(c, 1);
  const std::string lab = r.label(c, 2);
  const std::string cname = r.label(c, 4);
  auto& loads = r.model.explicit_dynamics.loads;
  if (option == "LIST") return list_loads(loads, lab, cname);
  if (option == "DELE") {
    std::erase_if(loads, [&](const ExplicitCurveLoad& l) {
      return (lab.empty() || l.label == lab) && (cname.empty() || l.component == cname);
    });
    return;
  }
  if (option != "ADD") r.fail(c, fmt::format("Option '{}': ADD, DELE or LIST", c.text(1)));
  if (kRefusedLabels.count(lab))
    r.fail(c, fmt::format("Lab {}: not implemented in explicit dynamics; EDLOAD carries out the "
                          "nodal forces FX, FY, FZ, the prescribed velocities VX, VY, VZ and "
                          "displacements UX, UY, UZ, the rotations ROTX.. and angular velocities "
                          "OMGX.. (shell and "
                          "beam nodes), the base accelerations ACLX, ACLY, ACLZ, "
                          "the pressure PRESS and, on rigid bodies, the forces RBFX, RBFY, RBFZ, "
                          "moments RBMX, RBMY, RBMZ, "
                          "velocities RBVX, RBVY, RBVZ and displacements RBUX, RBUY, RBUZ",
                          lab));
  if (!kLoadLabels.count(lab)) r.fail(c, fmt::format("Lab '{}': not an EDLOAD label", c.text(2)));
  const bool pressure = lab == "PRESS", rigid = lab.rfind("RB", 0) == 0;
  if (!pressure && r.real(c, 3, 0.0) != 0.0)
    r.fail(c, "KEY: a local coordinate system for the load is not implemented (global axes)");
  if (r.real(c, 7, 0.0) != 0.0)
    r.fail(c, "PHASE: loads in a stress initialization phase are not implemented (PHASE 0 only)");
  ExplicitCurveLoad load;
  load.label = lab;
  load.component = cname;
  if (rigid) {
    load.nodes = rigid_part_nodes(r, c, lab, load.part_material);
  } else {
    const auto it = r.model.components.find(cname);
    if (cname.empty() || it == r.model.components.end())
      r.fail(c, fmt::format("Cname '{}': no such component (CM); EDLOAD {} takes {} component",
                            c.text(4), lab, pressure ? "an element" : "a node"));
    const std::string entity = pressure ? "ELEM" : "NODE";
    if (it->second.entity != entity)
      r.fail(c, fmt::format("Cname {} is a {} component; EDLOAD {} takes {} component", cname,
                            it->second.entity, lab, pressure ? "an element" : "a node"));
    load.nodes = pressure
                     ? pressure_faces(r, c, cname, it->second, c.blank(3) ? 1 : r.integer(c, 3, 1))
                     : it->second.ids;
  }
  if (const auto lcid = r.opt_int(c, 8); lcid && *lcid != 0) {
    const auto& curves = r.model.explicit_dynamics.curves;
    const auto curve = curves.find(*lcid);
    if (curve == curves.end())
      r.fail(c, fmt::format("LCID {}: no such curve (EDCURVE,ADD)", *lcid));
    load.times = curve->second.x;
    load.values = curve->second.y;
  } else {
    load.times = array_column(r, c, 5, "Par1");
    load.values = array_column(r, c, 6, "Par2");
    check_curve(r, c, load.times, load.values);
  }
  load.scale = r.real(c, 9, 1.0);
  if (c.blank(9)) load.scale = 1.0;
  load.birth = r.real(c, 10, 0.0);
  load.death = r.real(c, 11, 0.0);
  if (load.death != 0.0 && load.death <= load.birth)
    r.fail(c, fmt::format("DTIME {:g} is not after BTIME {:g}", load.death, load.birth));
  load.where = c.where;
  // A load of the same label on the same component (and faces) is redefined, not added (the
  // VM's vme3 redefines its load so between two solutions).
  for (auto it = loads.begin(); it != loads.end();)
    if (it->label == load.label && it->component == load.component &&
        (!pressure || it->nodes == load.nodes)) {
      Log::info("{}:{}: EDLOAD: the {} load on {} of line {} is replaced", c.where.file,
                c.where.line, load.label, load.component, it->where.line);
      it = loads.erase(it);
    } else {
      ++it;
    }
  loads.push_back(std::move(load));
}

const std::set<std::string> kContactOptions = {"NTS", "ANTS", "OSTS", "STS", "ASTS", "ASSC", "SS"};

void cmd_edcgen(DeckReader& r, const Command& c) {
  // EDCGEN,Option,Cont,Targ,FS,FD,DC,VC,VDC,V1,V2,V3,V4,BTIME,DTIME,BOXID1,BOXID2
  const std::string option = r.label(c, 1);
  if (option == "AG")
    r.fail(c,
           "Option AG: automatic general contact adds the contact of shell edges and beams, "
           "not implemented; ASSC (automatic single surface) checks every exterior node "
           "against every exterior face");
  if (!kContactOptions.count(option))
    r.fail(c, fmt::format("Option '{}': the contact options carried out are NTS, ANTS, OSTS "
                          "(node to surface), STS, ASTS (surface to surface) and ASSC, SS "
                          "(single surface); the others (automatic general, eroding, forming, "
                          "tied, tiebreak, drawbead, rigid, edge) are not implemented",
                          c.text(1)));
  ExplicitContact k;
  k.option = option;
  k.contact = r.label(c, 2);
  k.target = r.label(c, 3);
  const bool single = option == "ASSC" || option == "SS";
  if (!single && (k.contact.empty() || k.target.empty()))
    r.fail(c, fmt::format("{} needs Cont and Targ (a part number or a component)", option));
  if (single && !k.target.empty())
    r.fail(c, fmt::format("Targ '{}': single surface contact ({}) has no target; Cont (blank: "
                          "the whole model) is both sides",
                          c.text(3), option));
  k.static_friction = r.real(c, 4, 0.0);
  k.dynamic_friction = r.real(c, 5, 0.0);
  k.decay = r.real(c, 6, 0.0);
  k.viscous_damping = r.real(c, 8, 0.0);
  if (k.static_friction < 0 || k.dynamic_friction < 0 || k.decay < 0 || k.viscous_damping < 0)
    r.fail(c, "FS, FD, DC and VDC are >= 0");
  if (k.viscous_damping > 100.0)
    r.fail(c, fmt::format("VDC {:g}: the viscous contact damping is a percentage of critical "
                          "damping, 0 to 100",
                          k.viscous_damping));
  if (r.real(c, 7, 0.0) != 0.0)
    r.fail(c, "VC: the viscous friction limit is not implemented (VC 0 only)");
  for (int f = 9; f <= 12; ++f)
    if (r.real(c, f, 0.0) != 0.0)
      r.fail(c, fmt::format("field {} (V{}): the tiebreak, drawbead and forming settings are not "
                            "implemented",
                            f, f - 8));
  for (int f = 15; f <= 16; ++f)
    if (!c.blank(f)) r.fail(c, "BOXID1, BOXID2: contact boxes (EDBX) are not implemented");
  k.birth = r.real(c, 13, 0.0);
  k.death = r.real(c, 14, 0.0);
  k.where = c.where;
  r.model.explicit_dynamics.contacts.push_back(std::move(k));
}

ExplicitContact& contact_entity(DeckReader& r, const Command& c, int number) {
  auto& list = r.model.explicit_dynamics.contacts;
  if (number < 1 || number > static_cast<int>(list.size()))
    r.fail(c, fmt::format("NUM {}: no such contact entity ({} defined by EDCGEN)", number,
                          list.size()));
  return list[static_cast<std::size_t>(number - 1)];
}

void cmd_edcmore(DeckReader& r, const Command& c) {
  // EDCMORE,Option,NUM,--,VAL1,VAL2
  const std::string option = r.label(c, 1).empty() ? "ADD" : r.label(c, 1);
  if (option == "DELE") {
    if (r.label(c, 2) == "ALL" || c.blank(2)) {
      for (auto& k : r.model.explicit_dynamics.contacts) k.slave_scale = k.master_scale = 1.0;
      return;
    }
    ExplicitContact& k = contact_entity(r, c, r.integer(c, 2, 0));
    k.slave_scale = k.master_scale = 1.0;
    return;
  }
  if (option != "ADD") r.fail(c, fmt::format("Option '{}': ADD or DELE", c.text(1)));
  ExplicitContact& k = contact_entity(r, c, r.integer(c, 2, 0));
  const double sfs = c.blank(4) ? 1.0 : r.real(c, 4, 1.0);
  const double sfm = c.blank(5) ? 1.0 : r.real(c, 5, 1.0);
  if (!(sfs > 0.0) || !(sfm > 0.0)) r.fail(c, "SFS and SFM are > 0");
  k.slave_scale = sfs;
  k.master_scale = sfm;
}

void cmd_eddc(DeckReader& r, const Command& c) {
  // EDDC,Option,Ctype,Cont,Targ
  const std::string option = r.label(c, 1).empty() ? "DELE" : r.label(c, 1);
  if (option != "DELE")
    r.fail(c, fmt::format("Option '{}': DACT and RACT are for restarts, not implemented; DELE is",
                          c.text(1)));
  const std::string type = r.label(c, 2), cont = r.label(c, 3), targ = r.label(c, 4);
  auto& list = r.model.explicit_dynamics.contacts;
  const auto before = list.size();
  std::erase_if(list, [&](const ExplicitContact& k) {
    return k.option == type && (cont.empty() || k.contact == cont) &&
           (targ.empty() || k.target == targ);
  });
  if (list.size() == before)
    r.warn(c, fmt::format("no contact definition {} {} {} to delete", type, cont, targ));
}

void cmd_edclist(DeckReader& r, const Command& c) {
  const std::string num = r.label(c, 1);
  int number = 0;
  for (const auto& k : r.model.explicit_dynamics.contacts) {
    ++number;
    if (!num.empty() && num != "ALL" && r.integer(c, 1, 0) != number) continue;
    Log::info("EDCGEN: contact {}: {} {} {} FS {:g} FD {:g} DC {:g} VDC {:g} SFS {:g} SFM {:g}",
              number, k.option, k.contact, k.target, k.static_friction, k.dynamic_friction, k.decay,
              k.viscous_damping, k.slave_scale, k.master_scale);
  }
}

}  // namespace

void register_explicit_load_commands(std::vector<CommandSpec>& t) {
  t.push_back({"EDCURVE", cmd_edcurve, kPrepSolu});
  t.push_back({"EDLOAD", cmd_edload, kPrepSolu});
  t.push_back({"EDCGEN", cmd_edcgen, kPrepSolu});
  t.push_back({"EDCMORE", cmd_edcmore, kPrepSolu});
  t.push_back({"EDDC", cmd_eddc, kPrepSolu});
  t.push_back({"EDCLIST", cmd_edclist, kPrepSolu});
}

}  // namespace impactfe::deck
