// POST1 listings: PRNSOL, PRESOL, PRRSOL, SET,LIST and the PRETAB table (APDL_SCRIPTING §D.2-4,
// §D.7). Layout after MAPDL's listings (headings, 5-significant-digit numbers, MAXIMUM /
// MINIMUM / TOTAL lines) so that a user can diff them.
#include "deck/post1_print.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

#include "deck/element_forces.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

std::string columns_heading(const char* first, const std::vector<std::string>& labels) {
  std::string out = fmt::format("\n    {:<4}", first);
  for (const auto& l : labels) out += fmt::format("  {:>11}", l);
  return out + "\n";
}

/// Rows of `ids` ordered as the last sort (NSORT / ESORT) when there is one.
std::vector<int> in_sort_order(std::vector<int> ids, const std::optional<std::vector<int>>& order) {
  if (!order) return ids;
  std::vector<int> out;
  for (int id : *order)
    if (std::binary_search(ids.begin(), ids.end(), id)) out.push_back(id);
  return out;
}

/// " MAXIMUM ABSOLUTE VALUES" block: per column the row with the largest |value|.
std::string max_abs_block(const std::vector<int>& ids,
                          const std::vector<std::vector<double>>& columns, const char* what) {
  std::string nodes = fmt::format(" {:<6}", what), values = " VALUE ";
  for (const auto& col : columns) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < col.size(); ++k)
      if (std::fabs(col[k]) > std::fabs(col[best])) best = k;
    const bool any = !col.empty() && col[best] != 0.0;
    nodes += fmt::format("  {:>11}", any ? ids[best] : 0);
    values += " " + listing_number(col.empty() ? 0.0 : col[best]);
  }
  return "\n MAXIMUM ABSOLUTE VALUES\n" + nodes + "\n" + values + "\n";
}

}  // namespace

