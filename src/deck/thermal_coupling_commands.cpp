// Temperatures of the thermal strain (TREF, TUNIF, BFUNIF, BF, BFDELE) and coupled DOF sets (CP,
// CPNGEN, CPSGEN, CPLGEN, CPINTF, CPDELE); docs/thermal_loads.md, docs/constraints.md.
// Temperatures are load-step state in Model::current, coupled sets model state in
// Model::coupled_sets.
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "core/dof.h"
#include "deck/modeling_helpers.h"

namespace impactfe::deck {

namespace {

void cmd_tref(DeckReader& r, const Command& c) {
  // TREF,TREF: blank is 0 (MAPDL Command Reference, TREF).
  r.model.current.reference_temperature = r.real(c, 1, 0.0);
}

void set_uniform_temperature(DeckReader& r, const Command& c, int field) {
  // TUNIF,TEMP / BFUNIF,TEMP,VALUE: a blank value is 0 (MAPDL Command Reference, TUNIF).
  if (!c.blank(field) && c.text(field).find('%') != std::string::npos)
    r.fail(c, "a uniform temperature given by a table is not implemented");
  // CDWRITE archives of MAPDL write BFUNIF,TEMP,_TINY for a uniform temperature never given: it
  // stays the default (TREF).
  if (r.label(c, field) == "_TINY" && !r.params.get("_TINY")) {
    r.model.current.uniform_temperature.reset();
    return;
  }
  r.model.current.uniform_temperature = r.real(c, field, 0.0);
}

void cmd_tunif(DeckReader& r, const Command& c) {
  set_uniform_temperature(r, c, 1);
}

void cmd_bfunif(DeckReader& r, const Command& c) {
  const std::string lab = r.label(c, 1);
  if (lab != "TEMP")
    r.fail(c, fmt::format("body load '{}' is not implemented (TEMP only)", c.text(1)));
  set_uniform_temperature(r, c, 2);
}

void cmd_bf(DeckReader& r, const Command& c) {
  // BF,NODE,Lab,VAL1 (NODE may be ALL or a component).
  const std::string lab = r.label(c, 2);
  if (lab != "TEMP")
    r.fail(c, fmt::format("body load '{}' is not implemented (TEMP only)", c.text(2)));
  if (c.text(3).find('%') != std::string::npos)
    r.fail(c, "a nodal temperature given by a table is not implemented");
  for (int f = 4; f <= c.n_fields(); ++f)
    if (!c.blank(f)) r.fail(c, fmt::format("field {}: only VAL1 is read by BF,,TEMP", f));
  const double value = r.real(c, 3, 0.0);
  LoadStep& s = r.model.current;
  for (int node : r.node_range(c, 1, 0, 0)) {
    s.node_temperatures[node] = value;
    s.temperature_where[node] = c.where;
  }
}

void cmd_bfdele(DeckReader& r, const Command& c) {
  // BFDELE,NODE,Lab
  const std::string lab = r.label(c, 2);
  if (lab != "TEMP" && lab != "ALL")
    r.fail(c, fmt::format("body load '{}' is not implemented (TEMP only)", c.text(2)));
  LoadStep& s = r.model.current;
  for (int node : r.node_range(c, 1, 0, 0)) {
    s.node_temperatures.erase(node);
    s.temperature_where.erase(node);
  }
}

/// Coupled set `id` of `dof`, new (defined at c) or existing with that DOF (else the command
/// fails: a set couples one DOF).
CoupledSet& open_set(DeckReader& r, const Command& c, int id, Dof dof) {
  CoupledSet& set = r.model.coupled_sets[id];
  if (set.nodes.empty()) {
    set.id = id;
    set.dof = dof;
    set.where = c.where;
  } else if (set.dof != dof) {
    r.fail(c,
           fmt::format("coupled set {} couples {}, not {}", id, dof_name(set.dof), dof_name(dof)));
  }
  return set;
}

void cmd_cp(DeckReader& r, const Command& c) {
  // CP,NSET,Lab,NODE1,...,NODE17: NSET blank or NEXT = the highest set number + 1, HIGH or -1 =
  // the highest; NODE1 = ALL: the selected nodes; a negative node leaves the set.
  auto& sets = r.model.coupled_sets;
  const std::string nset = r.label(c, 1);
  // CDWRITE writes coupled sets as CP commands (cdb_writer.cpp); the record form of MAPDL's own
  // archives is not documented where it could be checked, so it is refused, not guessed at.
  if (nset.rfind("R5.", 0) == 0)
    r.fail(c, fmt::format("the CDB record form CP,{} of a coupled set is not read: give the set as "
                          "CP,NSET,Lab,NODE1,...",
                          c.text(1)));
  const int highest = sets.empty() ? 0 : sets.rbegin()->first;
  int id = 0;
  if (nset.empty() || nset == "NEXT") {
    id = highest + 1;
  } else if (nset == "HIGH") {
    id = std::max(highest, 1);
  } else {
    id = r.integer(c, 1, 0);
    if (id == -1) id = std::max(highest, 1);
    if (id <= 0) r.fail(c, fmt::format("bad set number '{}'", c.text(1)));
  }
  const std::string lab = r.label(c, 2);
  const auto dof = parse_dof_label(lab);
  if (!dof) r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ)", c.text(2)));
  CoupledSet& set = open_set(r, c, id, *dof);
  std::vector<int> nodes;
  if (r.label(c, 3) == "ALL") {
    nodes = r.node_range(c, 3, 0, 0);
  } else {
    for (int f = 3; f <= std::min(c.n_fields(), 19); ++f) {
      if (c.blank(f)) continue;
      const int n = r.integer(c, f, 0);
      if (n == 0) continue;
      if (n < 0) {
        std::erase(set.nodes, -n);
        continue;
      }
      r.require_node(c, n);
      nodes.push_back(n);
    }
  }
  for (int n : nodes)
    if (std::find(set.nodes.begin(), set.nodes.end(), n) == set.nodes.end()) set.nodes.push_back(n);
  for (const auto& [other_id, other] : sets)
    if (other_id != id && other.dof == set.dof)
      for (int n : set.nodes)
        if (std::find(other.nodes.begin(), other.nodes.end(), n) != other.nodes.end())
          r.fail(c, fmt::format("node {} {} is already in coupled set {}", n, dof_name(set.dof),
                                other_id));
  if (set.nodes.empty()) sets.erase(id);
}

/// Fails at c when a node of `nodes` is already in another coupled set of `dof` than `id` (a DOF
/// belongs to one set at most).
void check_not_coupled(DeckReader& r, const Command& c, int id, Dof dof,
                       const std::vector<int>& nodes) {
  for (const auto& [other_id, other] : r.model.coupled_sets)
    if (other_id != id && other.dof == dof)
      for (int n : nodes)
        if (std::find(other.nodes.begin(), other.nodes.end(), n) != other.nodes.end())
          r.fail(c, fmt::format("node {} {} is already in coupled set {}", n, dof_name(dof),
                                other_id));
}

/// Adds a new set numbered after the highest (CPSGEN, CPLGEN: "the highest existing set number
/// + 1").
void add_next_set(DeckReader& r, const Command& c, Dof dof, std::vector<int> nodes) {
  for (int n : nodes) r.require_node(c, n);
  auto& sets = r.model.coupled_sets;
  const int id = sets.empty() ? 1 : sets.rbegin()->first + 1;
  check_not_coupled(r, c, id, dof, nodes);
  sets[id] = CoupledSet{id, dof, std::move(nodes), c.where};
}

void cmd_cpngen(DeckReader& r, const Command& c) {
  // CPNGEN,NSET,Lab,NODE1,NODE2,NINC: nodes NODE1..NODE2 by NINC (or a component) into set NSET
  // (Lab defaults to the set's own); −NODE1 removes the range from the set.
  auto& sets = r.model.coupled_sets;
  const int id = r.integer(c, 1, 0);
  if (id <= 0) r.fail(c, fmt::format("set number '{}' must be positive", c.text(1)));
  const auto existing = sets.find(id);
  std::optional<Dof> dof;
  if (!c.blank(2)) {
    dof = parse_dof_label(r.label(c, 2));
    if (!dof) r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ)", c.text(2)));
  } else if (existing != sets.end()) {
    dof = existing->second.dof;
  } else {
    r.fail(c, fmt::format("set {} does not exist: give its DOF label", id));
  }
  const bool remove = !c.blank(3) && r.label(c, 3).front() == '-';
  if (remove) {
    if (existing == sets.end()) return;
    const int first = -r.integer(c, 3, 0);
    const int last = c.blank(4) ? first : std::abs(r.integer(c, 4, first));
    const int inc = std::max(1, r.integer(c, 5, 1));
    for (int n = first; n <= last; n += inc) std::erase(existing->second.nodes, n);
    if (existing->second.nodes.empty()) sets.erase(existing);
    return;
  }
  const std::vector<int> nodes = r.node_range(c, 3, 4, 5);
  CoupledSet& set = open_set(r, c, id, *dof);
  for (int n : nodes)
    if (std::find(set.nodes.begin(), set.nodes.end(), n) == set.nodes.end()) set.nodes.push_back(n);
  check_not_coupled(r, c, id, set.dof, set.nodes);
  if (set.nodes.empty()) sets.erase(id);
}

