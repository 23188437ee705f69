// *GET (APDL_SCRIPTING §B) and the *GET items of the results, the POST1/POST26 state and the
// model database beyond get_hooks.cpp's model items: a GetItemProvider, so *VGET (and *GET)
// reach them through the one item registry. Results come from the current POST1 set / the
// POST26 variables (the results file written by the solution host); a request that cannot be
// satisfied is an error naming it.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>

#include "deck/get_hooks.h"
#include "deck/post1_path.h"
#include "deck/post1_print.h"
#include "deck/post26.h"
#include "deck/post_support.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

/// The start of the run, for *GET ACTIVE TIME WALL (the elapsed wall-clock time).
const auto kRunStart = std::chrono::steady_clock::now();

/// The fields of a *GET / *VGET after Par: Entity, ENTNUM, Item1, IT1NUM, Item2, IT2NUM.
struct GetRequest {
  std::string entity, entnum, item1, it1num, item2, it2num;
  std::string what() const {
    std::string s = entity;
    for (const auto* f : {&entnum, &item1, &it1num, &item2, &it2num})
      if (!f->empty()) s += "," + *f;
    return s;
  }
};

/// A result that is a number or a character value (JOBNAM, ETYP names).
struct GetValue {
  double number = 0.0;
  std::optional<std::string> text;
};

int integer_field(DeckReader& r, const Command& c, const GetRequest& g, const std::string& text);
double real_field(DeckReader& r, const Command& c, const GetRequest& g, const std::string& text);

[[noreturn]] void unsupported(DeckReader& r, const Command& c, const GetRequest& g,
                              const std::string& known) {
  r.fail(c, fmt::format("{} is not supported (known for {}: {})", g.what(), g.entity, known));
}

/// *GET NODE items. `vector`: a *VGET loop, where an absent node gives 0.
double get_node(DeckReader& r, const Command& c, const GetRequest& g, int n, bool vector) {
  const std::string& i1 = g.item1;
  // COUNT, NUM MAX/MIN, NSEL, NXTH/NXTL and LOC are get_hooks.cpp's model items.
  if (n == 0) {
    if (i1 == "NUM" && (g.it1num == "MAXD" || g.it1num == "MIND")) {
      if (r.model.nodes.empty()) return 0.0;
      return g.it1num == "MAXD" ? r.model.nodes.rbegin()->first : r.model.nodes.begin()->first;
    }
    if ((i1 == "MNLOC" || i1 == "MXLOC") &&
        (g.it1num == "X" || g.it1num == "Y" || g.it1num == "Z")) {
      // The least / greatest coordinate of the selected nodes (global Cartesian: in another
      // active system the coordinate would be that system's, not done here).
      if (r.model.coordinate_systems.active != 0)
        r.fail(c, fmt::format("{}: only in the global Cartesian system (CSYS,0); CSYS {} is "
                              "active",
                              g.what(), r.model.coordinate_systems.active));
      const int axis = g.it1num[0] - 'X';
      std::optional<double> out;
      for (const auto& [id, node] : r.model.nodes) {
        if (!r.model.selection.nodes.selected(id)) continue;
        const double v = node.x(axis);
        if (!out || (i1 == "MNLOC" ? v < *out : v > *out)) out = v;
      }
      return out.value_or(0.0);
    }
    unsupported(r, c, g, "ENTNUM 0: COUNT, NUM MAX/MIN/MAXD/MIND, MNLOC/MXLOC X/Y/Z");
  }
  const bool defined = r.model.nodes.count(n) != 0;
  if (!defined) {
    if (vector) return 0.0;
    r.fail(c, fmt::format("{}: node {} is not defined", g.what(), n));
  }
  const Node& node = r.model.node(n);
  if (i1 == "ANG") {
    if (g.it1num == "XY") return node.angles_deg[0];
    if (g.it1num == "YZ") return node.angles_deg[1];
    if (g.it1num == "ZX") return node.angles_deg[2];
  }
  if (i1 == "D" || i1 == "F") {
    const auto dof = i1 == "D" ? parse_dof_label(g.it1num) : parse_force_label(g.it1num);
    if (dof) {
      const auto& table = i1 == "D" ? r.model.current.constraints : r.model.current.forces;
      const auto it = table.find(DofKey{n, *dof});
      if (it != table.end()) return it->second;
      return i1 == "D" ? 2e100 : 0.0;  // MAPDL: a huge value for "no constraint"
    }
  }
  if ((i1 == "S" || i1 == "EPEL" || i1 == "EPPL" || i1 == "EPCR") && !g.it1num.empty()) {
    // The nodal stress of PRNSOL: the mean over the selected elements at the node of their
    // element values (post1_print.cpp, nodal_item_value).
    const NodalItem item = nodal_item(r, c, i1, g.it1num);
    if (item.labels.size() != 1)
      r.fail(c,
             fmt::format("{}: NODE {} needs one component ({} X, 1, EQV, ...)", g.what(), i1, i1));
    const auto v = nodal_item_value(r, c, item, 0, n);
    if (!v) {
      if (vector) return 0.0;
      r.fail(c, fmt::format("{}: node {} has no {} {} (no selected element with it)", g.what(), n,
                            i1, g.it1num));
    }
    return *v;
  }
  const std::string lab = nodal_label_of(i1, g.it1num);
  if (!lab.empty()) {
    if (vector) {
      // *VGET: absent results are 0 rather than errors.
      const ResultsReader& reader = results(r, c);
      const int row = node_row(reader.node_ids(), n);
      const double v = nodal_value(current_set(r, c), row, *parse_nodal_item(lab));
      return std::isfinite(v) ? v : 0.0;
    }
    return nodal_result(r, c, n, lab);
  }
  unsupported(
      r, c, g,
      "LOC, ANG, U, ROT, V, A, RF, D, F, S, EPEL, EPPL, EPCR, NSEL, NXTH, NXTL, COUNT, NUM");
}

