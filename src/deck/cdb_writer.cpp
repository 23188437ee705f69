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

void write_loads(const Model& m, std::ostream& out) {
  const LoadStep& s = m.current;
  for (const auto& [key, value] : s.constraints)
    if (!s.constraint_tables.count(key))
      out << fmt::format("D,{},{},{}\n", key.node, dof_name(key.dof), exact(value));
  for (const auto& [key, value] : s.forces)
    if (!s.force_tables.count(key))
      out << fmt::format("F,{},{},{}\n", key.node, force_name(key.dof), exact(value));
  if (!s.constraint_tables.empty() || !s.force_tables.empty() || !s.pressures.empty())
    throw std::invalid_argument(
        "table loads and surface loads are not written to a CDB yet: write the archive before "
        "applying them");
  for (const auto& [key, ic] : m.initial_conditions)
    out << fmt::format("IC,{},{},{},{}\n", key.node, dof_name(key.dof), exact(ic.displacement),
                       exact(ic.velocity));
  for (const auto& key : m.masters) out << fmt::format("M,{},{}\n", key.node, dof_name(key.dof));
  if (!m.gap_conditions.empty())
    throw std::invalid_argument("gap conditions (GP) are not written to a CDB");
  if (s.acel != Vec3::Zero())
    out << fmt::format("ACEL,{},{},{}\n", exact(s.acel[0]), exact(s.acel[1]), exact(s.acel[2]));
}

}  // namespace

void write_cdb(const Model& m, std::ostream& out) {
  out << "/COM,impactfe CDB archive (CDWRITE,DB): mesh, materials, sections, components, loads\n";
  out << "/PREP7\n";
  write_types(m, out);
  write_real_sets(m, out);
  write_materials(m, out);
  write_sections(m, out);
  write_nodes(m, out);
  write_elements(m, out);
  write_components(m, out);
  write_loads(m, out);
  out << "FINISH\n";
}

}  // namespace impactfe::deck
