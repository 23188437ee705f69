// Constraint equations (CE, CEDELE, CELIST, and RBE3's) and rigid regions (CERIG): model state
// in Model::constraint_equations and Model::rigid_regions. The deck only records them; the
// structure eliminates their slaves (assembly/constraint_equations.h, docs/constraints.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/dof.h"
#include "core/log.h"
#include "deck/modeling_helpers.h"
#include "deck/modeling_state.h"
#include "deck/parameters.h"
#include "elements/kinematic_constraint.h"

namespace impactfe::deck {

namespace {

Dof structural_dof(DeckReader& r, const Command& c, int field) {
  const auto dof = parse_dof_label(r.label(c, field));
  if (!dof)
    r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ: structural DOFs only)",
                          c.text(field)));
  return *dof;
}

/// One term of an equation: the DOF's coefficient is added to a term of the same DOF.
void add_term(ConstraintEquation& eq, const DofKey& key, double coefficient) {
  const auto same = std::find_if(eq.terms.begin(), eq.terms.end(),
                                 [&](const ConstraintTerm& t) { return t.dof == key; });
  if (same != eq.terms.end())
    same->coefficient += coefficient;
  else
    eq.terms.push_back({key, coefficient});
}

// The CDB archive form of CE: `CE,R5.0,DEFI,NTERMS,NEQN,CONST` defines equation NEQN, then
// `CE,R5.0,NODE,NODE1,Lab1,C1,NODE2,Lab2,C2` records give its NTERMS terms, two to a record,
// slave first. The equation replaces one of the same number (the archive holds all of it).
void ce_archive_form(DeckReader& r, const Command& c) {
  auto& equations = r.model.constraint_equations;
  const std::string part = r.label(c, 2);
  if (part == "DEFI") {
    if (r.modeling.archive_terms_left > 0)
      r.fail(c, fmt::format("CE,R5.0,DEFI before the last {} term(s) of equation {}",
                            r.modeling.archive_terms_left, r.modeling.archive_equation));
    const int n_terms = r.integer(c, 3, 0), id = r.integer(c, 4, 0);
    if (n_terms <= 0) r.fail(c, fmt::format("NTERMS {}: at least one term", c.text(3)));
    if (id <= 0) r.fail(c, fmt::format("bad equation number '{}'", c.text(4)));
    ConstraintEquation eq;
    eq.id = id;
    eq.constant = r.real(c, 5, 0.0);
    eq.where = c.where;
    equations[id] = std::move(eq);
    r.modeling.archive_equation = id;
    r.modeling.archive_terms_left = n_terms;
  } else if (part == "NODE") {
    if (r.modeling.archive_terms_left <= 0)
      r.fail(c, "CE,R5.0,NODE without a CE,R5.0,DEFI whose terms it continues");
    ConstraintEquation& eq = equations[r.modeling.archive_equation];
    for (int f = 3; f <= 6 && r.modeling.archive_terms_left > 0; f += 3) {
      if (c.blank(f) && f > 3) break;  // one term on this record, the rest on the next
      if (c.blank(f)) r.fail(c, "the node of the record's first term is missing");
      const int node = r.integer(c, f, 0);
      r.require_node(c, node);
      add_term(eq, DofKey{node, structural_dof(r, c, f + 1)}, r.real(c, f + 2, 0.0));
      --r.modeling.archive_terms_left;
    }
  } else {
    r.fail(c, fmt::format("CE,R5.0 record '{}': DEFI or NODE", c.text(2)));
  }
}