void cmd_cpsgen(DeckReader& r, const Command& c) {
  // CPSGEN,ITIME,INC,NSET1,NSET2,NINC: ITIME − 1 copies of sets NSET1..NSET2 by NINC (−NSET1:
  // the last |NSET1| sets), their nodes incremented by INC per copy, each numbered after the
  // highest set, with the same DOF label.
  const int itime = r.integer(c, 1, 0);
  const int inc = r.integer(c, 2, 0);
  if (itime <= 1) return;  // "ITIME must be > 1 for generation to occur"
  auto& sets = r.model.coupled_sets;
  const int nset1 = r.integer(c, 3, 0);
  std::vector<CoupledSet> sources;
  if (nset1 < 0) {
    int count = -nset1;
    for (auto it = sets.rbegin(); it != sets.rend() && count > 0; ++it, --count)
      sources.insert(sources.begin(), it->second);
  } else {
    if (nset1 == 0) r.fail(c, "NSET1 (the first set to copy) is missing");
    const int nset2 = r.integer(c, 4, nset1);
    const int ninc = std::max(1, r.integer(c, 5, 1));
    for (int id = nset1; id <= nset2; id += ninc) {
      const auto it = sets.find(id);
      if (it == sets.end()) r.fail(c, fmt::format("coupled set {} does not exist", id));
      sources.push_back(it->second);
    }
  }
  // Each copy's nodes must exist (add_next_set), so the copies end within the model's nodes.
  for (int k = 1; k < itime; ++k)
    for (const CoupledSet& source : sources) {
      std::vector<int> nodes;
      for (int n : source.nodes) {
        const long long node = n + static_cast<long long>(k) * inc;
        if (node <= 0 || node > std::numeric_limits<int>::max())
          r.fail(c, fmt::format("copy {} of coupled set {} would take node {}, which cannot exist",
                                k, source.id, node));
        nodes.push_back(static_cast<int>(node));
      }
      add_next_set(r, c, source.dof, std::move(nodes));
    }
}

