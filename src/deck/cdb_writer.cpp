// CDWRITE,DB: the model as a CDB archive (cdb_writer.h).
#include "deck/cdb_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/dof.h"

namespace impactfe::deck {

namespace {

/// A real that reads back to the same double (17 significant digits).
std::string exact(double v) {
  return fmt::format("{:.16E}", v);
}

/// Column width of the NBLOCK reals: "-1.2345678901234567E+308" is 24 characters.
constexpr int kRealWidth = 25;

void write_types(const Model& m, std::ostream& out) {
  for (const auto& [id, et] : m.element_types) {
    out << fmt::format("ET,{},{}\n", id, et.ansys_name);
    for (int k = 1; k < static_cast<int>(et.keyopt.size()); ++k)
      if (et.key(k) != 0) out << fmt::format("KEYOPT,{},{},{}\n", id, k, et.key(k));
  }
}

// RLBLOCK,NSET,MAXSET,MAXITEMS,NPERLN: (2i8,6g25.16) for the first record of a set, (7g25.16)
// for its continuation records.
void write_real_sets(const Model& m, std::ostream& out) {
  if (m.real_sets.empty()) return;
  std::size_t most = 0;
  for (const auto& [id, s] : m.real_sets) most = std::max(most, s.values.size());
  out << fmt::format("RLBLOCK,{},{},{},7\n(2i8,6e{}.16)\n(7e{}.16)\n", m.real_sets.size(),
                     m.real_sets.rbegin()->first, most, kRealWidth, kRealWidth);
  for (const auto& [id, s] : m.real_sets) {
    out << fmt::format("{:8d}{:8d}", id, s.values.size());
    for (std::size_t k = 0; k < s.values.size(); ++k) {
      if (k == 6 || (k > 6 && (k - 6) % 7 == 0)) out << '\n';
      out << fmt::format("{:>{}}", exact(s.values[k]), kRealWidth);
    }
    out << '\n';
  }
}

void write_materials(const Model& m, std::ostream& out) {
  for (const auto& [id, mat] : m.materials)
    for (const auto& [label, value] : mat.props)
      out << fmt::format("MPTEMP,R5.0,1,1,0.0,\nMPDATA,R5.0,1,{},{},1,{},\n", label, id,
                         exact(value));
  for (const auto& [key, t] : m.material_tables) {
    out << fmt::format("TB,{},{},{},{},{}\n", t.label, t.mat, t.temperatures.size(), t.n_points,
                       t.option);
    for (const auto& temp : t.temperatures) {
      out << fmt::format("TBTEMP,{}\n", exact(temp.temperature));
      for (std::size_t k = 0; k < temp.constants.size(); k += 6) {
        out << fmt::format("TBDATA,{}", k + 1);
        for (std::size_t j = k; j < std::min(k + 6, temp.constants.size()); ++j)
          out << ',' << exact(temp.constants[j]);
        out << '\n';
      }
      for (const auto& [x, y] : temp.points)
        out << fmt::format("TBPT,DEFI,{},{}\n", exact(x), exact(y));
    }
  }
}

void write_sections(const Model& m, std::ostream& out) {
  for (const auto& [id, s] : m.sections) {
    out << fmt::format("SECTYPE,{},{},{}\n", id, s.type, s.subtype);
    // A layered shell section: one SECDATA per layer, bottom first.
    const std::vector<std::vector<double>> lines =
        s.layers.empty() ? std::vector<std::vector<double>>{s.data} : s.layers;
    for (const std::vector<double>& line : lines) {
      if (line.empty()) continue;
      out << "SECDATA";
      for (double v : line) out << ',' << exact(v);
      out << '\n';
    }
    if (!s.offset.empty()) out << fmt::format("SECOFFSET,{}\n", s.offset);
    if (!s.controls.empty()) {
      out << "SECCONTROL";
      for (std::size_t k = 0; k < s.controls.size(); ++k)
        out << ',' << (k == 1 ? std::string() : exact(s.controls[k]));
      out << '\n';
    }
  }
}

// LOCAL,R5.0,LOC|ANG|PRM,KCN,KCS,...: the local systems (11 and up) as MAPDL's archives give
// them: origin, then the angles of the axes, then the shape parameters (1, 1: not elliptical).
// Each record makes its system active, so the block ends with CSYS,0, as MAPDL's archives do.
void write_coordinate_systems(const Model& m, std::ostream& out) {
  bool any = false;
  for (const auto& [id, cs] : m.coordinate_systems.systems()) {
    if (id <= 10) continue;
    const int kind = static_cast<int>(cs.kind);
    const Vec3 angles = angles_from_rotation(cs.axes);
    // The angles must give back the same axes: a SOLVE with elements or nodes in the system
    // would otherwise differ from the original in the last bits.
    if (rotation_from_angles(angles) != cs.axes)
      throw std::invalid_argument(fmt::format(
          "the axes of local system {} are not reproduced exactly by the angles a CDB holds "
          "(THXY THYZ THZX {} {} {})",
          id, exact(angles[0]), exact(angles[1]), exact(angles[2])));
    out << fmt::format("LOCAL,R5.0,LOC,{},{},{},{},{}\n", id, kind, exact(cs.origin[0]),
                       exact(cs.origin[1]), exact(cs.origin[2]));
    out << fmt::format("LOCAL,R5.0,ANG,{},{},{},{},{}\n", id, kind, exact(angles[0]),
                       exact(angles[1]), exact(angles[2]));
    out << fmt::format("LOCAL,R5.0,PRM,{},{},{},{}\n", id, kind, exact(1.0), exact(1.0));
    any = true;
  }
  if (any) out << "CSYS,0\n";
}

// NBLOCK,6,SOLID: node, solid-model entity, line location (both 0), X Y Z THXY THYZ THZX.
void write_nodes(const Model& m, std::ostream& out) {
  if (m.nodes.empty()) return;
  out << fmt::format("NBLOCK,6,SOLID,{},{}\n(3i10,6e{}.16)\n", m.nodes.rbegin()->first,
                     m.nodes.size(), kRealWidth);
  for (const auto& [id, n] : m.nodes) {
    out << fmt::format("{:10d}{:10d}{:10d}", id, 0, 0);
    for (int k = 0; k < 3; ++k) out << fmt::format("{:>{}}", exact(n.x[k]), kRealWidth);
    if (n.rotated())
      for (int k = 0; k < 3; ++k) out << fmt::format("{:>{}}", exact(n.angles_deg[k]), kRealWidth);
    out << '\n';
  }
  out << "N,R5.3,LOC,-1,\n";
}

// EBLOCK,19,SOLID (19i10): MAT TYPE REAL SECNUM ESYS death solid-model shape NNODES 0 ID, the
// first 8 nodes, further nodes 19 to a continuation line; -1 ends the block.
void write_elements(const Model& m, std::ostream& out) {
  if (m.elements.empty()) return;
  out << fmt::format("EBLOCK,19,SOLID,{},{}\n(19i10)\n", m.elements.rbegin()->first,
                     m.elements.size());
  for (const auto& [id, e] : m.elements) {
    if (!e.superelement_file.empty())
      throw std::invalid_argument(
          fmt::format("element {} is a superelement (MATRIX50): not written to a CDB", id));
    out << fmt::format("{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}{:10d}", e.mat,
                       e.type, e.real, e.secnum, e.esys, 0, 0, 0, e.nodes.size(), 0, id);
    for (std::size_t k = 0; k < e.nodes.size(); ++k) {
      if (k == 8 || (k > 8 && (k - 8) % 19 == 0)) out << '\n';
      out << fmt::format("{:10d}", e.nodes[k]);
    }
    out << '\n';
  }
  out << fmt::format("{:10d}\n", -1);
}

// CMBLOCK,Cname,Entity,NUMITEMS (8i10): ascending ids, a run of consecutive ids as first, -last.
void write_components(const Model& m, std::ostream& out) {
  for (const auto& [name, comp] : m.components) {
    if (comp.entity != "NODE" && comp.entity != "ELEM") continue;  // solid-model components
    std::vector<long long> items;
    for (std::size_t k = 0; k < comp.ids.size();) {
      std::size_t j = k;
      while (j + 1 < comp.ids.size() && comp.ids[j + 1] == comp.ids[j] + 1) ++j;
      items.push_back(comp.ids[k]);
      if (j > k) items.push_back(-static_cast<long long>(comp.ids[j]));
      k = j + 1;
    }
    out << fmt::format("CMBLOCK,{},{},{}\n(8i10)\n", name, comp.entity, items.size());
    for (std::size_t k = 0; k < items.size(); ++k)
      out << fmt::format("{:10d}", items[k])
          << ((k + 1) % 8 == 0 || k + 1 == items.size() ? "\n" : "");
  }
}

// CP,NSET,Lab,NODE1,...,NODE17: the coupled sets as CP commands (the prime node first), a set
// of more nodes continued by further CP commands of the same set, which add to it.
void write_coupled_sets(const Model& m, std::ostream& out) {
  for (const auto& [id, set] : m.coupled_sets)
    for (std::size_t k = 0; k < set.nodes.size(); k += 17) {
      out << fmt::format("CP,{},{}", id, dof_name(set.dof));
      for (std::size_t j = k; j < std::min(k + 17, set.nodes.size()); ++j)
        out << ',' << set.nodes[j];
      out << '\n';
    }
}

// CE,R5.0,DEFI,NTERMS,NEQN,CONST and CE,R5.0,NODE records of two terms each (node, DOF,
// coefficient), the slave first: the form of MAPDL's archives.
void write_constraint_equations(const Model& m, std::ostream& out) {
  for (const auto& [id, eq] : m.constraint_equations) {
    out << fmt::format("CE,R5.0,DEFI,{},{},{}\n", eq.terms.size(), id, exact(eq.constant));
    for (std::size_t k = 0; k < eq.terms.size(); k += 2) {
      out << "CE,R5.0,NODE";
      for (std::size_t j = k; j < std::min(k + 2, eq.terms.size()); ++j)
        out << fmt::format(",{},{},{}", eq.terms[j].dof.node, dof_name(eq.terms[j].dof.dof),
                           exact(eq.terms[j].coefficient));
      out << '\n';
    }
  }
}

// CERIG,MASTE,SLAVE,Ldof,...: the rigid regions, one command per slave. impactfe writes a
// region's equations when the structure is built, where the DOFs the elements carry make it 3-D
// or 2-D; kept as CERIG, the region read back gives the same equations in the same order.
void write_rigid_regions(const Model& m, std::ostream& out) {
  for (const RigidRegion& region : m.rigid_regions) {
    // The single labels, when given, are the whole list the equations are written for
    // (RigidRegion::only); otherwise the groups.
    std::vector<std::string> labels;
    for (Dof d : region.only) labels.emplace_back(dof_name(d));
    if (region.only.empty()) {
      if (region.translations && region.rotations)
        labels.emplace_back("ALL");
      else
        labels.emplace_back(region.translations ? "UXYZ" : "RXYZ");
    }
    if (labels.size() > 5)
      throw std::invalid_argument(fmt::format(
          "the rigid region of master node {} ({}:{}) has more DOF labels than one CERIG holds",
          region.master, region.where.file, region.where.line));
    for (int slave : region.slaves) {
      out << fmt::format("CERIG,{},{}", region.master, slave);
      for (const std::string& label : labels) out << ',' << label;
      out << '\n';
    }
  }
}

// SFE,ELEM,LKEY,PRES,1,R5.0 and the values at the face's corners on the next line: the form of
// MAPDL's archives.
void write_surface_loads(const LoadStep& s, std::ostream& out) {
  for (const auto& [face, load] : s.pressures) {
    out << fmt::format("SFE,{},{},PRES,1,R5.0\n", face.element, face.face);
    for (double v : load.values) out << fmt::format("{:>{}}", exact(v), kRealWidth);
    out << '\n';
  }
}

/// What a CDB written here cannot hold in the current load step: refused, so that an archive
/// never reads back as a different model.
void refuse_unwritten_loads(const Model& m) {
  const LoadStep& s = m.current;
  if (!s.constraint_tables.empty() || !s.force_tables.empty())
    throw std::invalid_argument(
        "table (%TABLE%) constraints and forces are not written to a CDB: write the archive "
        "before applying them");
  for (const auto& [face, load] : s.pressures)
    if (load.tabular())
      throw std::invalid_argument(fmt::format(
          "the pressure on face {} of element {} is a table (%{}%): table loads are not written "
          "to a CDB",
          face.face, face.element, load.table));
  for (const std::string& table : s.acel_tables)
    if (!table.empty())
      throw std::invalid_argument(
          fmt::format("ACEL by the table %{}% is not written to a CDB", table));
  if (!s.forces_imag.empty())
    throw std::invalid_argument("imaginary parts of forces (F VALUE2) are not written to a CDB");
  if (s.load_vector_scale != 0.0)
    throw std::invalid_argument("LVSCALE load vectors are not written to a CDB");
  if (!m.gap_conditions.empty())
    throw std::invalid_argument(
        fmt::format("gap conditions (GP, the first at {}:{}) are not written to a CDB",
                    m.gap_conditions.front().where.file, m.gap_conditions.front().where.line));
}

void write_loads(const Model& m, std::ostream& out) {
  const LoadStep& s = m.current;
  for (const auto& [key, value] : s.constraints)
    if (!s.constraint_tables.count(key))
      out << fmt::format("D,{},{},{}\n", key.node, dof_name(key.dof), exact(value));
  for (const auto& [key, value] : s.forces)
    if (!s.force_tables.count(key))
      out << fmt::format("F,{},{},{}\n", key.node, force_name(key.dof), exact(value));
  write_surface_loads(s, out);
  for (const auto& [key, ic] : m.initial_conditions)
    out << fmt::format("IC,{},{},{},{}\n", key.node, dof_name(key.dof), exact(ic.displacement),
                       exact(ic.velocity));
  for (const auto& key : m.masters) out << fmt::format("M,{},{}\n", key.node, dof_name(key.dof));
  // Temperatures of the thermal strain: TREF, the uniform temperature, the node temperatures.
  if (s.reference_temperature != 0.0)
    out << fmt::format("TREF,{}\n", exact(s.reference_temperature));
  if (s.uniform_temperature) out << fmt::format("BFUNIF,TEMP,{}\n", exact(*s.uniform_temperature));
  for (const auto& [node, value] : s.node_temperatures)
    out << fmt::format("BF,{},TEMP,{}\n", node, exact(value));
  if (s.acel != Vec3::Zero())
    out << fmt::format("ACEL,{},{},{}\n", exact(s.acel[0]), exact(s.acel[1]), exact(s.acel[2]));
  const RotationalLoads& w = s.rotation;
  const std::pair<const char*, const Vec3*> rotational[] = {{"OMEGA", &w.omega},
                                                            {"DOMEGA", &w.domega},
                                                            {"CGLOC", &w.cg_location},
                                                            {"CGOMGA", &w.cg_omega},
                                                            {"DCGOMG", &w.cg_domega}};
  for (const auto& [name, v] : rotational)
    if (*v != Vec3::Zero())
      out << fmt::format("{},{},{},{}\n", name, exact((*v)(0)), exact((*v)(1)), exact((*v)(2)));
}

}  // namespace

void write_cdb(const Model& m, std::ostream& out) {
  refuse_unwritten_loads(m);
  out << "/COM,impactfe CDB archive (CDWRITE,DB): mesh, materials, sections, components, loads\n";
  out << "/PREP7\n";
  write_types(m, out);
  write_real_sets(m, out);
  write_materials(m, out);
  write_sections(m, out);
  write_coordinate_systems(m, out);
  write_nodes(m, out);
  write_elements(m, out);
  write_components(m, out);
  write_coupled_sets(m, out);
  write_constraint_equations(m, out);
  write_rigid_regions(m, out);
  write_loads(m, out);
  out << "FINISH\n";
}

}  // namespace impactfe::deck