/// LENG: the distance between an element's first and last node; 0 for a point element
/// (MASS21) and for one whose nodes come from elsewhere (a MATRIX50 read from its file).
double element_length(const DeckReader& r, const ElementRecord& e) {
  if (e.nodes.size() < 2) return 0.0;
  return (r.model.node(e.nodes.back()).x - r.model.node(e.nodes.front()).x).norm();
}

double get_element(DeckReader& r, const Command& c, const GetRequest& g, int e, bool vector) {
  const std::string& i1 = g.item1;
  // COUNT, NUM MAX/MIN, ESEL, NXTH/NXTL, NODE, CENT and ATTR MAT/TYPE/REAL/SECN are
  // get_hooks.cpp's model items.
  if (e == 0) unsupported(r, c, g, "ENTNUM 0: COUNT, NUM MAX/MIN");
  const bool defined = r.model.elements.count(e) != 0;
  if (!defined) {
    if (vector) return 0.0;
    r.fail(c, fmt::format("{}: element {} is not defined", g.what(), e));
  }
  const ElementRecord& rec = r.model.elements.at(e);
  if (i1 == "ATTR") {
    if (g.it1num == "ESYS") return static_cast<double>(rec.esys);
    if (g.it1num == "ENAM") {
      const ElementTypeDescriptor* d = find_element_type(element_type_name(r, e));
      return d != nullptr ? d->number : 0.0;
    }
  }
  if (i1 == "LENG") return element_length(r, rec);
  if (i1 == "VOLU" || i1 == "GEOM") {
    const auto v = element_volume(r, c, e);
    if (!v) {
      if (vector) return 0.0;
      r.fail(c, fmt::format("{}: a {} has no volume", g.what(), element_type_name(r, e)));
    }
    return *v;
  }
  if (i1 == "ETAB") {
    const PostState& ps = post_state(r);
    const auto col = std::find_if(ps.etable.begin(), ps.etable.end(), [&](const EtableColumn& x) {
      return x.label == g.it1num.substr(0, 8);
    });
    if (col == ps.etable.end())
      r.fail(c, fmt::format("{}: no element-table column '{}'", g.what(), g.it1num));
    const auto it = col->values.find(e);
    if (it == col->values.end()) {
      if (vector) return 0.0;
      r.fail(c, fmt::format("{}: element {} is not in column {} (not selected when it was filled)",
                            g.what(), e, g.it1num));
    }
    return it->second;
  }
  // Element results by MAPDL item: SMISC,n, NMISC,n, LS,n, LEPEL,n (numbers), S,EQV (labels),
  // or a stored name.
  const bool numbered = i1 == "SMISC" || i1 == "NMISC" || i1 == "LS" || i1 == "LEPEL";
  const std::string comp = numbered ? std::to_string(integer_field(r, c, g, g.it1num)) : g.it1num;
  const auto v = element_result(r, c, e, i1, comp);
  if (v) {
    if (std::isfinite(*v)) return *v;
    if (vector) return 0.0;
    r.fail(c, fmt::format("{}: element {} has no {} value in the current set{}", g.what(), e, i1,
                          current_set(r, c).reduced ? " (a reduced run: expand it)" : ""));
  }
  unsupported(r, c, g,
              fmt::format("NODE, ATTR, CENT, LENG, VOLU, ETAB, ESEL, NXTH, NXTL, COUNT, NUM, and "
                          "the results of a {}",
                          element_type_name(r, e)));
}

