// Materials (APDL_MODELING §6): MP and the 4x property commands (EX, NUXY, ...), MPTEMP, MPDATA,
// MPDELE, and the nonlinear material tables TB, TBTEMP, TBDATA, TBPT, TBDELE (parsed and stored;
// TB,ELASTIC and TB,FRIC act at once; the plasticity and implicit creep laws are built with the
// elements, materials/j2_plasticity.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "deck/modeling_helpers.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

/// Labels impactfe knows: elastic constants, density, thermal expansion and reference
/// temperature, damping (ALPD mass, BETD/DAMP stiffness proportional; DMPR, DMPS structural),
/// friction MU.
const std::vector<std::string>& material_labels() {
  static const std::vector<std::string> labels = {
      "EX",   "EY",   "EZ",   "NUXY", "NUYZ", "NUXZ", "PRXY", "PRYZ", "PRXZ", "GXY",  "GYZ", "GXZ",
      "DENS", "ALPX", "ALPY", "ALPZ", "REFT", "DAMP", "ALPD", "BETD", "DMPR", "DMPS", "MU"};
  return labels;
}

/// Stores Lab = value for material `mat`, with the aliases the elements read: PRxy is also
/// NUxy (isotropic use). DAMP (stiffness-proportional damping, like BETD) stays DAMP: the
/// assembler applies it element by element (Structure::material_stiffness_damping), BETD and ALPD
/// as the element's material damping (Element::material_damping).
void store_property(DeckReader& r, const Command& c, const std::string& lab, int mat,
                    double value) {
  static const std::set<std::string> refused = {"CTEX", "CTEY", "CTEZ", "THSX", "THSY", "THSZ"};
  if (refused.count(lab) != 0)
    r.fail(c, fmt::format("{} (instantaneous expansion / thermal strain) is not supported; use "
                          "ALPX",
                          lab));
  if (std::find(material_labels().begin(), material_labels().end(), lab) == material_labels().end())
    r.fail(c, fmt::format("unknown material property '{}'", lab));
  if (mat <= 0) r.fail(c, fmt::format("material number {} must be positive", mat));
  Material& m = r.model.materials[mat];
  m.id = mat;
  m.props[lab] = value;
  if (lab.rfind("PR", 0) == 0) m.props["NU" + lab.substr(2)] = value;
  if (lab.rfind("NU", 0) == 0) m.props["PR" + lab.substr(2)] = value;
  if (lab == "DMPR" || lab == "DMPS")
    r.warn(c, fmt::format("{} is a structural damping quantity of harmonic analyses: stored, not "
                          "used by impactfe's static and transient analyses",
                          lab));
  // MU: the Coulomb coefficient of the contact elements (CONTA175, CONTA178) of this MAT;
  // COMBIN40 takes its slider force from real constants.
}

/// MP,Lab,MAT,C0,C1..C4 and the 4x form Lab,MAT,C0,C1..C4.
void set_material(DeckReader& r, const Command& c, const std::string& lab, int mat_field) {
  const int mat = r.integer(c, mat_field, r.modeling.current_mat);
  const std::string c0_text = trim(c.text(mat_field + 1));
  if (!c0_text.empty() && c0_text.front() == '%')
    r.fail(c, "tabular material properties (%TABLE%) are not supported");
  const double c0 = r.real(c, mat_field + 1, 0.0);
  for (int f = mat_field + 2; f <= mat_field + 5; ++f)
    if (r.real(c, f, 0.0) != 0.0)
      r.warn(c, "temperature coefficients C1..C4 ignored (no temperature loads)");
  for (int f = mat_field + 6; f <= c.n_fields(); ++f)
    if (!c.blank(f)) r.warn(c, fmt::format("field {} ignored", f));
  store_property(r, c, lab, mat, c0);
}

void cmd_material(DeckReader& r, const Command& c) {
  set_material(r, c, c.name, 1);
}

void cmd_mp(DeckReader& r, const Command& c) {
  if (c.blank(1)) r.fail(c, "property label missing");
  set_material(r, c, r.label(c, 1), 2);
}

/// The CDB archive form `MPTEMP,R5.0,N,SLOC,T1..` / `MPDATA,R5.0,N,Lab,MAT,SLOC,C1..`: the
/// command without its R5.0 and count fields (nullopt for the ordinary form).
std::optional<Command> archive_form(DeckReader& r, const Command& c) {
  if (r.label(c, 1) != "R5.0") return std::nullopt;
  Command plain = c;
  plain.fields.erase(plain.fields.begin(), plain.fields.begin() + std::min(2, c.n_fields()));
  return plain;
}

