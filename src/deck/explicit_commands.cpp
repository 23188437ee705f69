// Explicit dynamics settings (the ED* commands of MAPDL's ANSYS LS-DYNA interface, Command
// Reference release 18.2; docs/explicit_dynamics.md): EDCTS, EDHGLS, EDBVIS, EDRST, EDHTIME,
// EDVEL, EDPART, EDMP, EDCRB, EDDAMP, EDHIST (loads by curve and contact:
// explicit_load_commands.cpp). They set Model::explicit_dynamics; the explicit run (src/explicit)
// reads it. The ED commands of features not implemented (restarts, ...) are refused where they
// appear, so that no deck runs without them silently.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "core/log.h"
#include "deck/deck_context.h"

namespace impactfe::deck {

/// EDCURVE, EDLOAD, EDCGEN, EDCMORE, EDDC, EDCLIST (explicit_load_commands.cpp).
void register_explicit_load_commands(std::vector<CommandSpec>& t);

namespace {

/// The model's parts as EDPART numbers them: its elements grouped by (type, material, real
/// set), the groups in ascending order (part 1 first), the ids ascending in each.
std::map<std::tuple<int, int, int>, std::vector<int>> model_parts(const Model& model) {
  std::map<std::tuple<int, int, int>, std::vector<int>> parts;
  for (const auto& [id, e] : model.elements) parts[{e.type, e.mat, e.real}].push_back(id);
  return parts;
}

ExplicitControls& controls(DeckReader& r, const Command& c) {
  r.model.explicit_dynamics.where = c.where;
  return r.model.explicit_dynamics;
}

void cmd_edcts(DeckReader& r, const Command& c) {
  // EDCTS,DTMS,TSSFAC
  const double dtms = r.real(c, 1, 0.0);
  const double tssfac = r.real(c, 2, 0.9);
  if (!(tssfac > 0.0) || tssfac > 1.0)
    r.fail(c, fmt::format("TSSFAC {:g}: the factor on the stable time step must lie in (0, 1] "
                          "(a larger step is beyond the central difference's stability limit)",
                          tssfac));
  ExplicitControls& e = controls(r, c);
  e.mass_scaling_step = dtms;
  e.time_step_factor = tssfac;
}

void cmd_edhgls(DeckReader& r, const Command& c) {
  // EDHGLS,HGCO
  const double hgco = r.real(c, 1, 0.1);
  if (hgco < 0.0) r.fail(c, fmt::format("HGCO {:g}: the hourglass coefficient is >= 0", hgco));
  if (hgco > 0.15)
    r.warn(c, fmt::format("HGCO {:g} above 0.15 may make the run unstable (EDHGLS notes)", hgco));
  controls(r, c).hourglass_coefficient = hgco;
}

void cmd_edbvis(DeckReader& r, const Command& c) {
  // EDBVIS,QVCO,LVCO
  const double quadratic = r.real(c, 1, 1.5);
  const double linear = r.real(c, 2, 0.06);
  if (quadratic < 0.0 || linear < 0.0)
    r.fail(c, "the bulk viscosity coefficients QVCO and LVCO are >= 0");
  ExplicitControls& e = controls(r, c);
  e.bulk_quadratic = quadratic;
  e.bulk_linear = linear;
}

ExplicitOutputInterval output_interval(DeckReader& r, const Command& c) {
  // EDRST / EDHTIME,NSTEP,DT: NSTEP wins when both are given.
  ExplicitOutputInterval out;
  if (const auto n = r.opt_int(c, 1)) {
    if (*n <= 0) r.fail(c, fmt::format("NSTEP {}: the number of output steps is > 0", *n));
    out.steps = *n;
    if (!c.blank(2)) r.warn(c, "NSTEP and DT both given: DT is ignored");
  } else if (const auto dt = r.opt_real(c, 2)) {
    if (!(*dt > 0.0)) r.fail(c, fmt::format("DT {:g}: the output interval is > 0", *dt));
    out.interval = *dt;
  }
  return out;
}

void edmp_hourglass(DeckReader& r, const Command& c, int mat) {
  // EDMP,HGLS,MAT,VAL1..VAL6: hourglass type, QM, the bulk viscosity coefficients, the shell's
  // bending and warping coefficients (default QM).
  ExplicitHourglass h;
  h.type = r.integer(c, 3, 0);
  if (h.type < 0 || h.type > 5)
    r.fail(c, fmt::format("VAL1 {}: the hourglass control type is 0 to 5 (0 to 3 viscous, 4 and "
                          "5 stiffness)",
                          h.type));
  h.membrane = r.real(c, 4, 0.1);
  h.bulk_quadratic = r.real(c, 5, 1.5);
  h.bulk_linear = r.real(c, 6, 0.06);
  h.bending = r.real(c, 7, h.membrane);
  h.warping = r.real(c, 8, h.membrane);
  for (const double v : {h.membrane, h.bulk_quadratic, h.bulk_linear, h.bending, h.warping})
    if (!(v >= 0.0)) r.fail(c, fmt::format("VAL2 to VAL6 are coefficients >= 0, got {:g}", v));
  if (const double most = std::max({h.membrane, h.bending, h.warping}); most > 0.15)
    r.warn(c, fmt::format("hourglass coefficient {:g} above 0.15 may make the run unstable "
                          "(EDMP notes)",
                          most));
  for (int k = 9; k <= c.n_fields(); ++k)
    if (!c.blank(k)) r.fail(c, "HGLS takes VAL1 to VAL6 only");
  h.where = c.where;
  controls(r, c).hourglass_materials[mat] = h;
}

void cmd_edmp(DeckReader& r, const Command& c) {
  // EDMP,Lab,MAT,VAL1..VAL6: RIGID (VAL1, VAL2 the translational and rotational constraint
  // codes) and HGLS (hourglass and bulk viscosity); the other labels are refused.
  const std::string lab = r.label(c, 1);
  const bool hourglass = lab == "HGLS";
  if (lab.rfind("RIGI", 0) != 0 && !hourglass)
    r.fail(c, fmt::format("Lab '{}' is not implemented in explicit dynamics (RIGID, HGLS)",
                          c.text(1)));
  const int mat = r.integer(c, 2, r.modeling.current_mat);
  if (mat <= 0) r.fail(c, fmt::format("MAT {}: a material number is positive", mat));
  if (hourglass) return edmp_hourglass(r, c, mat);
  ExplicitRigidMaterial m;
  m.translation = r.integer(c, 3, 0);
  m.rotation = r.integer(c, 4, 0);
  for (const int code : {m.translation, m.rotation})
    if (code < 0 || code > 7)
      r.fail(c,
             fmt::format("constraint code {}: VAL1 and VAL2 are 0 (free) to 7 (x, y and z)", code));
  for (int k = 5; k <= c.n_fields(); ++k)
    if (!c.blank(k)) r.fail(c, "RIGID takes VAL1 and VAL2 only");
  m.where = c.where;
  controls(r, c).rigid_materials[mat] = m;
}

void list_rigid_merges(const ExplicitControls& e, int neqn) {
  for (const auto& [number, m] : e.rigid_merges)
    if (neqn == 0 || number == neqn)
      Log::info("EDCRB: equation {}: part {} (material {}) moves with part {} (material {})",
                number, m.slave_part, m.slave_material, m.master_part, m.master_material);
}

void cmd_edcrb(DeckReader& r, const Command& c) {
  // EDCRB,Option,NEQN,PARTM,PARTS: the slave part's rigid body joins the master part's. Whether
  // both are rigid (EDMP,RIGID may follow) is checked when the run starts.
  const std::string option = r.label(c, 1).empty() ? "ADD" : r.label(c, 1);
  auto& merges = r.model.explicit_dynamics.rigid_merges;
  const int neqn = r.integer(c, 2, 0);
  if (neqn < 0) r.fail(c, fmt::format("NEQN {}: an equation number is positive", neqn));
  if (option == "LIST") return list_rigid_merges(r.model.explicit_dynamics, neqn);
  if (option == "DELE") {
    if (neqn == 0)
      merges.clear();
    else if (merges.erase(neqn) == 0)
      r.fail(c, fmt::format("NEQN {}: no such rigid body equation (EDCRB,LIST)", neqn));
    return;
  }
  if (option != "ADD") r.fail(c, fmt::format("Option '{}': ADD, DELE or LIST", c.text(1)));
  for (int k = 5; k <= c.n_fields(); ++k)
    if (!c.blank(k)) r.fail(c, "EDCRB takes Option, NEQN, PARTM and PARTS only");
  const ExplicitPart master = explicit_part(r, c, 3, "PARTM");
  const ExplicitPart slave = explicit_part(r, c, 4, "PARTS");
  if (master.number == slave.number)
    r.fail(c, fmt::format("PARTM and PARTS are both part {}", master.number));
  ExplicitRigidMerge m{.master_part = master.number,
                       .slave_part = slave.number,
                       .master_material = master.mat,
                       .slave_material = slave.mat,
                       .where = c.where};
  // NEQN defaults to PARTS; an equation number given again replaces its equation.
  controls(r, c).rigid_merges[neqn > 0 ? neqn : slave.number] = m;
}

void cmd_eddamp(DeckReader& r, const Command& c) {
  // EDDAMP,PART,LCID,VALDMP: PART = ALL (or blank) is the mass-weighted damping of the whole
  // model, by the curve LCID or the constant VALDMP; a part number gives that part
  // stiffness-weighted damping, which is not implemented.
  const std::string part = r.label(c, 1);
  if (!part.empty() && part != "ALL")
    r.fail(c, fmt::format("PART {}: stiffness-weighted damping of a part is not implemented "
                          "(EDDAMP,ALL, the mass-weighted damping of the model, is)",
                          c.text(1)));
  const int lcid = r.integer(c, 2, 0);
  const double valdmp = r.real(c, 3, 0.0);
  if (lcid < 0) r.fail(c, fmt::format("LCID {}: a curve number is positive", lcid));
  if (lcid > 0 && r.model.explicit_dynamics.curves.count(lcid) == 0)
    r.fail(c, fmt::format("LCID {}: no such curve (EDCURVE,ADD)", lcid));
  if (lcid > 0 && valdmp != 0.0)
    r.fail(c, "LCID and VALDMP both given: the damping is either the curve's or the constant");
  if (valdmp < 0.0) r.fail(c, fmt::format("VALDMP {:g}: the damping constant is >= 0", valdmp));
  if (lcid == 0 && valdmp == 0.0) {
    controls(r, c).mass_damping.reset();  // EDDAMP,ALL,,0: no damping
    return;
  }
  controls(r, c).mass_damping = ExplicitMassDamping{valdmp, lcid, c.where};
}

void cmd_edhist(DeckReader& r, const Command& c) {
  // EDHIST,Comp: the nodes of a component go to the history points (EDHTIME). impactfe stores
  // every node at those points, so the components only need to exist; LIST and DELE as MAPDL.
  const std::string comp = r.label(c, 1);
  auto& list = controls(r, c).history_components;
  if (comp == "LIST") {
    for (const auto& name : list) Log::info("EDHIST: component {}", name);
    return;
  }
  if (comp == "DELE") {
    list.clear();
    return;
  }
  const auto it = r.model.components.find(comp);
  if (comp.empty() || it == r.model.components.end())
    r.fail(c, fmt::format("Comp '{}': no such component (CM)", c.text(1)));
  if (it->second.entity != "NODE")
    r.fail(c, fmt::format("Comp {} is a {} component; the history of element components is "
                          "not implemented (node components are)",
                          comp, it->second.entity));
  if (std::find(list.begin(), list.end(), comp) == list.end()) list.push_back(comp);
}

void cmd_edrst(DeckReader& r, const Command& c) {
  const ExplicitOutputInterval out = output_interval(r, c);
  controls(r, c).results = out;
}

void cmd_edhtime(DeckReader& r, const Command& c) {
  const ExplicitOutputInterval out = output_interval(r, c);
  controls(r, c).history = out;
}

void list_initial_velocities(const DeckReader& r) {
  for (const auto& v : r.model.explicit_dynamics.initial_velocities)
    Log::info("EDVEL: {} ({} nodes): VX {:g} VY {:g} VZ {:g}", v.component, v.nodes.size(),
              v.velocity.x(), v.velocity.y(), v.velocity.z());
}

void cmd_edvel(DeckReader& r, const Command& c) {
  // EDVEL,Option,Cname,VX,VY,VZ,OMEGAX,OMEGAY,OMEGAZ,XC,YC,ZC,ANGX,ANGY,ANGZ
  const std::string option = r.label(c, 1).empty() ? "VGEN" : r.label(c, 1);
  auto& list = r.model.explicit_dynamics.initial_velocities;
  const std::string cname = r.label(c, 2);
  if (option == "LIST") return list_initial_velocities(r);
  if (option == "DELE") {
    std::erase_if(list, [&](const auto& v) { return cname.empty() || v.component == cname; });
    return;
  }
  if (option != "VGEN" && option != "VELO")
    r.fail(c, fmt::format("Option '{}': VGEN, VELO, LIST or DELE", c.text(1)));
  for (int f = 6; f <= 14; ++f)
    if (r.real(c, f, 0.0) != 0.0)
      r.fail(c, fmt::format("field {}: initial angular velocities (OMEGAX..ANGZ) are not "
                            "implemented; only the translational VX, VY, VZ are",
                            f));
  const auto it = r.model.components.find(cname);
  if (cname.empty() || it == r.model.components.end())
    r.fail(c, fmt::format("Cname '{}': no such component (CM); EDVEL takes a node component "
                          "(PART numbers are not implemented)",
                          c.text(2)));
  if (it->second.entity != "NODE")
    r.fail(c, fmt::format("Cname {} is a {} component; EDVEL takes a node component", cname,
                          it->second.entity));
  ExplicitInitialVelocity v;
  v.component = cname;
  v.nodes = it->second.ids;
  v.velocity = Vec3(r.real(c, 3, 0.0), r.real(c, 4, 0.0), r.real(c, 5, 0.0));
  v.where = c.where;
  // A component given again replaces its velocity (EDVEL defines one per component).
  std::erase_if(list, [&](const auto& old) { return old.component == cname; });
  list.push_back(std::move(v));
}

void cmd_edpart(DeckReader& r, const Command& c) {
  // EDPART,Option: a part is one combination of element type, material and real set, numbered
  // in ascending (type, material, real) order: EDCGEN refers to them by number.
  const std::string option = r.label(c, 1).empty() ? "CREATE" : r.label(c, 1);
  if (option != "CREATE" && option != "UPDATE" && option != "LIST")
    r.fail(c, fmt::format("Option '{}': CREATE, UPDATE or LIST", c.text(1)));
  int number = 0;
  for (const auto& [key, elements] : model_parts(r.model))
    Log::info("EDPART: part {}: TYPE {} MAT {} REAL {} ({} elements)", ++number, std::get<0>(key),
              std::get<1>(key), std::get<2>(key), elements.size());
}

}  // namespace

ExplicitPart explicit_part(DeckReader& r, const Command& c, int field, const char* name) {
  const auto number = r.opt_int(c, field);
  if (!number || *number <= 0)
    r.fail(c, fmt::format("{} '{}': a part number (EDPART) is expected", name, c.text(field)));
  auto parts = model_parts(r.model);
  if (*number > static_cast<int>(parts.size()))
    r.fail(c,
           fmt::format("{} {}: the model has {} parts (EDPART,LIST)", name, *number, parts.size()));
  auto it = parts.begin();
  std::advance(it, *number - 1);
  return ExplicitPart{.number = *number,
                      .type = std::get<0>(it->first),
                      .mat = std::get<1>(it->first),
                      .real = std::get<2>(it->first),
                      .elements = std::move(it->second)};
}

void register_explicit_commands(std::vector<CommandSpec>& t) {
  t.push_back({"EDCTS", cmd_edcts, kPrepSolu});
  t.push_back({"EDHGLS", cmd_edhgls, kPrepSolu});
  t.push_back({"EDBVIS", cmd_edbvis, kPrepSolu});
  t.push_back({"EDRST", cmd_edrst, kPrepSolu});
  t.push_back({"EDHTIME", cmd_edhtime, kPrepSolu});
  t.push_back({"EDVEL", cmd_edvel, kPrepSolu});
  t.push_back({"EDPART", cmd_edpart, kPrepSolu});
  t.push_back({"EDMP", cmd_edmp, kPrepSolu});
  t.push_back({"EDCRB", cmd_edcrb, kPrepSolu});
  t.push_back({"EDDAMP", cmd_eddamp, kPrepSolu});
  t.push_back({"EDHIST", cmd_edhist, kPrepSolu});
  register_explicit_load_commands(t);
  constexpr const char* kNo = "not implemented in explicit dynamics (docs/explicit_dynamics.md)";
  for (const char* name : {"EDCNSTR", "EDBOUND", "EDWRITE", "EDCONTACT", "EDCSC", "EDSHELL",
                           "EDSTART", "EDADAPT", "EDOUT", "EDINT", "EDENERGY", "EDNROT"})
    t.push_back({name, [](DeckReader&, const Command&) {}, kPrepSolu, nullptr, kNo});
}

}  // namespace impactfe::deck
