// Loads and initial conditions: D, DDELE, F, FDELE, ACEL, IC, ICDELE (APDL_SUBSET §3.19, §3.22,
// §3.23; APDL_SCRIPTING §E.9), and the rotational inertia loads OMEGA, DOMEGA, CGLOC, CGOMGA,
// DCGOMG (MAPDL 18.2 Command Reference). Loads are cumulative state in Model::current.
#include <fmt/format.h>

#include "core/dof.h"
#include "deck/modeling_helpers.h"

namespace impactfe::deck {

std::vector<Dof> parse_dof_labels(DeckReader& r, const Command& c, int lab_field, int& end_field,
                                  int& inc_field, int extra_first, int extra_last) {
  std::vector<std::string> labels{r.label(c, lab_field)};
  for (int f : {end_field, inc_field}) {
    if (f <= 0) continue;
    const std::string l = r.label(c, f);
    if ((parse_dof_label(l) || l == "ALL") && !r.params.get(l)) {
      if (r.dialect != Dialect::Classic4x)
        r.fail(c, fmt::format("field {}: bad number '{}' (a DOF label belongs in Lab2..Lab6)", f,
                              c.text(f)));
      r.warn(c,
             fmt::format("DOF label '{}' in numeric field {} taken as an extra label (4x)", l, f));
      for (int g = f; g <= inc_field; ++g)
        if (!c.blank(g)) labels.push_back(r.label(c, g));
      if (f == end_field) end_field = 0;
      inc_field = 0;
      break;
    }
  }
  for (int f = extra_first; f <= extra_last; ++f)
    if (!c.blank(f)) labels.push_back(r.label(c, f));
  if (labels[0].empty()) r.fail(c, "DOF label missing");
  std::vector<Dof> dofs;
  for (const auto& l : labels) {
    if (l == "ALL") return {kAllDofs.begin(), kAllDofs.end()};
    auto d = parse_dof_label(l);
    if (!d) r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ ALL)", l));
    dofs.push_back(*d);
  }
  return dofs;
}