void cmd_mpdata(DeckReader& r, const Command& c);

void cmd_mptemp(DeckReader& r, const Command& c) {
  if (const auto plain = archive_form(r, c)) {  // each property of an archive has its table
    r.modeling.mptemp.clear();
    if (plain->last_given() > 0) cmd_mptemp(r, *plain);
    return;
  }
  // MPTEMP,SLOC,T1..T6: all blank erases the table.
  auto& t = r.modeling.mptemp;
  if (c.last_given() == 0) {
    t.clear();
    return;
  }
  const int sloc = r.integer(c, 1, static_cast<int>(t.size()) + 1);
  if (sloc < 1 || sloc > 100) r.fail(c, fmt::format("SLOC {} out of range 1..100", sloc));
  for (int k = 0; k < 6; ++k) {
    const std::size_t pos = static_cast<std::size_t>(sloc - 1 + k);
    if (k > 0 && c.blank(2 + k)) continue;
    if (t.size() <= pos) t.resize(pos + 1, 0.0);
    t[pos] = r.real(c, 2 + k, 0.0);
  }
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] < t[i - 1]) r.fail(c, "temperatures must be in non-descending order");
}

void cmd_mpdata(DeckReader& r, const Command& c) {
  if (const auto plain = archive_form(r, c)) return cmd_mpdata(r, *plain);
  // MPDATA,Lab,MAT,SLOC,C1..C6
  const std::string lab = r.label(c, 1);
  if (lab.empty()) r.fail(c, "property label missing");
  int mat = r.integer(c, 2, 1);
  if (mat == 0) mat = 1;
  const int sloc = r.integer(c, 3, 1);
  if (sloc < 1) r.fail(c, fmt::format("SLOC {} must be positive", sloc));
  std::vector<double> values;
  for (int f = 4; f <= std::min(9, c.last_given()); ++f) values.push_back(r.real(c, f, 0.0));
  if (values.empty()) r.fail(c, "no property value given");
  // One temperature only: several values are allowed only when they are all the same.
  const std::size_t n_temps = std::max<std::size_t>(1, r.modeling.mptemp.size());
  const bool constant =
      std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
  if (sloc > 1 || (values.size() > 1 && !constant && n_temps > 1) ||
      (values.size() > 1 && !constant))
    r.fail(c, fmt::format("temperature-dependent {} of material {}: only one temperature is "
                          "supported (give one value, or MP for a constant)",
                          lab, mat));
  store_property(r, c, lab, mat, values.front());
}

void cmd_mpdele(DeckReader& r, const Command& c) {
  // MPDELE,Lab,MAT1,MAT2,INC,LCHK
  const std::string lab = r.label(c, 1);
  std::vector<int> mats;
  if (r.label(c, 2) == "ALL") {
    for (const auto& [id, m] : r.model.materials) mats.push_back(id);
  } else {
    const int first = r.integer(c, 2, 1), last = r.integer(c, 3, first);
    const int inc = std::max(1, r.integer(c, 4, 1));
    for (int m = first; m <= last; m += inc) mats.push_back(m);
  }
  const std::string lchk = r.label(c, 5);
  for (int m : mats) {
    const auto it = r.model.materials.find(m);
    if (it == r.model.materials.end()) continue;
    if (lab.empty() || lab == "ALL") {
      if (lchk == "CHECK" || lchk == "WARN")
        for (const auto& [id, e] : r.model.elements)
          if (e.mat == m) {
            if (lchk == "CHECK") r.fail(c, fmt::format("material {} is used by element {}", m, id));
            r.warn(c, fmt::format("material {} is used by element {}", m, id));
            break;
          }
      r.model.materials.erase(it);
    } else {
      it->second.props.erase(lab);
      if (lab.rfind("PR", 0) == 0) it->second.props.erase("NU" + lab.substr(2));
      if (lab.rfind("NU", 0) == 0) it->second.props.erase("PR" + lab.substr(2));
    }
  }
}

// ---- TB tables ----------------------------------------------------------------------------------

bool is_plasticity(const std::string& label) {
  return label == "PLAS" || label == "BISO" || label == "BKIN" || label == "MISO" ||
         label == "MKIN" || label == "KINH";
}