void cmd_cplgen(DeckReader& r, const Command& c) {
  // CPLGEN,NSETF,Lab1,...,Lab5: a new set of the nodes of set NSETF for each label.
  const int from = r.integer(c, 1, 0);
  const auto it = r.model.coupled_sets.find(from);
  if (it == r.model.coupled_sets.end())
    r.fail(c, fmt::format("coupled set {} does not exist", c.text(1)));
  const std::vector<int> nodes = it->second.nodes;
  for (int f = 2; f <= 6; ++f) {
    if (c.blank(f)) continue;
    const auto dof = parse_dof_label(r.label(c, f));
    if (!dof) r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ)", c.text(f)));
    add_next_set(r, c, *dof, nodes);
  }
}

void cmd_cpintf(DeckReader& r, const Command& c) {
  // CPINTF,Lab,TOLER: one coupled set per group of coincident selected nodes (all coordinates
  // within TOLER, default 1e-4) for Lab (ALL: UX..ROTZ), numbered after the highest set.
  const std::string lab = r.label(c, 1);
  std::vector<Dof> dofs;
  if (lab == "ALL") {
    dofs.assign(kAllDofs.begin(), kAllDofs.end());
  } else if (const auto d = parse_dof_label(lab)) {
    dofs = {*d};
  } else {
    r.fail(c, fmt::format("bad DOF label '{}' (UX UY UZ ROTX ROTY ROTZ ALL)", c.text(1)));
  }
  const double tol = r.real(c, 2, 1e-4) > 0.0 ? r.real(c, 2, 1e-4) : 1e-4;
  std::vector<std::pair<Vec3, int>> nodes;
  for (const auto& [id, n] : r.model.nodes)
    if (r.node_selected(id)) nodes.emplace_back(n.x, id);
  std::sort(nodes.begin(), nodes.end(),
            [](const auto& a, const auto& b) { return a.first.x() < b.first.x(); });
  // Union of coincident pairs (a sweep along x: only nodes within tol in x are compared).
  std::vector<std::size_t> root(nodes.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = i;
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t j = i + 1; j < nodes.size() && nodes[j].first.x() - nodes[i].first.x() <= tol;
         ++j)
      if ((nodes[j].first - nodes[i].first).cwiseAbs().maxCoeff() <= tol) {
        const std::size_t a = find(i), b = find(j);
        if (a != b) root[std::max(a, b)] = std::min(a, b);
      }
  std::map<std::size_t, std::vector<int>> groups;
  for (std::size_t i = 0; i < nodes.size(); ++i) groups[find(i)].push_back(nodes[i].second);
  auto& sets = r.model.coupled_sets;
  for (Dof d : dofs)
    for (auto& [key, ids] : groups) {
      if (ids.size() < 2) continue;
      std::sort(ids.begin(), ids.end());
      const int id = sets.empty() ? 1 : sets.rbegin()->first + 1;
      for (const auto& [other_id, other] : sets)
        if (other.dof == d)
          for (int n : ids)
            if (std::find(other.nodes.begin(), other.nodes.end(), n) != other.nodes.end())
              r.fail(c, fmt::format("node {} {} is already in coupled set {}", n, dof_name(d),
                                    other_id));
      sets[id] = CoupledSet{id, d, ids, c.where};
    }
}

