// POST1 (APDL_SCRIPTING §D): SET, FILE, the element table (ETABLE, PRETAB, SSUM), sorting
// (NSORT, ESORT, NUSORT, EUSORT) and force sums (FSUM, NFORCE, FORCE). The listings PRNSOL,
// PRESOL, PRRSOL are in post1_print.cpp, the pictures in post1_plot_commands.cpp.
#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "deck/element_forces.h"
#include "deck/post1_path.h"
#include "deck/post1_print.h"
#include "deck/post_support.h"

namespace impactfe::deck {

namespace {

/// "load step 1: substeps 1..101" lines of the sets of the file, for error messages.
std::string available_sets(const std::vector<ResultSet>& sets) {
  std::string out;
  for (std::size_t k = 0; k < sets.size();) {
    std::size_t j = k;
    while (j + 1 < sets.size() && sets[j + 1].analysis == sets[k].analysis &&
           sets[j + 1].load_step == sets[k].load_step)
      ++j;
    out += fmt::format("{}load step {} substep{} {}", out.empty() ? "" : "; ", sets[k].load_step,
                       j > k ? "s" : "",
                       j > k ? fmt::format("{}..{}", sets[k].substep, sets[j].substep)
                             : std::to_string(sets[k].substep));
    k = j + 1;
  }
  return out.empty() ? "none" : out;
}

/// Index of the current set in the set list (-1 when interpolated or unknown).
int current_index(const PostState& ps) {
  if (!ps.current || ps.current->interpolated) return -1;
  for (std::size_t k = 0; k < ps.sets.size(); ++k)
    if (ps.sets[k].number == ps.current->set.number) return static_cast<int>(k);
  return -1;
}

void cmd_results_set(DeckReader& r, const Command& c) {
  // SET,Lstep,Sbstep,Fact,KIMG,TIME,ANGLE,NSET,ORDER
  const ResultsReader& reader = results(r, c);
  PostState& ps = post_state(r);
  const auto& sets = ps.sets;
  const std::string l = r.label(c, 1);
  if (l == "LIST") {
    print_set_list(r, sets);
    return;
  }
  if (sets.empty()) r.fail(c, fmt::format("the results file {} holds no data set", ps.path));
  if (r.real(c, 4, 0.0) != 0.0) r.warn(c, "KIMG ignored (no complex results)");
  if (!c.blank(6) && r.real(c, 6, 0.0) != 0.0) r.warn(c, "ANGLE ignored (no harmonic elements)");
  std::optional<std::size_t> pick;
  std::optional<double> at_time;
  const int nset = r.integer(c, 7, 0);
  const auto time = r.opt_real(c, 5);
  if (nset > 0) {
    if (nset > static_cast<int>(sets.size()))
      r.fail(c, fmt::format("data set {} does not exist (the file has {})", nset, sets.size()));
    pick = static_cast<std::size_t>(nset - 1);
  } else if (l == "FIRST") {
    pick = 0;
  } else if (l == "LAST") {
    pick = sets.size() - 1;
  } else if (l == "NEXT" || l == "PREVIOUS" || l == "PREV") {
    current_set(r, c);
    const int k = current_index(ps);
    const int n = static_cast<int>(sets.size());
    pick = static_cast<std::size_t>(l == "NEXT" ? (k + 1) % n : (k <= 0 ? n - 1 : k - 1));
  } else if (l == "NEAR") {
    const double t = time.value_or(sets.front().time);
    std::size_t best = 0;
    for (std::size_t k = 1; k < sets.size(); ++k)
      if (std::fabs(sets[k].time - t) < std::fabs(sets[best].time - t)) best = k;
    pick = best;
  } else if ((l.empty() || r.integer(c, 1, 0) == 0) &&
             (c.blank(2) || (r.label(c, 2) != "LAST" && r.integer(c, 2, 0) == 0)) && time) {
    at_time = *time;
  } else {
    const int ls = l.empty() ? 1 : r.integer(c, 1, 1);
    // Sbstep blank or 0 (a zero field is a blank one): the last substep (MAPDL SET).
    const bool last_sub = c.blank(2) || r.label(c, 2) == "LAST" || r.integer(c, 2, 0) == 0;
    const int sbs = last_sub ? 0 : r.integer(c, 2, 1);
    for (std::size_t k = 0; k < sets.size(); ++k) {
      if (sets[k].load_step != ls) continue;
      if (last_sub) {
        // The last substep of the load step; a modal analysis's first mode.
        if (sets[k].mode > 0 && pick && sets[*pick].mode > 0) continue;
        pick = k;
      } else if (sets[k].substep == sbs) {
        pick = k;  // the last analysis with this load step and substep wins
      }
    }
    if (!pick)
      r.fail(c, fmt::format("load step {}{} is not on the results file {} (it has {})", ls,
                            last_sub ? "" : fmt::format(" substep {}", sbs), ps.path,
                            available_sets(sets)));
  }
  SetData data;
  try {
    if (at_time) {
      // Between two stored times: linear interpolation; outside: the nearest end (§D.1).
      std::vector<std::size_t> timed;
      for (std::size_t k = 0; k < sets.size(); ++k)
        if (sets[k].mode == 0) timed.push_back(k);
      if (timed.empty()) r.fail(c, "SET at a TIME needs time points (the file holds modes only)");
      std::size_t hi = timed.size();
      for (std::size_t k = 0; k < timed.size(); ++k)
        if (sets[timed[k]].time >= *at_time - 1e-12 * std::max(1.0, std::fabs(*at_time))) {
          hi = k;
          break;
        }
      if (hi == timed.size()) {
        data = read_set(reader, sets[timed.back()]);
      } else if (hi == 0 || same_time(sets[timed[hi]].time, *at_time)) {
        data = read_set(reader, sets[timed[hi]]);
      } else {
        data = interpolate_sets(read_set(reader, sets[timed[hi - 1]]),
                                read_set(reader, sets[timed[hi]]), *at_time);
      }
    } else {
      data = read_set(reader, sets[*pick]);
    }
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
  const double fact = r.real(c, 3, 0.0);
  if (fact != 0.0 && fact != 1.0) scale_set(data, fact);
  Log::info("{}:{}: SET: load step {} substep {} {}={:.6g}{}", c.where.file, c.where.line,
            data.set.load_step, data.set.substep, data.set.mode > 0 ? "FREQ" : "TIME",
            data.set.time, data.interpolated ? " (interpolated)" : "");
  make_current(r, std::move(data));
}

void cmd_shell(DeckReader& r, const Command& c) {
  // SHELL,Loc: the surface of a shell whose stresses POST1 reports (MAPDL SHELL; TOP default).
  std::string loc = c.blank(1) ? "TOP" : r.label(c, 1);
  // MAPDL reads the label's first letters: SHELL,BOTTOM is BOT, SHELL,MIDDLE is MID.
  if (loc == "BOTTOM") loc = "BOT";
  if (loc == "MIDDLE") loc = "MID";
  if (loc != "TOP" && loc != "MID" && loc != "BOT")
    r.fail(c, fmt::format("Loc '{}': TOP, MID or BOT", c.text(1)));
  post_state(r).shell_location = loc;
}

void cmd_layer(DeckReader& r, const Command& c) {
  // LAYER,NUM: the layer of a layered shell whose TOP, MID or BOT surface (SHELL) POST1 reports;
  // 0 (blank) the section's own top, middle and bottom (MAPDL LAYER).
  const std::string key = c.blank(1) ? "" : r.label(c, 1);
  if (key == "FCMAX")
    r.fail(c, "NUM FCMAX: failure criteria (FC) are not carried out (a layer number)");
  const int layer = r.integer(c, 1, 0);
  if (layer < 0) r.fail(c, fmt::format("layer number {} must not be negative", layer));
  post_state(r).layer = layer;
}

void cmd_rsys(DeckReader& r, const Command& c) {
  // RSYS,KCN: the results coordinate system (MAPDL RSYS; KCN blank = 0) of the nodal vector
  // results and of the element stress and strain components (rotated from the element's
  // result axes at the element's centroid or, for nodal averages, at the node). SOLU: the
  // components as the elements give them and the nodal vectors in the nodal axes. LSYS (layer
  // systems) is not carried out.
  const std::string key = c.blank(1) ? "" : r.label(c, 1);
  PostState& ps = post_state(r);
  if (key == "SOLU") {
    ps.rsys.reset();
    ps.rsys_solution = true;
    return;
  }
  if (key == "LSYS")
    r.fail(c, "KCN LSYS: layer coordinate systems are not carried out (a number or SOLU)");
  const int kcn = r.integer(c, 1, 0);
  if (!r.model.coordinate_systems.has(kcn))
    r.fail(c, fmt::format("coordinate system {} is not defined", kcn));
  ps.rsys = kcn;
  ps.rsys_solution = false;
}

void cmd_file(DeckReader& r, const Command& c) {
  // FILE,Fname,Ext: the results file of the postprocessors; a blank Fname is the jobname
  // (MAPDL FILE: "Fname ... defaults to Jobname"), e.g. FILE,,RDSP after a reduced transient.
  PostState& ps = post_state(r);
  ps.file_command = results_file_name(c.blank(1) ? r.model.jobname : c.text(1), c.text(2));
  ps.reader.reset();
  ps.current.reset();
  results(r, c);  // open it now: a missing file is an error here
}

std::string default_label(const std::string& item, const std::string& comp) {
  return item.substr(0, 4) + comp.substr(0, 4);
}

void fill_column(DeckReader& r, const Command& c, EtableColumn& col) {
  col.values.clear();
  bool any = false;
  for (int e : require_selected_elements(r, c)) {
    const auto v = element_result(r, c, e, col.item, col.comp);
    if (v) any = true;
    col.values[e] = v && std::isfinite(*v) ? *v : 0.0;  // MAPDL: 0 where an element has none
  }
  if (!any)
    r.fail(c, fmt::format("item {}{}{} is not available for any selected element", col.item,
                          col.comp.empty() ? "" : ",", col.comp));
}

void cmd_etable(DeckReader& r, const Command& c) {
  // ETABLE,Lab,Item,Comp,Option
  PostState& ps = post_state(r);
  // A label has at most 8 characters: a longer one is known by its first 8, here and wherever
  // it is named (column()).
  const std::string given = r.label(c, 1);
  const std::string lab = given.substr(0, 8);
  if (given.size() > 8)
    r.warn(c, fmt::format("label '{}' is longer than 8 characters: taken as '{}'", given, lab));
  const std::string item = r.label(c, 2);
  if (lab == "REFL") {
    for (auto& col : ps.etable) fill_column(r, c, col);
    return;
  }
  if (lab == "ERAS" || (lab.empty() && item == "ERAS")) {
    ps.etable.clear();
    return;
  }
  if (lab == "STAT") {
    std::string out = "\n STATUS OF ELEMENT TABLE\n\n   LABEL    ITEM COMP\n";
    for (const auto& col : ps.etable)
      out += fmt::format("   {:<8} {:<4} {}\n", col.label, col.item, col.comp);
    print(r, out);
    return;
  }
  auto existing = std::find_if(ps.etable.begin(), ps.etable.end(),
                               [&](const EtableColumn& e) { return e.label == lab; });
  if (item == "ERAS") {
    if (existing == ps.etable.end()) r.fail(c, fmt::format("no element-table column '{}'", lab));
    ps.etable.erase(existing);
    return;
  }
  if (item.empty()) r.fail(c, "Item missing");
  const std::string option = r.label(c, 4);
  if (!option.empty() && option != "AVG" && option != "MIN" && option != "MAX")
    r.fail(c, fmt::format("Option '{}': AVG, MIN or MAX", option));
  EtableColumn col;
  col.item = item;
  col.comp = r.label(c, 3);
  col.label = lab.empty() ? default_label(item, col.comp).substr(0, 8) : lab;
  fill_column(r, c, col);
  existing = std::find_if(ps.etable.begin(), ps.etable.end(),
                          [&](const EtableColumn& e) { return e.label == col.label; });
  if (existing != ps.etable.end()) {
    *existing = std::move(col);
  } else {
    if (ps.etable.size() >= 200) r.fail(c, "the element table holds 200 columns already");
    ps.etable.push_back(std::move(col));
  }
}

const EtableColumn& column(DeckReader& r, const Command& c, const std::string& label) {
  const PostState& ps = post_state(r);
  const auto it = std::find_if(ps.etable.begin(), ps.etable.end(), [&](const EtableColumn& e) {
    return e.label == label.substr(0, 8);
  });
  if (it == ps.etable.end())
    r.fail(c, fmt::format("no element-table column '{}' (ETABLE first)", label));
  return *it;
}

double column_value(const EtableColumn& col, int element) {
  const auto it = col.values.find(element);
  return it == col.values.end() ? 0.0 : it->second;
}

void cmd_pretab(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  std::vector<const EtableColumn*> cols;
  if (c.last_given() == 0 || r.label(c, 1) == "ALL") {
    for (const auto& col : ps.etable) cols.push_back(&col);
  } else {
    for (int f = 1; f <= c.last_given(); ++f) {
      if (c.blank(f)) continue;
      const std::string l = r.label(c, f);
      // GRPn: the n-th group of ten stored columns (MAPDL PRETAB), unless a column has the name.
      const bool named = std::any_of(ps.etable.begin(), ps.etable.end(),
                                     [&](const EtableColumn& col) { return col.label == l; });
      if (!named && l.size() > 3 && l.compare(0, 3, "GRP") == 0 &&
          l.find_first_not_of("0123456789", 3) == std::string::npos) {
        const std::size_t group = std::stoul(l.substr(3));
        if (group == 0 || 10 * (group - 1) >= ps.etable.size())
          r.fail(c, fmt::format("{}: the element table has {} columns", l, ps.etable.size()));
        for (std::size_t k = 10 * (group - 1); k < std::min(ps.etable.size(), 10 * group); ++k)
          cols.push_back(&ps.etable[k]);
        continue;
      }
      cols.push_back(&column(r, c, l));
    }
  }
  if (cols.empty()) r.fail(c, "the element table is empty (ETABLE first)");
  std::vector<int> elements = require_selected_elements(r, c);
  if (ps.element_order) {
    std::vector<int> sorted;
    for (int e : *ps.element_order)
      if (std::binary_search(elements.begin(), elements.end(), e)) sorted.push_back(e);
    elements = sorted;
  }
  std::vector<std::string> labels;
  std::vector<std::vector<double>> values(cols.size());
  for (std::size_t k = 0; k < cols.size(); ++k) {
    labels.push_back(cols[k]->label);
    for (int e : elements) values[k].push_back(column_value(*cols[k], e));
  }
  print(r, element_table_listing(elements, labels, values));
}

void cmd_ssum(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (ps.etable.empty()) r.fail(c, "the element table is empty (ETABLE first)");
  const std::vector<int> elements = require_selected_elements(r, c);
  std::string out =
      "\n SUM ALL THE ACTIVE ENTRIES IN THE ELEMENT TABLE\n\n TABLE LABEL     TOTAL\n";
  for (const auto& col : ps.etable) {
    double sum = 0.0;
    for (int e : elements) sum += column_value(col, e);
    ps.ssum[col.label] = sum;
    out += fmt::format(" {:<8}  {}\n", col.label, listing_number(sum, 14));
  }
  print(r, out);
}

/// Sorts `ids` by value (ORDER 0 descending, 1 ascending; KABS 1 by |value|), keeps NUMB, and
/// records the extremes for *GET SORT.
std::vector<int> sort_ids(DeckReader& r, const Command& c, std::vector<int> ids,
                          const std::function<double(int)>& value, int order_field) {
  const int order = r.integer(c, order_field, 0);
  const bool kabs = r.integer(c, order_field + 1, 0) == 1;
  const int numb = r.integer(c, order_field + 2, 0);
  auto key = [&](int id) { return kabs ? std::fabs(value(id)) : value(id); };
  std::stable_sort(ids.begin(), ids.end(),
                   [&](int a, int b) { return order == 1 ? key(a) < key(b) : key(a) > key(b); });
  SortResult s;
  s.imax = *std::max_element(ids.begin(), ids.end(), [&](int a, int b) { return key(a) < key(b); });
  s.imin = *std::min_element(ids.begin(), ids.end(), [&](int a, int b) { return key(a) < key(b); });
  s.max = key(s.imax);
  s.min = key(s.imin);
  post_state(r).sort = s;
  if (numb > 0 && numb < static_cast<int>(ids.size())) ids.resize(static_cast<std::size_t>(numb));
  return ids;
}

void cmd_esort(DeckReader& r, const Command& c) {
  // ESORT,Item,Lab,ORDER,KABS,NUMB (Item = ETAB)
  if (r.label(c, 1) != "ETAB") r.fail(c, "Item must be ETAB");
  const EtableColumn col = column(r, c, r.label(c, 2));
  post_state(r).element_order = sort_ids(
      r, c, require_selected_elements(r, c), [&](int e) { return column_value(col, e); }, 3);
}

void cmd_nsort(DeckReader& r, const Command& c) {
  // NSORT,Item,Comp,ORDER,KABS,NUMB,SEL
  const std::string lab = nodal_label_of(r.label(c, 1), r.label(c, 2));
  if (lab.empty())
    r.fail(c, fmt::format("item {},{} not supported (U, ROT, V, A with X, Y, Z or SUM; RF)",
                          r.label(c, 1), r.label(c, 2)));
  if (!c.blank(6)) r.fail(c, "SEL is not supported (sort first, then NSEL)");
  const auto ids = require_selected_nodes(r, c);
  std::map<int, double> v;
  for (int n : ids) v[n] = nodal_result(r, c, n, lab);
  post_state(r).node_order = sort_ids(
      r, c, ids, [&](int n) { return v.at(n); }, 3);
}

void cmd_unsort(DeckReader& r, const Command& c) {
  if (c.name == "NUSORT")
    post_state(r).node_order.reset();
  else
    post_state(r).element_order.reset();
}

void cmd_force(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1).empty() ? "TOTAL" : r.label(c, 1);
  if (l != "TOTAL" && l != "STATIC" && l != "DAMP" && l != "INERT")
    r.fail(c, fmt::format("'{}': TOTAL, STATIC, DAMP or INERT", c.text(1)));
  post_state(r).force_kind = l;
}

void cmd_fsum(DeckReader& r, const Command& c) {
  // FSUM,Lab,Item: selected nodes, forces of the selected elements (global Cartesian).
  if (!r.label(c, 1).empty() && r.label(c, 1) != "RSYS")
    r.fail(c, fmt::format("Lab '{}': blank or RSYS", c.text(1)));
  if (r.label(c, 1) == "RSYS") r.warn(c, "RSYS: the sums are in the global Cartesian system");
  const std::vector<int> nodes = require_selected_nodes(r, c);
  const auto sums = nodal_force_sums(r, c, require_selected_elements(r, c));
  std::array<double, 6> total{};
  for (int n : nodes) {
    const auto it = sums.find(n);
    if (it == sums.end()) continue;
    const Vec3 f(it->second[0], it->second[1], it->second[2]);
    const Vec3 m = r.model.node(n).x.cross(f);
    for (int k = 0; k < 3; ++k) {
      total[static_cast<std::size_t>(k)] += f[k];
      total[static_cast<std::size_t>(k + 3)] += m[k] + it->second[static_cast<std::size_t>(k + 3)];
    }
  }
  post_state(r).fsum = total;
  static const char* kNames[6] = {"FX", "FY", "FZ", "MX", "MY", "MZ"};
  std::string out =
      "\n *** NOTE ***\n SUMMATION OF TOTAL FORCES AND MOMENTS IN THE GLOBAL "
      "COORDINATE SYSTEM\n\n";
  for (int k = 0; k < 6; ++k)
    out += fmt::format("  {}  = {}\n", kNames[k],
                       listing_number(total[static_cast<std::size_t>(k)], 14));
  out += "  SUMMATION POINT=  0.0000       0.0000       0.0000\n";
  print(r, out);
}

void cmd_nforce(DeckReader& r, const Command& c) {
  // NFORCE,Item: element nodal force sums at each selected node, then the total.
  const std::vector<int> nodes = require_selected_nodes(r, c);
  const auto sums = nodal_force_sums(r, c, require_selected_elements(r, c));
  std::string out = "\n  ***** SUMMATION OF ELEMENT NODAL FORCES *****\n\n" +
                    set_heading(current_set(r, c)) + "\n    NODE";
  for (const char* l : {"FX", "FY", "FZ", "MX", "MY", "MZ"}) out += fmt::format(" {:>12}", l);
  out += "\n";
  NodalForce total{};
  for (int n : nodes) {
    const auto it = sums.find(n);
    if (it == sums.end()) continue;
    out += fmt::format("{:8d}", n);
    for (std::size_t k = 0; k < 6; ++k) {
      out += " " + listing_number(it->second[k]);
      total[k] += it->second[k];
    }
    out += "\n";
  }
  out += "\n   TOTAL";
  for (double v : total) out += " " + listing_number(v);
  print(r, out + "\n");
}

// AVPRIN,KEY,EFFNU: how nodal principal stresses are averaged (post_state.h); EFFNU (the
// effective Poisson's ratio of equivalent strains) only as MAPDL's automatic choice.
void cmd_avprin(DeckReader& r, const Command& c) {
  const int key = r.integer(c, 1, 0);
  if (key != 0 && key != 1) r.fail(c, fmt::format("KEY = {}: 0 or 1", key));
  if (r.real(c, 2, 0.0) != 0.0)
    r.fail(c,
           "EFFNU: a given effective Poisson's ratio is not supported (blank or 0: the "
           "material's for elastic strains)");
  post_state(r).average_principal = key;
}

}  // namespace

void register_post1_commands(std::vector<CommandSpec>& t) {
  t.push_back({"SET", cmd_results_set, kPost1});
  t.push_back({"FILE", cmd_file, kPost1 | kPost26});
  t.push_back({"SHELL", cmd_shell, kPost1});
  t.push_back({"LAYER", cmd_layer, kPost1});
  t.push_back({"RSYS", cmd_rsys, kPost1});
  t.push_back({"AVPRIN", cmd_avprin, kPost1 | kPost26});
  t.push_back({"ETABLE", cmd_etable, kPost1});
  t.push_back({"PRETAB", cmd_pretab, kPost1});
  t.push_back({"SSUM", cmd_ssum, kPost1});
  t.push_back({"ESORT", cmd_esort, kPost1});
  t.push_back({"NSORT", cmd_nsort, kPost1});
  t.push_back({"NUSORT", cmd_unsort, kPost1});
  t.push_back({"EUSORT", cmd_unsort, kPost1});
  t.push_back({"FORCE", cmd_force, kPost1 | kPost26});
  t.push_back({"FSUM", cmd_fsum, kPost1});
  t.push_back({"NFORCE", cmd_nforce, kPost1});
  register_post1_print_commands(t);
  register_post1_path_commands(t);
}

}  // namespace impactfe::deck