void cmd_ce(DeckReader& r, const Command& c) {
  if (r.label(c, 1) == "R5.0") return ce_archive_form(r, c);
  // CE,NEQN,CONST,NODE1,Lab1,C1,NODE2,Lab2,C2,NODE3,Lab3,C3: CONST = Σ C_i u_i (MAPDL Command
  // Reference, CE). NEQN blank or NEXT: the highest equation number + 1; HIGH: the highest (to
  // add terms); n: that equation (terms are added to it). A zero coefficient drops its term.
  // The first term of the equation is its slave (the DOF eliminated).
  auto& equations = r.model.constraint_equations;
  const std::string neqn = r.label(c, 1);
  const int highest = equations.empty() ? 0 : equations.rbegin()->first;
  int id = 0;
  if (neqn.empty() || neqn == "NEXT") {
    id = highest + 1;
  } else if (neqn == "HIGH") {
    id = std::max(highest, 1);
  } else {
    id = r.integer(c, 1, 0);
    if (id <= 0) r.fail(c, fmt::format("bad equation number '{}'", c.text(1)));
  }
  ConstraintEquation& eq = equations[id];
  const bool fresh = eq.terms.empty();
  if (fresh) {
    eq.id = id;
    eq.where = c.where;
  }
  if (!c.blank(2)) eq.constant = r.real(c, 2, 0.0);
  for (int f = 3; f + 2 <= std::max(c.n_fields(), 5) && f <= 9; f += 3) {
    if (c.blank(f)) continue;
    const int node = r.integer(c, f, 0);
    if (node == 0) continue;
    r.require_node(c, node);
    const Dof dof = structural_dof(r, c, f + 1);
    const double coefficient = r.real(c, f + 2, 0.0);
    if (coefficient == 0.0) continue;
    add_term(eq, DofKey{node, dof}, coefficient);
  }
  if (eq.terms.empty()) {
    if (fresh) equations.erase(id);
    r.fail(c, "the equation has no term with a node, a DOF label and a non-zero coefficient");
  }
}

void cmd_cedele(DeckReader& r, const Command& c) {
  // CEDELE,NEQN1,NEQN2,NINC (NEQN1 = ALL: every equation).
  auto& equations = r.model.constraint_equations;
  if (r.label(c, 1) == "ALL") {
    equations.clear();
    return;
  }
  const int first = r.integer(c, 1, 0);
  const int last = std::max(first, r.integer(c, 2, first));
  const int inc = std::max(1, r.integer(c, 3, 1));
  for (int id = first; id <= last; id += inc) equations.erase(id);
}

void cmd_celist(DeckReader& r, const Command& c) {
  // CELIST,NEQN1,NEQN2,NINC: the equations in the log (blank or ALL: all of them).
  const auto& equations = r.model.constraint_equations;
  const bool all = c.blank(1) || r.label(c, 1) == "ALL";
  const int first = all ? 0 : r.integer(c, 1, 0);
  const int last = all ? (equations.empty() ? 0 : equations.rbegin()->first)
                       : std::max(first, r.integer(c, 2, first));
  const int inc = all ? 1 : std::max(1, r.integer(c, 3, 1));
  Log::info("{}:{}: CELIST: {} constraint equation(s) defined", c.where.file, c.where.line,
            equations.size());
  for (const auto& [id, eq] : equations) {
    if (id < first || id > last || (id - first) % inc != 0) continue;
    std::string text;
    for (const auto& t : eq.terms) text += fmt::format(" {:+g} {}", t.coefficient, describe(t.dof));
    Log::info("  CE {}: {:g} ={}", id, eq.constant, text);
  }
}

void cmd_cerig(DeckReader& r, const Command& c) {
  // CERIG,MASTE,SLAVE,Ldof,Ldof2,...,Ldof5 (MAPDL Command Reference, CERIG): SLAVE a node, ALL
  // (the selected nodes) or a component; Ldof ALL (default), UXYZ, RXYZ or single labels UX ..
  // ROTZ. The equations are written when the structure is built, where the master's DOFs say
  // whether the region is 3-D (ROTX ROTY ROTZ) or 2-D (UX UY ROTZ).
  RigidRegion region;
  region.where = c.where;
  region.master = r.integer(c, 1, 0);
  if (r.label(c, 1) == "P") r.fail(c, "graphical picking (MASTE = P) is not available");
  r.require_node(c, region.master);
  for (int s : r.node_range(c, 2, 0, 0))
    if (s != region.master) region.slaves.push_back(s);
  if (region.slaves.empty()) r.fail(c, "no slave node besides the master");
  bool translations = false, rotations = false;
  for (int f = 3; f <= 7; ++f) {
    const std::string lab = r.label(c, f);
    if (lab.empty()) continue;
    if (lab == "ALL" || lab == "RIGID") {
      translations = rotations = true;
    } else if (lab == "UXYZ") {
      translations = true;
    } else if (lab == "RXYZ") {
      rotations = true;
    } else if (const auto dof = parse_dof_label(lab)) {
      region.only.push_back(*dof);
    } else {
      r.fail(c,
             fmt::format("bad DOF label '{}' (ALL UXYZ RXYZ UX UY UZ ROTX ROTY ROTZ)", c.text(f)));
    }
  }
  if (!translations && !rotations && region.only.empty()) translations = rotations = true;
  if (!region.only.empty() && (translations || rotations)) {
    // Groups and single labels together: the single labels of the groups join the list.
    if (translations)
      for (Dof d : {Dof::UX, Dof::UY, Dof::UZ}) region.only.push_back(d);
    if (rotations)
      for (Dof d : {Dof::ROTX, Dof::ROTY, Dof::ROTZ}) region.only.push_back(d);
    std::sort(region.only.begin(), region.only.end());
    region.only.erase(std::unique(region.only.begin(), region.only.end()), region.only.end());
  }
  region.translations = translations;
  region.rotations = rotations;
  r.model.rigid_regions.push_back(std::move(region));
}