MaterialTable& current_table(DeckReader& r, const Command& c) {
  if (!r.modeling.table) r.fail(c, "no TB table is active (TB first)");
  return r.model.material_tables.at(*r.modeling.table);
}

void cmd_tb(DeckReader& r, const Command& c) {
  // TB,Lab,MATID,NTEMP,NPTS,TBOPT,FuncName
  std::string lab = r.label(c, 1);
  const int mat = r.integer(c, 2, 1);
  if (mat <= 0 || mat >= 100000) r.fail(c, fmt::format("MATID {} out of range 1..99999", mat));
  const int ntemp = r.integer(c, 3, 1);
  const int npts = r.integer(c, 4, 0);
  if (ntemp < 1 || npts < 0) r.fail(c, "NTEMP must be ≥ 1 and NPTS ≥ 0");
  std::string opt = r.label(c, 5);
  if (!c.blank(6)) r.fail(c, "FuncName (function-based tables) is not supported");
  if (lab == "PLAS") {
    if (opt.empty()) opt = "MISO";
    if (opt != "BISO" && opt != "BKIN" && opt != "MISO" && opt != "KINH")
      r.fail(c, fmt::format("TB,PLAS,,,,{}: option not supported (BISO, BKIN, MISO, KINH)", opt));
  } else if (lab == "ELASTIC") {
    if (opt.empty()) opt = "ISOT";
    if (opt != "ISOT") r.fail(c, fmt::format("TB,ELASTIC,,,,{}: only ISOT is supported", opt));
  } else if (lab == "FRIC") {
    if (opt.empty()) opt = "ISO";
    if (opt != "ISO") r.fail(c, fmt::format("TB,FRIC,,,,{}: only ISO is supported", opt));
  } else if (lab == "CREEP") {
    // Implicit creep equations (TBOPT 1-3, 6, 7, 10, 11; materials/j2_plasticity.h CreepLaw).
    // TBOPT 0 / blank is explicit creep (and 100 user creep): not implemented.
    static const std::set<std::string> implicit = {"1", "2", "3", "6", "7", "10", "11"};
    if (opt.empty() || opt == "0")
      r.fail(c,
             "TB,CREEP without TBOPT is explicit creep, which is not implemented; give an "
             "implicit creep equation (TBOPT 1, 2, 3, 6, 7, 10 or 11)");
    // A TBOPT written as a number (6.0) or a parameter: its integral value.
    if (implicit.count(opt) == 0) {
      const auto value = r.opt_real(c, 5);
      if (value && *value == std::round(*value))
        opt = std::to_string(static_cast<long long>(*value));
    }
    if (implicit.count(opt) == 0)
      r.fail(c, fmt::format("TB,CREEP,,,,{}: creep equation not supported (implicit TBOPT 1, 2, "
                            "3, 6, 7, 10, 11)",
                            c.text(5)));
    if (ntemp != 1)
      r.fail(c, fmt::format("TB,CREEP: NTEMP = {}: temperature-dependent creep constants are "
                            "not implemented (one temperature)",
                            ntemp));
  } else if (lab == "HILL") {
    // Hill's anisotropic potential: only its isotropic form (all six ratios 1, von Mises) is
    // carried out; the ratios are checked where the law is built (plasticity_of).
    if (!opt.empty())
      r.fail(c, fmt::format("TB,HILL,,,,{}: only the common potential (blank TBOPT) is supported",
                            c.text(5)));
    if (ntemp != 1) r.fail(c, "TB,HILL: one temperature only");
  } else if (lab.rfind("DISC", 0) == 0) {
    // The spring-damper tables of COMBI165 (explicit dynamics): TBOPT 0 a linear elastic spring,
    // 1 a linear viscous damper, C1 the constant of either.
    lab = "DISCRETE";
    if (opt.empty()) opt = "0";
    if (const auto value = r.opt_real(c, 5); value && *value == std::round(*value))
      opt = std::to_string(static_cast<long long>(*value));
    if (opt != "0" && opt != "1")
      r.fail(c, fmt::format("TB,DISCRETE,,,,{}: only TBOPT 0 (linear elastic spring) and 1 "
                            "(linear viscous damper) are implemented; the nonlinear, "
                            "elastoplastic, Maxwell and inelastic springs (2 to 7) are not",
                            c.text(5)));
    if (ntemp != 1) r.fail(c, "TB,DISCRETE: one temperature only (NTEMP = 1)");
  } else if (lab == "FCLI") {
    // Strength limits for the failure criteria of POST1 (FC, FAIL): they do not enter the
    // solution, and impactfe computes no failure criteria, so the table is kept unused. Workbench
    // input files write it for every composite material.
    r.warn(c,
           "TB,FCLI: failure-criterion limits are read but not used: impactfe computes no "
           "failure criteria (the solution does not depend on them)");
  } else if (lab != "BISO" && lab != "BKIN" && lab != "MISO" && lab != "MKIN") {
    r.fail(c, fmt::format("TB,{}: material model not supported", lab.empty() ? "(blank)" : lab));
  }
  MaterialTable t;
  t.label = lab;
  t.option = opt;
  t.mat = mat;
  t.n_temperatures = ntemp;
  t.n_points = npts;
  t.temperatures.push_back(MaterialTable::Temperature{});
  t.where = c.where;
  const auto key = std::pair{mat, lab};
  r.model.material_tables[key] = t;
  r.modeling.table = key;
  r.modeling.table_temperature = 0;
  // One plasticity law per material: a new one replaces the old one.
  for (auto it = r.model.material_tables.begin(); it != r.model.material_tables.end();)
    it = it->first.first == mat && it->first.second != lab && is_plasticity(lab) &&
                 is_plasticity(it->first.second)
             ? r.model.material_tables.erase(it)
             : std::next(it);
}