GetValue get_active(DeckReader& r, const Command& c, const GetRequest& g) {
  const std::string& i1 = g.item1;
  if (i1 == "SET") {
    const SetData& s = current_set(r, c);
    const PostState& ps = post_state(r);
    if (g.it1num == "TIME" || g.it1num == "FREQ") return {s.set.time};
    if (g.it1num == "LSTP") return {static_cast<double>(s.set.load_step)};
    if (g.it1num == "SBST") return {static_cast<double>(s.set.substep)};
    if (g.it1num == "NSET") {
      if (g.item2.empty()) return {static_cast<double>(ps.sets.size())};
      const int ls = integer_field(r, c, g, g.it2num);
      double found = 0.0;
      for (const auto& set : ps.sets)
        if (set.load_step == ls) {
          found = set.number;
          if (g.item2 == "FIRST") break;
        }
      return {found};
    }
  }
  if (i1 == "SOLU") {
    const ResultsReader& reader = results(r, c);
    const auto analyses = reader.analyses();
    if (analyses.empty()) r.fail(c, fmt::format("{}: nothing was solved", g.what()));
    const auto& a = analyses.back();
    auto attr = [&](const char* name) {
      const auto it = a.numeric_attributes.find(name);
      if (it == a.numeric_attributes.end())
        r.fail(c, fmt::format("{}: '{}' is not recorded for the last analysis", g.what(), name));
      return it->second;
    };
    if (g.it1num == "DTIME") {
      const auto t = reader.times(a.index);
      return {t.size() >= 2 ? t[t.size() - 1] - t[t.size() - 2] : 0.0};
    }
    if (g.it1num == "NCMLS") {
      const auto steps = reader.load_steps_of(a.index);
      return {steps.empty() ? 0.0 : static_cast<double>(steps.back().first)};
    }
    if (g.it1num == "NCMSS") return {attr("substeps")};
    if (g.it1num == "NCMIT") return {attr("iterations")};
    if (g.it1num == "CNVG") return {a.status == "complete" ? 1.0 : 0.0};
    // Distributed-solution statistics a Workbench input file prints after SOLVE. COMB, the time
    // spent combining per-process files: impactfe writes none (rank 0 writes the results), 0.
    // DLBR, the element load balance ratio: 1 on one process; on several MPI ranks the split is
    // in the run summary's "element assembly split" line.
    if (g.it1num == "COMB") return {0.0};
    if (g.it1num == "DLBR") {
      if (r.options.processes != 1)
        r.fail(c, fmt::format("{}: the run uses {} MPI ranks; their element split is in the run "
                              "summary (element assembly split), not a *GET item",
                              g.what(), r.options.processes));
      return {1.0};
    }
  }
  if (i1 == "ANTY") {
    switch (r.model.options.type) {
      case AnalysisType::Static:
        return {0.0};
      case AnalysisType::Modal:
        return {2.0};
      case AnalysisType::Harmonic:
        return {3.0};
      case AnalysisType::Transient:
        return {4.0};
      case AnalysisType::Substructure:
        return {7.0};
      case AnalysisType::Spectrum:
        return {8.0};
    }
  }
  // The interactive key: impactfe runs every deck as a batch job (0), which Workbench input
  // files test before their SOLVE.
  if (i1 == "INT") return {0.0};
  if (i1 == "TYPE") return {static_cast<double>(r.modeling.current_type)};
  if (i1 == "MAT") return {static_cast<double>(r.modeling.current_mat)};
  if (i1 == "REAL") return {static_cast<double>(r.modeling.current_real)};
  if (i1 == "SECT") return {static_cast<double>(r.modeling.current_secnum)};
  if (i1 == "CSYS") return {0.0};
  if (i1 == "JOBNAM") return {0.0, r.model.jobname};
  if (i1 == "TITLE") return {0.0, r.model.title};
  // Run timers, as Workbench input files read them around SOLVE: WALL is the elapsed wall-clock
  // time in hours (ds.dat multiplies differences by 3600), CPU the processor time in seconds.
  if (i1 == "TIME" && g.it1num == "WALL") {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - kRunStart;
    return {elapsed.count() / 3600.0};
  }
  if (i1 == "TIME" && g.it1num == "CPU")
    return {static_cast<double>(std::clock()) / CLOCKS_PER_SEC};
  unsupported(r, c, g,
              "SET TIME/FREQ/LSTP/SBST/NSET, SOLU DTIME/NCMLS/NCMSS/NCMIT/CNVG/COMB/DLBR, ANTY, "
              "INT, TYPE, MAT, REAL, SECT, CSYS, JOBNAM, TITLE, TIME WALL/CPU");
}