namespace {

void cmd_d(DeckReader& r, const Command& c) {
  // D,NODE,Lab,VALUE,VALUE2,NEND,NINC,Lab2..Lab6
  int end_field = 5;
  int inc_field = 6;
  const auto dofs = parse_dof_labels(r, c, 2, end_field, inc_field, 7, 11);
  const LoadField value = load_field(r, c, 3);  // a number or %TABLE% (APDL_MODELING §5.5)
  if (r.real(c, 4, 0.0) != 0.0) r.warn(c, "VALUE2 (imaginary part) ignored");
  LoadStep& s = r.model.current;
  for (int node : r.node_range(c, 1, end_field, inc_field))
    for (Dof d : dofs) {
      s.constraints[DofKey{node, d}] = value.value;
      if (value.table.empty())
        s.constraint_tables.erase(DofKey{node, d});
      else
        s.constraint_tables[DofKey{node, d}] = value.table;
    }
}

void cmd_ddele(DeckReader& r, const Command& c) {
  // DDELE,NODE,Lab,NEND,NINC
  std::vector<Dof> dofs(kAllDofs.begin(), kAllDofs.end());
  const std::string l = r.label(c, 2);
  if (!l.empty() && l != "ALL") {
    auto d = parse_dof_label(l);
    if (!d) r.fail(c, fmt::format("bad DOF label '{}'", c.text(2)));
    dofs = {*d};
  }
  for (int node : r.node_range(c, 1, 3, 4))
    for (Dof d : dofs) {
      r.model.current.constraints.erase(DofKey{node, d});
      r.model.current.constraint_tables.erase(DofKey{node, d});
    }
}

void cmd_f(DeckReader& r, const Command& c) {
  // F,NODE,Lab,VALUE,VALUE2,NEND,NINC ; a blank VALUE is 0 (§3.23)
  const std::string l = r.label(c, 2);
  auto d = parse_force_label(l);
  if (!d) r.fail(c, fmt::format("bad force label '{}' (FX FY FZ MX MY MZ)", c.text(2)));
  const LoadField value = load_field(r, c, 3);
  // VALUE2: the imaginary part of a harmonic force (ANTYPE,HARMIC); other analyses have none.
  const double imag = r.real(c, 4, 0.0);
  const bool harmonic = r.model.options.type == AnalysisType::Harmonic;
  if (imag != 0.0 && !harmonic)
    r.warn(c, "VALUE2 (imaginary part) ignored: only a harmonic analysis has one");
  if (imag != 0.0 && !value.table.empty())
    r.fail(c, "VALUE2 (imaginary part) with a table VALUE is not supported");
  LoadStep& s = r.model.current;
  for (int node : r.node_range(c, 1, 5, 6)) {
    s.forces[DofKey{node, *d}] = value.value;
    if (harmonic && imag != 0.0)
      s.forces_imag[DofKey{node, *d}] = imag;
    else
      s.forces_imag.erase(DofKey{node, *d});
    s.force_where[DofKey{node, *d}] = c.where;
    if (value.table.empty())
      s.force_tables.erase(DofKey{node, *d});
    else
      s.force_tables[DofKey{node, *d}] = value.table;
  }
}

void cmd_fdele(DeckReader& r, const Command& c) {
  // FDELE,NODE,Lab,NEND,NINC
  std::vector<Dof> dofs(kAllDofs.begin(), kAllDofs.end());
  const std::string l = r.label(c, 2);
  if (!l.empty() && l != "ALL") {
    auto d = parse_force_label(l);
    if (!d) r.fail(c, fmt::format("bad force label '{}'", c.text(2)));
    dofs = {*d};
  }
  for (int node : r.node_range(c, 1, 3, 4))
    for (Dof d : dofs) {
      r.model.current.forces.erase(DofKey{node, d});
      r.model.current.force_tables.erase(DofKey{node, d});
      r.model.current.force_where.erase(DofKey{node, d});
      r.model.current.forces_imag.erase(DofKey{node, d});
    }
}

void cmd_acel(DeckReader& r, const Command& c) {
  LoadStep& s = r.model.current;
  for (int k = 0; k < 3; ++k) {
    const LoadField v = load_field(r, c, k + 1);
    s.acel(k) = v.value;
    s.acel_tables[static_cast<std::size_t>(k)] = v.table;
  }
}

// OMEGA,OMEGX,OMEGY,OMEGZ,KSPIN; DOMEGA,DOMGX,DOMGY,DOMGZ; CGLOC,XLOC,YLOC,ZLOC;
// CGOMGA,CGOMX,CGOMY,CGOMZ; DCGOMG,DCGOX,DCGOY,DCGOZ: three global Cartesian components each
// (blank = 0), replacing the earlier ones. The analysis applies them as the inertia load of the
// acceleration field they give (core/rotating_frame.h). Tables (%TABLE%) and spin softening
// (KSPIN) are refused: they would change the load or the stiffness in ways not carried out.
void set_rotational_vector(DeckReader& r, const Command& c, Vec3& v, int first_other_field) {
  for (int k = 0; k < 3; ++k) {
    const std::string text = trim(c.text(k + 1));
    if (!text.empty() && text.front() == '%')
      r.fail(c, fmt::format("field {} '{}': a {} given by a table is not supported (numbers only)",
                            k + 1, text, c.name));
    v(k) = r.real(c, k + 1, 0.0);
  }
  for (int f = first_other_field; f <= c.n_fields(); ++f)
    if (!c.blank(f))
      r.fail(c, fmt::format("field {} '{}' is not a {} field", f, c.text(f), c.name));
  if (v != Vec3::Zero()) r.model.current.rotation.where = c.where;
}

void cmd_omega(DeckReader& r, const Command& c) {
  // KSPIN (field 4): spin softening, the stiffness change of a rotating body, is not carried
  // out; 0 / OFF (the default) is what impactfe does.
  if (const std::string kspin = r.label(c, 4); !kspin.empty() && kspin != "0" && kspin != "OFF") {
    if (kspin == "ON" || r.real(c, 4, 0.0) != 0.0)
      r.fail(c, fmt::format("KSPIN '{}': spin softening is not implemented (0 or OFF only)",
                            c.text(4)));
  }
  set_rotational_vector(r, c, r.model.current.rotation.omega, 5);
}
void cmd_domega(DeckReader& r, const Command& c) {
  set_rotational_vector(r, c, r.model.current.rotation.domega, 4);
}
void cmd_cgloc(DeckReader& r, const Command& c) {
  set_rotational_vector(r, c, r.model.current.rotation.cg_location, 4);
}
void cmd_cgomga(DeckReader& r, const Command& c) {
  set_rotational_vector(r, c, r.model.current.rotation.cg_omega, 4);
}
void cmd_dcgomg(DeckReader& r, const Command& c) {
  set_rotational_vector(r, c, r.model.current.rotation.cg_domega, 4);
}

void cmd_ic(DeckReader& r, const Command& c) {
  // IC,NODE,Lab,VALUE,VALUE2,NEND,NINC
  const std::string l = r.label(c, 2);
  const double value = r.real(c, 3, 0.0);
  const auto value2 = r.opt_real(c, 4);
  std::vector<Dof> dofs;
  bool velocity = false;
  if (l == "ALL") {
    dofs.assign(kAllDofs.begin(), kAllDofs.end());
  } else if (auto d = parse_dof_label(l)) {
    dofs = {*d};
  } else if (l == "VELX" || l == "VELY" || l == "VELZ") {
    dofs = {static_cast<Dof>(l[3] - 'X')};
    velocity = true;
  } else if (l == "OMGX" || l == "OMGY" || l == "OMGZ") {
    dofs = {static_cast<Dof>(3 + (l[3] - 'X'))};
    velocity = true;
  } else {
    r.fail(c,
           fmt::format("bad initial-condition label '{}' (UX..ROTZ, VELX..VELZ, OMGX..OMGZ, ALL)",
                       c.text(2)));
  }
  for (int node : r.node_range(c, 1, 5, 6)) {
    for (Dof d : dofs) {
      InitialCondition& ic = r.model.initial_conditions[DofKey{node, d}];
      ic.where = c.where;
      if (velocity) {
        ic.velocity = value;
      } else {
        ic.displacement = value;
        if (value2) ic.velocity = *value2;  // legacy: velocity in VALUE2
      }
    }
  }
}

void cmd_icdele(DeckReader& r, const Command&) {
  r.model.initial_conditions.clear();
}

}  // namespace

void register_load_commands(std::vector<CommandSpec>& t) {
  t.push_back({"D", cmd_d, kPrepSolu});
  t.push_back({"DDELE", cmd_ddele, kPrepSolu});
  t.push_back({"F", cmd_f, kPrepSolu});
  t.push_back({"FDELE", cmd_fdele, kPrepSolu});
  t.push_back({"ACEL", cmd_acel, kPrepSolu});
  t.push_back({"OMEGA", cmd_omega, kPrepSolu});
  t.push_back({"DOMEGA", cmd_domega, kPrepSolu});
  t.push_back({"CGLOC", cmd_cgloc, kPrepSolu});
  t.push_back({"CGOMGA", cmd_cgomga, kPrepSolu});
  t.push_back({"DCGOMG", cmd_dcgomg, kPrepSolu});
  t.push_back({"IC", cmd_ic, kPrepSolu});
  t.push_back({"ICDELE", cmd_icdele, kPrepSolu});
}

}  // namespace impactfe::deck