NodalItem nodal_item(DeckReader& r, const Command& c, const std::string& item_in,
                     const std::string& comp_in) {
  const std::string item = to_upper(item_in), comp = to_upper(comp_in);
  NodalItem out;
  out.heading = item;
  auto dofs = [&](const std::string& base, std::vector<std::string> all, const std::string& sum) {
    if (comp.empty() || comp == "COMP") {
      for (const auto& l : all) out.labels.push_back(base + l);
      if (!sum.empty()) out.labels.push_back(sum);
    } else if (comp == "SUM") {
      out.labels = {sum};
    } else if (std::find(all.begin(), all.end(), comp) != all.end()) {
      out.labels = {base + comp};
    } else {
      r.fail(c, fmt::format("{}: Comp '{}' unknown", item, comp_in));
    }
    out.elements.assign(out.labels.size(), "");
  };
  if (item == "U" || item.empty()) {
    out.heading = "U";
    dofs("U", {"X", "Y", "Z"}, "USUM");
  } else if (item == "ROT") {
    dofs("ROT", {"X", "Y", "Z"}, "ROTSUM");
  } else if (item == "V" || item == "A") {
    dofs(item, {"X", "Y", "Z"}, item + "SUM");
  } else if (item == "DOF") {
    dofs("", {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"}, "");
  } else if (item == "S" || item == "EPEL") {
    out.element_item = item;
    std::vector<std::string> comps;
    if (comp.empty() || comp == "COMP")
      comps = {"X", "Y", "Z", "XY", "YZ", "XZ"};
    else if (comp == "PRIN")
      comps = {"1", "2", "3", "INT", "EQV"};
    else
      comps = {comp};
    for (const auto& k : comps) {
      out.labels.push_back(item.substr(0, 1) + k);
      out.elements.push_back(k);
    }
  } else if (item == "EPPL" || item == "EPCR") {
    // Plastic and creep strain: the components (engineering shears) and the equivalent of the
    // elements that report them (NL items of a plastic or creep material).
    out.element_item = item;
    static const std::vector<std::string> all = {"X", "Y", "Z", "XY", "YZ", "XZ"};
    std::vector<std::string> comps;
    if (comp.empty() || comp == "COMP")
      comps = all;
    else if (comp == "EQV" || std::find(all.begin(), all.end(), comp) != all.end())
      comps = {comp};
    else
      r.fail(c,
             fmt::format("{}: Comp '{}' unknown (X, Y, Z, XY, YZ, XZ, EQV, COMP)", item, comp_in));
    for (const auto& k : comps) {
      out.labels.push_back(item + k);
      out.elements.push_back(k);
    }
  } else {
    r.fail(c, fmt::format("item '{}' not supported (U, ROT, DOF, V, A, S, EPEL, EPPL, EPCR)",
                          item_in));
  }
  return out;
}

std::optional<double> element_item_value_at_node(DeckReader& r, const Command& c,
                                                 const NodalItem& item, std::size_t k, int e,
                                                 int node) {
  const int direction = tensor_direction(item.elements[k]);
  static const std::array<const char*, 6> kComponents = {"X", "Y", "Z", "XY", "YZ", "XZ"};
  // The element's values extrapolated to this node when it has them, else its centroid value.
  const ElementTypeDescriptor* d = find_element_type(element_type_name(r, e));
  std::optional<std::map<int, std::vector<double>>> at;
  const auto at_node = [&](const std::string& comp) -> std::optional<double> {
    if (d == nullptr) return std::nullopt;
    const auto seq = find_result_sequence(*d, item.element_item, comp);
    if (!seq) return std::nullopt;
    // A shell's surface items at the SHELL location (TOP, MID, BOT).
    const auto column = std::find(d->result_names.begin(), d->result_names.end(),
                                  shell_location_column(r, seq->name));
    if (column == d->result_names.end()) return std::nullopt;
    if (!at) at = element_nodal_results(r, c, e);
    if (at->count(node) == 0) return std::nullopt;
    // A homogeneous element of a type whose layered elements have more columns.
    const auto index = static_cast<std::size_t>(column - d->result_names.begin());
    if (index >= at->at(node).size()) return std::nullopt;
    return at->at(node)[index];
  };
  std::optional<double> v;
  if (direction >= 0 && is_tensor_item(item.element_item)) {
    // A stress or strain component: the element's tensor at the node (or its centroid values;
    // absent components 0 in its axes), rotated into the results system at the node.
    std::array<std::optional<double>, 6> six;
    for (std::size_t i = 0; i < six.size(); ++i) six[i] = at_node(kComponents[i]);
    if (std::none_of(six.begin(), six.end(), [](const auto& x) { return x.has_value(); }))
      for (std::size_t i = 0; i < six.size(); ++i)
        six[i] = stored_element_result(r, c, e, item.element_item, kComponents[i]);
    if (std::any_of(six.begin(), six.end(), [](const auto& x) { return x.has_value(); })) {
      std::array<double, 6> stored{};
      for (std::size_t i = 0; i < six.size(); ++i)
        stored[i] = six[i] && std::isfinite(*six[i]) ? *six[i] : 0.0;
      v = tensor_in_results_system(r, c, e, item.element_item, stored, direction,
                                   r.model.node(node).x);
    }
  } else {
    v = at_node(item.elements[k]);
    if (!v) v = stored_element_result(r, c, e, item.element_item, item.elements[k]);
  }
  if (v && !std::isfinite(*v)) return std::nullopt;
  return v;
}

std::optional<double> nodal_item_value(DeckReader& r, const Command& c, const NodalItem& item,
                                       std::size_t k, int node) {
  if (item.element_item.empty()) return nodal_result(r, c, node, item.labels[k]);
  // AVPRIN,0 (MAPDL's default): a principal stress, the stress intensity or the von Mises stress
  // at a node from the averaged components (AVPRIN,1: the elements' own values averaged, as for
  // every strain here).
  const std::string& comp = item.elements[k];
  const bool derived = comp == "1" || comp == "2" || comp == "3" || comp == "INT" || comp == "EQV";
  if (derived && item.element_item == "S" && post_state(r).average_principal == 0) {
    const NodalItem components = nodal_item(r, c, "S", "COMP");
    std::array<double, 6> s{};
    bool complete = true;
    for (std::size_t j = 0; j < 6 && complete; ++j) {
      const auto v = nodal_item_value(r, c, components, j, node);
      complete = v.has_value();
      if (v) s[j] = *v;
    }
    if (complete) {
      Eigen::Matrix3d t;
      t << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
      const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(t).eigenvalues();
      if (comp == "1") return e[2];
      if (comp == "2") return e[1];
      if (comp == "3") return e[0];
      if (comp == "INT") return e[2] - e[0];
      return std::sqrt(0.5 * ((e[2] - e[1]) * (e[2] - e[1]) + (e[1] - e[0]) * (e[1] - e[0]) +
                              (e[2] - e[0]) * (e[2] - e[0])));
    }
  }
  double sum = 0.0;
  int n = 0;
  for (int e : selected_elements(r)) {
    const auto& nodes = r.model.elements.at(e).nodes;
    if (std::find(nodes.begin(), nodes.end(), node) == nodes.end()) continue;
    if (const auto v = element_item_value_at_node(r, c, item, k, e, node)) {
      sum += *v;
      ++n;
    }
  }
  if (n == 0) return std::nullopt;
  return sum / n;  // element values at the node averaged
}

std::string element_table_listing(const std::vector<int>& elements,
                                  const std::vector<std::string>& labels,
                                  const std::vector<std::vector<double>>& columns) {
  std::string out =
      "\n PRINT ELEMENT TABLE ITEMS PER ELEMENT\n\n   *****  POST1 ELEMENT TABLE "
      "LISTING *****\n\n    STAT  ";
  for (std::size_t k = 0; k < labels.size(); ++k) out += fmt::format("  {:>11}", "CURRENT");
  out += columns_heading("ELEM", labels);
  for (std::size_t i = 0; i < elements.size(); ++i) {
    out += fmt::format("{:8d}", elements[i]);
    for (const auto& col : columns) out += " " + listing_number(col[i]);
    out += "\n";
  }
  for (const char* which : {"MINIMUM", "MAXIMUM"}) {
    std::string ids = " ELEM  ", values = " VALUE ";
    for (const auto& col : columns) {
      const auto it = which[1] == 'I' ? std::min_element(col.begin(), col.end())
                                      : std::max_element(col.begin(), col.end());
      ids += fmt::format("  {:>11}", elements[static_cast<std::size_t>(it - col.begin())]);
      values += " " + listing_number(*it);
    }
    out += fmt::format("\n {} VALUES\n{}\n{}\n", which, ids, values);
  }
  return out;
}

void print_set_list(DeckReader& r, const std::vector<ResultSet>& sets) {
  std::string out =
      "\n *****  INDEX OF DATA SETS ON RESULTS FILE  *****\n\n   SET   TIME/FREQ    "
      "LOAD STEP   SUBSTEP  CUMULATIVE\n";
  for (const auto& s : sets)
    out += fmt::format("{:6d} {} {:9d} {:9d} {:9d}\n", s.number, listing_number(s.time, 12),
                       s.load_step, s.substep, s.number);
  print(r, out);
}

namespace {

void cmd_prnsol(DeckReader& r, const Command& c) {
  // PRNSOL,Item,Comp: one row per selected node (NSORT order), then the maximum absolute values.
  const NodalItem item = nodal_item(r, c, r.label(c, 1), r.label(c, 2));
  const SetData& set = current_set(r, c);
  const auto nodes = in_sort_order(require_selected_nodes(r, c), post_state(r).node_order);
  std::vector<int> rows;
  std::vector<std::vector<double>> columns(item.labels.size());
  for (int n : nodes) {
    std::vector<std::optional<double>> v;
    for (std::size_t k = 0; k < item.labels.size(); ++k)
      v.push_back(nodal_item_value(r, c, item, k, n));
    if (std::none_of(v.begin(), v.end(), [](const auto& x) { return x.has_value(); })) continue;
    rows.push_back(n);
    for (std::size_t k = 0; k < v.size(); ++k) columns[k].push_back(v[k].value_or(0.0));
  }
  const bool dof = item.element_item.empty();
  std::string out = fmt::format(
      "\n PRINT {:<4} NODAL SOLUTION PER NODE\n\n  ***** POST1 {} "
      "LISTING *****\n\n",
      item.heading, dof ? "NODAL DEGREE OF FREEDOM" : "NODAL ELEMENT SOLUTION");
  out += set_heading(set);
  const PostState& ps = post_state(r);
  const std::string system = ps.rsys_solution ? "THE SOLUTION COORDINATE SYSTEMS"
                             : ps.rsys && *ps.rsys != 0
                                 ? fmt::format("COORDINATE SYSTEM {}", *ps.rsys)
                                 : "THE GLOBAL COORDINATE SYSTEM";
  out += fmt::format("\n  THE FOLLOWING {} RESULTS ARE IN {}\n",
                     dof ? "DEGREE OF FREEDOM" : "X,Y,Z", system);
  if (!dof) out += "  (element values at the nodes averaged)\n";
  out += columns_heading("NODE", item.labels);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out += fmt::format("{:8d}", rows[i]);
    for (const auto& col : columns) out += " " + listing_number(col[i]);
    out += "\n";
  }
  if (rows.empty()) r.fail(c, fmt::format("no selected node has {} results", item.heading));
  out += max_abs_block(rows, columns, "NODE");
  print(r, out);
}

void cmd_presol(DeckReader& r, const Command& c) {
  // PRESOL,Item,Comp: per element type, one row per selected element (ESORT order).
  const std::string item = r.label(c, 1), comp = r.label(c, 2);
  const SetData& set = current_set(r, c);
  const auto elements = in_sort_order(require_selected_elements(r, c), post_state(r).element_order);
  std::string out = fmt::format(
      "\n PRINT {} ELEMENT SOLUTION PER ELEMENT\n\n  ***** POST1 "
      "ELEMENT SOLUTION LISTING *****\n\n",
      item.empty() ? "ELEM" : item);
  out += set_heading(set);
  bool any = false;
  if (item == "F" || item == "M") {
    // Element nodal forces / moments, one line per element node.
    const std::size_t first = item == "F" ? 0 : 3;
    const char* names[6] = {"FX", "FY", "FZ", "MX", "MY", "MZ"};
    out += fmt::format("\n    EL= element, NODE, {} {} {} in global axes\n", names[first],
                       names[first + 1], names[first + 2]);
    for (int e : elements) {
      out += fmt::format("\n    EL={:8d}\n", e);
      for (const auto& [node, f] : element_nodal_forces(r, c, e)) {
        out += fmt::format("{:12d}", node);
        for (std::size_t k = first; k < first + 3; ++k) out += " " + listing_number(f[k]);
        out += "\n";
      }
    }
    print(r, out);
    return;
  }
  // Group the elements by type name, each group with its own columns.
  std::map<std::string, std::vector<int>> groups;
  for (int e : elements) groups[element_type_name(r, e)].push_back(e);
  for (const auto& [type, ids] : groups) {
    const ElementTypeDescriptor* d = find_element_type(type);
    if (d == nullptr) continue;
    std::vector<std::pair<std::string, std::string>> cols;  // (item, comp)
    if (item.empty() || item == "ELEM") {
      for (const auto& n : d->result_names) cols.emplace_back(n, "");
    } else if (comp.empty()) {
      for (const auto& s : d->result_sequences)
        if (s.item == item) cols.emplace_back(s.item, s.comp);
      if (cols.empty() && find_result_sequence(*d, item, "")) cols.emplace_back(item, "");
    } else if (find_result_sequence(*d, item, comp)) {
      cols.emplace_back(item, comp);
    }
    if (cols.empty()) continue;
    std::vector<std::string> labels;
    for (const auto& [i, k] : cols) labels.push_back(k.empty() ? i : i + k);
    std::vector<std::vector<double>> values(cols.size());
    for (int e : ids)
      for (std::size_t k = 0; k < cols.size(); ++k) {
        const auto v = element_result(r, c, e, cols[k].first, cols[k].second);
        values[k].push_back(v && std::isfinite(*v) ? *v : 0.0);
      }
    any = true;
    out += fmt::format("\n  ELEMENT TYPE {}\n", type) + columns_heading("ELEM", labels);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      out += fmt::format("{:8d}", ids[i]);
      for (const auto& col : values) out += " " + listing_number(col[i]);
      out += "\n";
    }
  }
  if (!any)
    r.fail(c, fmt::format("no selected element has results for {}{}{}",
                          item.empty() ? "ELEM" : item, comp.empty() ? "" : ",", comp));
  print(r, out);
}

void cmd_prrsol(DeckReader& r, const Command& c) {
  // PRRSOL,Lab: reactions at the selected constrained nodes and their totals.
  const std::string lab = r.label(c, 1);
  std::vector<std::string> labels;
  if (lab.empty())
    labels = {"FX", "FY", "FZ", "MX", "MY", "MZ"};
  else if (lab == "F")
    labels = {"FX", "FY", "FZ"};
  else if (lab == "M")
    labels = {"MX", "MY", "MZ"};
  else if (parse_force_label(lab))
    labels = {lab};
  else
    r.fail(c, fmt::format("Lab '{}': FX..MZ, F or M", c.text(1)));
  const ResultsReader& reader = results(r, c);
  const SetData& set = current_set(r, c);
  std::vector<int> rows;
  std::vector<std::vector<double>> columns(labels.size());
  std::vector<bool> used(labels.size(), false);
  for (int n : require_selected_nodes(r, c)) {
    const int row = node_row(reader.node_ids(), n);
    std::vector<double> v;
    bool any = false;
    for (std::size_t k = 0; k < labels.size(); ++k) {
      v.push_back(nodal_value(set, row, *parse_nodal_item(labels[k])));
      any = any || std::isfinite(v.back());
      used[k] = used[k] || std::isfinite(v.back());
    }
    if (!any) continue;
    rows.push_back(n);
    for (std::size_t k = 0; k < v.size(); ++k)
      columns[k].push_back(std::isfinite(v[k]) ? v[k] : 0.0);
  }
  if (rows.empty()) r.fail(c, "no selected node has a reaction (no constrained DOF selected)");
  std::vector<std::string> shown;
  std::vector<std::vector<double>> shown_cols;
  for (std::size_t k = 0; k < labels.size(); ++k)
    if (used[k]) {
      shown.push_back(labels[k]);
      shown_cols.push_back(columns[k]);
    }
  std::string out =
      "\n PRINT REACTION SOLUTIONS PER NODE\n\n  ***** POST1 TOTAL REACTION "
      "SOLUTION LISTING *****\n\n" +
      set_heading(set) + "\n  THE FOLLOWING X,Y,Z SOLUTIONS ARE IN THE GLOBAL COORDINATE SYSTEM\n" +
      columns_heading("NODE", shown);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out += fmt::format("{:8d}", rows[i]);
    for (const auto& col : shown_cols) out += " " + listing_number(col[i]);
    out += "\n";
  }
  out += "\n  TOTAL VALUES\n VALUE  ";
  for (const auto& col : shown_cols) {
    double sum = 0.0;
    for (double v : col) sum += v;
    out += " " + listing_number(sum);
  }
  print(r, out + "\n");
}

}  // namespace

void register_post1_print_commands(std::vector<CommandSpec>& t) {
  t.push_back({"PRNSOL", cmd_prnsol, kPost1});
  t.push_back({"PRESOL", cmd_presol, kPost1});
  t.push_back({"PRRSOL", cmd_prrsol, kPost1});
}

}  // namespace impactfe::deck