void cmd_cpdele(DeckReader& r, const Command& c) {
  // CPDELE,NSET1,NSET2,NINC (NSET1 = ALL: every set)
  auto& sets = r.model.coupled_sets;
  if (r.label(c, 1) == "ALL") {
    sets.clear();
    return;
  }
  const int first = r.integer(c, 1, 0);
  const int last = r.integer(c, 2, first);
  const int inc = std::max(1, r.integer(c, 3, 1));
  for (int id = first; id <= last; id += inc) sets.erase(id);
}

}  // namespace

void register_thermal_coupling_commands(std::vector<CommandSpec>& t) {
  t.push_back({"TREF", cmd_tref, kPrepSolu});
  t.push_back({"TUNIF", cmd_tunif, kPrepSolu});
  t.push_back({"BFUNIF", cmd_bfunif, kPrepSolu});
  t.push_back({"BF", cmd_bf, kPrepSolu});
  t.push_back({"BFDELE", cmd_bfdele, kPrepSolu});
  t.push_back({"CP", cmd_cp, kPrepSolu});
  t.push_back({"CPNGEN", cmd_cpngen, kPrepSolu});
  t.push_back({"CPSGEN", cmd_cpsgen, kPrepSolu});
  t.push_back({"CPLGEN", cmd_cplgen, kPrepSolu});
  t.push_back({"CPINTF", cmd_cpintf, kPrepSolu});
  t.push_back({"CPDELE", cmd_cpdele, kPrepSolu});
}

}  // namespace impactfe::deck