// A numeric field of *GET: parameters and get functions (NODE(x,y,z)) evaluated.
double field_number(const DeckReader& r, const std::string& text) {
  const Value v = r.evaluate_expression(text.empty() ? "0" : text);
  if (is_text(v))
    throw ExpressionError(fmt::format("'{}' is a text, not a number", std::get<std::string>(v)));
  return std::get<double>(v);
}

int integer_field(DeckReader& r, const Command& c, const GetRequest& g, const std::string& text) {
  try {
    return static_cast<int>(std::lround(field_number(r, text)));
  } catch (const ExpressionError& e) {
    r.fail(c, fmt::format("{}: bad number '{}' ({})", g.what(), text, e.what()));
  }
}

double real_field(DeckReader& r, const Command& c, const GetRequest& g, const std::string& text) {
  try {
    return field_number(r, text);
  } catch (const ExpressionError& e) {
    r.fail(c, fmt::format("{}: bad number '{}' ({})", g.what(), text, e.what()));
  }
}

// *GET,Par,ETAB,col,ELEM,e: column number col (1-based).
GetValue get_etab(DeckReader& r, const Command& c, const GetRequest& g, bool vector) {
  const int col = integer_field(r, c, g, g.entnum);
  const PostState& ps = post_state(r);
  if (col < 1 || col > static_cast<int>(ps.etable.size()))
    r.fail(c, fmt::format("{}: the element table has {} columns", g.what(), ps.etable.size()));
  if (g.item1 != "ELEM") unsupported(r, c, g, "ELEM,e");
  GetRequest e2 = g;
  e2.entity = "ELEM";
  e2.entnum = g.it1num;
  e2.item1 = "ETAB";
  e2.it1num = ps.etable[static_cast<std::size_t>(col - 1)].label;
  return GetValue{get_element(r, c, e2, integer_field(r, c, g, g.it1num), vector)};
}