void cmd_rbe3(DeckReader& r, const Command& c) {
  // RBE3,Master,DOF,Slaves,Wtfact (MAPDL Command Reference, RBE3): the master's DOF (ALL, the
  // default, UXYZ, RXYZ or one label) follow the weighted rigid fit of the slaves' translations;
  // Slaves: ALL (the selected nodes) or an array of node numbers NAME(n), Wtfact an array of
  // weights (default 1 each). Written as constraint equations now, from the nodes' positions,
  // master first, numbered after the highest equation.
  const int master = r.integer(c, 1, 0);
  r.require_node(c, master);
  std::vector<Dof> dofs;
  const std::string lab = r.label(c, 2);
  if (lab.empty() || lab == "ALL")
    dofs.assign(kAllDofs.begin(), kAllDofs.end());
  else if (lab == "UXYZ")
    dofs = {Dof::UX, Dof::UY, Dof::UZ};
  else if (lab == "RXYZ")
    dofs = {Dof::ROTX, Dof::ROTY, Dof::ROTZ};
  else
    dofs = {structural_dof(r, c, 2)};
  std::vector<int> slaves;
  if (r.label(c, 3) == "ALL") {
    slaves = r.node_range(c, 3, 0, 0);
  } else {
    for (double v : array_column(r, c, 3, "Slaves")) {
      if (!(std::abs(v) < 2e9)) r.fail(c, fmt::format("slave node {:g} is not a node number", v));
      const int node = static_cast<int>(std::lround(v));
      if (node == 0) continue;  // unused entries past the list
      if (static_cast<double>(node) != v)
        r.fail(c, fmt::format("slave node {:g} is not a node number", v));
      r.require_node(c, node);
      slaves.push_back(node);
    }
  }
  std::erase(slaves, master);
  if (slaves.empty()) r.fail(c, "no slave node besides the master");
  std::vector<double> weights(slaves.size(), 1.0);
  if (!c.blank(4)) {
    const std::vector<double> given = array_column(r, c, 4, "Wtfact");
    if (given.size() < slaves.size())
      r.fail(c, fmt::format("Wtfact has {} weight(s) for {} slave node(s)", given.size(),
                            slaves.size()));
    for (std::size_t i = 0; i < slaves.size(); ++i) {
      if (!(given[i] >= 0.0))
        r.fail(c, fmt::format("weight {:g} of slave node {} is negative", given[i], slaves[i]));
      weights[i] = given[i];
    }
  }
  for (int s : slaves)
    if (r.model.node(s).rotated() || r.model.node(master).rotated())
      r.fail(c, fmt::format("node {} has a rotated nodal coordinate system; RBE3 is written in "
                            "global axes here",
                            r.model.node(s).rotated() ? s : master));
  std::vector<Vec3> x;
  for (int s : slaves) x.push_back(r.model.node(s).x);
  auto& equations = r.model.constraint_equations;
  int next = equations.empty() ? 1 : equations.rbegin()->first + 1;
  for (auto& eq : distributing_coupling_equations(master, r.model.node(master).x, slaves, x,
                                                  weights, dofs, c.where)) {
    eq.id = next++;
    equations[eq.id] = std::move(eq);
  }
}

}  // namespace

void register_constraint_equation_commands(std::vector<CommandSpec>& t) {
  t.push_back({"CE", cmd_ce, kPrepSolu});
  t.push_back({"CEDELE", cmd_cedele, kPrepSolu});
  t.push_back({"CELIST", cmd_celist, kPrepSolu});
  t.push_back({"CERIG", cmd_cerig, kPrepSolu});
  t.push_back({"RBE3", cmd_rbe3, kPrepSolu});
}

}  // namespace impactfe::deck