void cmd_tbtemp(DeckReader& r, const Command& c) {
  MaterialTable& t = current_table(r, c);
  if (!c.blank(2)) r.fail(c, "KMOD (modifying a temperature) is not supported");
  const double temp = r.real(c, 1, 0.0);
  auto& temps = t.temperatures;
  // The first TBTEMP names the entry TB opened; later ones add entries in ascending order.
  if (temps.size() == 1 && temps[0].constants.empty() && temps[0].points.empty()) {
    temps[0].temperature = temp;
    r.modeling.table_temperature = 0;
    return;
  }
  if (temp <= temps.back().temperature)
    r.fail(c,
           fmt::format("temperatures must ascend ({} after {})", temp, temps.back().temperature));
  if (static_cast<int>(temps.size()) >= t.n_temperatures)
    r.fail(c, fmt::format("more temperatures than NTEMP = {}", t.n_temperatures));
  temps.push_back(MaterialTable::Temperature{temp, {}, {}});
  r.modeling.table_temperature = temps.size() - 1;
}

void cmd_tbdata(DeckReader& r, const Command& c) {
  MaterialTable& t = current_table(r, c);
  const int stloc = r.integer(c, 1, 1);
  if (stloc < 1) r.fail(c, fmt::format("STLOC {} must be positive", stloc));
  auto& values = t.temperatures[r.modeling.table_temperature].constants;
  for (int k = 0; k < 6; ++k) {
    if (c.blank(2 + k)) continue;
    const std::size_t pos = static_cast<std::size_t>(stloc - 1 + k);
    if (values.size() <= pos) values.resize(pos + 1, 0.0);
    values[pos] = r.real(c, 2 + k, 0.0);
  }
  // Laws that act at once: isotropic elasticity overrides MP,EX/PRXY; friction sets MU.
  if (t.label == "ELASTIC" && t.temperatures.size() == 1 && values.size() >= 1) {
    Material& m = r.model.materials[t.mat];
    m.id = t.mat;
    m.props["EX"] = values[0];
    if (values.size() >= 2) m.props["PRXY"] = m.props["NUXY"] = values[1];
  }
  if (t.label == "FRIC" && !values.empty()) {
    Material& m = r.model.materials[t.mat];
    m.id = t.mat;
    m.props["MU"] = values[0];
  }
}

void cmd_tbpt(DeckReader& r, const Command& c) {
  MaterialTable& t = current_table(r, c);
  std::string oper = r.label(c, 1);
  if (oper.empty()) oper = "DEFI";
  const auto x = r.opt_real(c, 2);
  if (!x) r.fail(c, "X1 missing");
  auto& pts = t.temperatures[r.modeling.table_temperature].points;
  const auto it =
      std::find_if(pts.begin(), pts.end(), [&](const auto& p) { return p.first == *x; });
  if (oper == "DELE") {
    if (it == pts.end()) r.fail(c, fmt::format("no point with X = {}", *x));
    pts.erase(it);
  } else if (oper == "DEFI") {
    const double y = r.real(c, 3, 0.0);
    if (it != pts.end()) {
      it->second = y;
    } else {
      pts.emplace_back(*x, y);
      std::sort(pts.begin(), pts.end());
    }
  } else {
    r.fail(c, fmt::format("bad Oper '{}' (DEFI, DELE)", c.text(1)));
  }
}