// *GET,Par,MODE,m,FREQ (undamped natural frequency), after MODOPT,QRDAMP DFRQ and STAB (damped
// frequency Im λ / 2π and stability Re λ / 2π, Hz), and of the last spectrum analysis MCOEF (mode
// coefficient), PFACT (participation factor), EFFM (effective mass), DAMP (effective damping
// ratio).
double get_mode(DeckReader& r, const Command& c, const GetRequest& g) {
  const int m = integer_field(r, c, g, g.entnum);
  static const std::map<std::string, const char*> kSpectrumItems = {
      {"MCOEF", "mode_coefficient"},
      {"PFACT", "participation_factor"},
      {"EFFM", "effective_mass"},
      {"DAMP", "damping_ratio"}};
  if (const auto item = kSpectrumItems.find(g.item1); item != kSpectrumItems.end()) {
    const auto analyses = results(r, c).analyses();
    for (auto a = analyses.rbegin(); a != analyses.rend(); ++a) {
      if (a->kind != ResultsKind::Spectrum) continue;
      const auto v = a->numeric_attributes.find(fmt::format("{}_{}", item->second, m));
      if (v == a->numeric_attributes.end())
        r.fail(c, fmt::format("{}: mode {} was not used by the spectrum analysis", g.what(), m));
      return v->second;
    }
    r.fail(c, fmt::format("{}: no spectrum analysis (ANTYPE,SPECTR) was solved", g.what()));
  }
  if (g.item1 != "FREQ" && g.item1 != "DFRQ" && g.item1 != "STAB")
    unsupported(r, c, g, "FREQ, DFRQ, STAB, MCOEF, PFACT, EFFM, DAMP");
  std::vector<double> f;
  bool undamped = false;
  try {
    const ResultsReader& file = results(r, c);
    f = g.item1 == "FREQ"   ? file.frequencies()
        : g.item1 == "DFRQ" ? file.damped_frequencies()
                            : file.stabilities();
    undamped = f.empty() && g.item1 != "FREQ" && !file.frequencies().empty();
  } catch (const InputError& err) {
    r.fail(c, err.what());
  }
  if (undamped)
    r.fail(c, fmt::format("{}: the modal analysis was undamped; {} needs MODOPT,QRDAMP", g.what(),
                          g.item1));
  if (m < 1 || m > static_cast<int>(f.size()))
    r.fail(c, fmt::format("{}: mode {} was not computed (modes 1..{})", g.what(), m, f.size()));
  return f[static_cast<std::size_t>(m - 1)];
}

// The sums and sorts of POST1: FSUM (ITEM,FX..MZ), SSUM (ITEM,column), SORT (MAX ... IMIN).
double get_post1_sum(DeckReader& r, const Command& c, const GetRequest& g) {
  const PostState& ps = post_state(r);
  if (g.entity == "FSUM") {
    if (!ps.fsum) r.fail(c, fmt::format("{}: no FSUM was issued", g.what()));
    static const char* kNames[6] = {"FX", "FY", "FZ", "MX", "MY", "MZ"};
    for (std::size_t k = 0; k < 6; ++k)
      if (g.item1 == "ITEM" && g.it1num == kNames[k]) return (*ps.fsum)[k];
    unsupported(r, c, g, "ITEM,FX..MZ");
  }
  if (g.entity == "SSUM") {
    const auto it = ps.ssum.find(g.it1num);
    if (g.item1 != "ITEM") unsupported(r, c, g, "ITEM,Lab");
    if (it == ps.ssum.end())
      r.fail(c, fmt::format("{}: no SSUM of column '{}'", g.what(), g.it1num));
    return it->second;
  }
  const auto& s = ps.sort;
  if (!s) r.fail(c, fmt::format("{}: no NSORT or ESORT was issued", g.what()));
  if (g.item1 == "MAX") return s->max;
  if (g.item1 == "MIN") return s->min;
  if (g.item1 == "IMAX") return static_cast<double>(s->imax);
  if (g.item1 == "IMIN") return static_cast<double>(s->imin);
  unsupported(r, c, g, "MAX, MIN, IMAX, IMIN");
}

// *GET,Par,PLNSOL,0,MIN|MAX: the extremes of the last contour picture (PLNSOL, PLESOL,
// PLETAB) over what it drew.
double get_contour_range(DeckReader& r, const Command& c, const GetRequest& g) {
  const auto& range = post_state(r).contour_range;
  if (!range)
    r.fail(c, fmt::format("{}: no contour picture (PLNSOL, PLESOL, PLETAB) was drawn", g.what()));
  if (g.item1 == "MIN") return range->first;
  if (g.item1 == "MAX") return range->second;
  unsupported(r, c, g, "MIN, MAX");
}

// *GET,Par,VARI,n,...: a POST26 variable's extremes or its value at a time or location.
double get_variable(DeckReader& r, const Command& c, const GetRequest& g) {
  const int n = integer_field(r, c, g, g.entnum);
  if (g.item1 == "EXTREM") {
    const Extremes x = post26_extremes(r, c, n);
    if (g.it1num == "VMAX") return x.vmax;
    if (g.it1num == "VMIN") return x.vmin;
    if (g.it1num == "TMAX") return x.tmax;
    if (g.it1num == "TMIN") return x.tmin;
    if (g.it1num == "VLAST") return x.vlast;
    if (g.it1num == "TLAST") return x.tlast;
  }
  // RTIME: the real part (amplitude under PRCPLX,1) of a complex variable; ITIME: its imaginary
  // part (phase angle).
  if (g.item1 == "REAL" || g.item1 == "RTIME")
    return post26_value_at(r, c, n, real_field(r, c, g, g.it1num));
  if (g.item1 == "IMAG" || g.item1 == "ITIME")
    return post26_value_at(r, c, n, real_field(r, c, g, g.it1num), true);
  if (g.item1 == "RSET") {
    const auto v = post26_values(r, c, n);
    const int k = integer_field(r, c, g, g.it1num);
    if (k < 1 || k > static_cast<int>(v.size()))
      r.fail(c, fmt::format("{}: location {} outside 1..{}", g.what(), k, v.size()));
    return v[static_cast<std::size_t>(k - 1)];
  }
  unsupported(r, c, g,
              "EXTREM VMAX/VMIN/TMAX/TMIN/VLAST/TLAST, REAL t, RTIME t, IMAG t, ITIME t, RSET k");
}

// *GET,Par,ETYP,t,...: the element type's number (ATTR ENAM), a KEYOPT, or the highest type.
double get_element_type(DeckReader& r, const Command& c, const GetRequest& g) {
  const int t = integer_field(r, c, g, g.entnum);
  if (t == 0 && g.item1 == "NUM" && g.it1num == "MAX")
    return r.model.element_types.empty() ? 0.0 : r.model.element_types.rbegin()->first;
  const auto it = r.model.element_types.find(t);
  if (it == r.model.element_types.end())
    r.fail(c, fmt::format("{}: element type {} is not defined", g.what(), t));
  if (g.item1 == "ATTR" && g.it1num == "ENAM") {
    const ElementTypeDescriptor* d = find_element_type(it->second.ansys_name);
    return d != nullptr ? d->number : 0.0;
  }
  if (g.item1 == "KOPT") {
    const int k = integer_field(r, c, g, g.it1num);
    if (k < 1 || k > 18) r.fail(c, fmt::format("{}: KEYOPT {} outside 1..18", g.what(), k));
    return static_cast<double>(it->second.key(k));
  }
  unsupported(r, c, g, "ATTR ENAM, KOPT k, NUM MAX");
}

// *GET,Par,RCON,s,CONST,k or NUM,MAX.
double get_real_constant(DeckReader& r, const Command& c, const GetRequest& g) {
  const int s = integer_field(r, c, g, g.entnum);
  if (s == 0 && g.item1 == "NUM" && g.it1num == "MAX")
    return r.model.real_sets.empty() ? 0.0 : r.model.real_sets.rbegin()->first;
  const auto it = r.model.real_sets.find(s);
  if (it == r.model.real_sets.end())
    r.fail(c, fmt::format("{}: real constant set {} is not defined", g.what(), s));
  if (g.item1 == "CONST") return it->second.get(integer_field(r, c, g, g.it1num));
  unsupported(r, c, g, "CONST k, NUM MAX");
}