void cmd_tbdele(DeckReader& r, const Command& c) {
  // TBDELE,Lab,MAT1,MAT2,INC
  const std::string lab = r.label(c, 1);
  const bool all_mats = r.label(c, 2) == "ALL" || c.blank(2);
  const int first = all_mats ? 0 : r.integer(c, 2, 1);
  const int last = all_mats ? 0 : r.integer(c, 3, first);
  const int inc = std::max(1, r.integer(c, 4, 1));
  auto& tables = r.model.material_tables;
  for (auto it = tables.begin(); it != tables.end();) {
    const int m = it->first.first;
    const bool mat_ok = all_mats || (m >= first && m <= last && (m - first) % inc == 0);
    const bool lab_ok = lab.empty() || lab == "ALL" || lab == it->first.second;
    it = mat_ok && lab_ok ? tables.erase(it) : std::next(it);
  }
  if (r.modeling.table && tables.count(*r.modeling.table) == 0) r.modeling.table.reset();
}

}  // namespace

void check_material_tables(DeckReader& r, const Command& c) {
  // The laws themselves (BISO, BKIN, MISO, CREEP) are checked when the elements are built
  // (plasticity_of, at the TB command); here: element types that take neither plasticity nor
  // creep (creep uses the same inelastic material point as plasticity).
  for (const auto& [key, table] : r.model.material_tables) {
    const bool creep = table.label == "CREEP";
    if (!is_plasticity(table.label) && !creep) continue;
    for (const auto& [id, e] : r.model.elements) {
      if (e.mat != key.first) continue;
      const auto et = r.model.element_types.find(e.type);
      const ElementTypeDescriptor* type =
          et == r.model.element_types.end() ? nullptr : find_element_type(et->second.ansys_name);
      if (!type || type->plasticity || !type->needs_material) continue;
      // The types that take it, from the registry (ElementTypeDescriptor::plasticity).
      std::string with;
      for (const ElementTypeDescriptor* d : registered_element_types())
        if (d->plasticity) with += (with.empty() ? "" : ", ") + d->name;
      r.fail(c, fmt::format("material {} has TB,{}{} {} (TB at {}:{}), but element {} "
                            "({}) is elastic only; plasticity and creep are available for {}",
                            key.first, table.label,
                            table.label == "PLAS" || creep ? ",,,," + table.option : std::string(),
                            creep ? "creep" : "plasticity", table.where.file, table.where.line, id,
                            type->name, with));
    }
  }
}

void register_material_commands(std::vector<CommandSpec>& t) {
  // The 4x form Lab,MAT,C0 only for the labels ANSYS 4.2 had: DMPR, ALPD, BETD, REFT, MU as
  // commands would shadow DMPRAT and friends under the 4x four-character rule.
  static const std::vector<std::string> legacy = {"EX",   "EY",   "EZ",   "NUXY", "NUYZ", "NUXZ",
                                                  "PRXY", "PRYZ", "PRXZ", "GXY",  "GYZ",  "GXZ",
                                                  "DENS", "ALPX", "ALPY", "ALPZ", "DAMP"};
  for (const auto& lab : legacy) t.push_back({lab.c_str(), cmd_material, kPrep7});
  t.push_back({"MP", cmd_mp, kPrep7 | kSolu});
  t.push_back({"MPTEMP", cmd_mptemp, kPrep7});
  t.push_back({"MPDATA", cmd_mpdata, kPrep7 | kSolu});
  t.push_back({"MPDELE", cmd_mpdele, kPrep7});
  t.push_back({"TB", cmd_tb, kPrep7});
  t.push_back({"TBTEMP", cmd_tbtemp, kPrep7});
  t.push_back({"TBDATA", cmd_tbdata, kPrep7});
  t.push_back({"TBPT", cmd_tbpt, kPrep7});
  t.push_back({"TBDELE", cmd_tbdele, kPrep7});
}

}  // namespace impactfe::deck