// Material properties: *GET,Par,MP,Lab,MAT (older: *GET,Par,Lab,MAT,TEMP,t); nullopt when the
// entity names no property of any material.
std::optional<double> get_material_property(DeckReader& r, const Command& c, const GetRequest& g) {
  const bool mp = g.entity == "MP";
  const std::string lab = mp ? g.item1 : g.entity;
  if (!mp && (lab.empty() || std::none_of(r.model.materials.begin(), r.model.materials.end(),
                                          [&](const auto& m) { return m.second.has(lab); })))
    return std::nullopt;
  const int mat = integer_field(r, c, g, g.entnum);
  const auto it = r.model.materials.find(mat);
  if (it == r.model.materials.end())
    r.fail(c, fmt::format("{}: material {} is not defined", g.what(), mat));
  std::string l = lab == "NUXY" ? "PRXY" : lab;
  if (!it->second.has(l) && lab == "PRXY") l = "NUXY";
  if (!it->second.has(l)) r.fail(c, fmt::format("{}: material {} has no {}", g.what(), mat, lab));
  return it->second.get(l, 0.0);
}

/// The item `g`; nullopt when its entity is none of these (another provider's, or unknown).
std::optional<GetValue> get_value(DeckReader& r, const Command& c, const GetRequest& g,
                                  bool vector) {
  const std::string& e = g.entity;
  if (e == "NODE") return GetValue{get_node(r, c, g, integer_field(r, c, g, g.entnum), vector)};
  if (e == "ELEM") return GetValue{get_element(r, c, g, integer_field(r, c, g, g.entnum), vector)};
  if (e == "ACTIVE" || e == "ACTI") return get_active(r, c, g);
  if (e == "ETAB") return get_etab(r, c, g, vector);
  if (e == "MODE") return GetValue{get_mode(r, c, g)};
  if (e == "FSUM" || e == "SSUM" || e == "SORT") return GetValue{get_post1_sum(r, c, g)};
  if (e == "VARI") return GetValue{get_variable(r, c, g)};
  if (e == "PATH") {
    if (g.item1 == "ITEM" && g.item2 == "PATHPT")
      return GetValue{get_path_value(r, c, g.item1, g.it1num, integer_field(r, c, g, g.it2num))};
    return GetValue{get_path_value(r, c, g.item1, g.it1num)};
  }
  if (e == "PLNSOL" || e == "PLNS") return GetValue{get_contour_range(r, c, g)};
  if (e == "ETYP") return GetValue{get_element_type(r, c, g)};
  // REAL: the name Workbench input files write for RCON (*get,,real,0,NUM,MAX).
  if (e == "RCON" || e == "REAL") return GetValue{get_real_constant(r, c, g)};
  if (const auto value = get_material_property(r, c, g)) return GetValue{*value};
  if (e == "COMM" || e == "COMMON")
    r.fail(c, fmt::format("{}: MAPDL's internal common blocks do not exist in impactfe", g.what()));
  return std::nullopt;
}

/// get_value as a GetItemProvider. Registered before the model items (tried after them), so
/// its "not supported (known for ...)" errors are the last word on the entities it knows.
std::optional<Value> results_items(DeckReader& r, const Command& c, const GetItem& q) {
  const GetRequest g{q.entity, q.entname.empty() ? format_number(q.entnum) : q.entname,
                     q.item1,  q.it1num,
                     q.item2,  q.it2num};
  const auto v = get_value(r, c, g, q.missing_is_zero);
  if (!v) return std::nullopt;
  if (v->text) return Value(*v->text);
  return Value(v->number);
}

void cmd_get(DeckReader& r, const Command& c) {
  // *GET,Par,Entity,ENTNUM,Item1,IT1NUM,Item2,IT2NUM
  if (c.blank(1)) r.fail(c, "Par missing");
  const Value v = get_item(r, c, read_get_item(r, c, 2));
  if (is_text(v))
    assign_text_parameter(r, c, c.text(1), std::get<std::string>(v));
  else
    assign_parameter(r, c, c.text(1), std::get<double>(v));
}

}  // namespace

void register_get_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*GET", cmd_get, kAnywhere});  // *VGET / *VPUT: matrix_commands.cpp
}

void register_results_get_items(std::vector<GetItemProvider>& t) {
  t.push_back(results_items);
}

}  // namespace impactfe::deck
