// POST26, the time-history postprocessor (APDL_SCRIPTING §C): variables over the stored time
// points (NSOL, ESOL, RFORCE, GAPF), their arithmetic (ADD, PROD, QUOT, ABS, SQRT, DERIV, INT1),
// FILLDATA, TIMERANGE, STORE, NUMVAR, PRTIME, NPRINT, PRVAR, EXTREM, PLVAR with /AXLAB, /XRANGE,
// /YRANGE, /GRID, XVAR, and the array moves VGET / VPUT.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>

#include "deck/post26.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

using Series = std::vector<std::pair<double, double>>;

bool is_filled(const Post26Variable& v) {
  return v.kind == "NSOL" || v.kind == "ESOL" || v.kind == "RFORCE" || v.kind == "GAPF";
}

/// The series of element item `name` at the element's node position k (1-based) when the element
/// stores element nodal values (ITEM@k: PLANE182/183, the values MAPDL's ERESX default puts at
/// the nodes); the principal and equivalent stresses are formed from the stored components.
/// nullopt when the element has none.
std::optional<Series> element_nodal_series(const ResultsReader& reader, int element, int k,
                                           const std::string& name) {
  auto stored = [&](const std::string& item) -> std::optional<Series> {
    try {
      return reader.element_series(element, fmt::format("{}@{}", item, k));
    } catch (const InputError&) {
      return std::nullopt;
    }
  };
  if (auto s = stored(name)) return s;
  const auto sx = stored("SX");
  if (!sx) return std::nullopt;
  const int derived = name == "S1"     ? 0
                      : name == "S2"   ? 1
                      : name == "S3"   ? 2
                      : name == "SINT" ? 3
                      : name == "SEQV" ? 4
                                       : -1;
  if (derived < 0) return std::nullopt;
  const Series zero(sx->size(), {0.0, 0.0});
  const Series sy = stored("SY").value_or(zero), sz = stored("SZ").value_or(zero);
  const Series sxy = stored("SXY").value_or(zero), syz = stored("SYZ").value_or(zero);
  const Series sxz = stored("SXZ").value_or(zero);
  Series out;
  for (std::size_t i = 0; i < sx->size(); ++i) {
    Eigen::Matrix3d t;
    t << (*sx)[i].second, sxy[i].second, sxz[i].second, sxy[i].second, sy[i].second, syz[i].second,
        sxz[i].second, syz[i].second, sz[i].second;
    // Principal stresses S1 >= S2 >= S3, SINT = S1 - S3, SEQV the von Mises stress.
    const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(t).eigenvalues();
    const double s1 = p(2), s2 = p(1), s3 = p(0);
    const double values[5] = {
        s1, s2, s3, s1 - s3,
        std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)))};
    out.emplace_back((*sx)[i].first, values[derived]);
  }
  return out;
}

/// The series of a results-based variable (ResultsReader merge rule across analyses).
Series series_of(DeckReader& r, const Command& c, const Post26Variable& v) {
  const ResultsReader& reader = results(r, c);
  try {
    if (v.kind == "GAPF") return reader.gap_force_series(v.id);
    if (v.kind == "ESOL") {
      const ElementTypeDescriptor* d = find_element_type(element_type_name(r, v.id));
      if (d == nullptr) r.fail(c, fmt::format("element {} is not in the model", v.id));
      const auto seq = find_result_sequence(*d, v.item, v.comp);
      if (!seq)
        r.fail(c, fmt::format("{} element {} has no item {}{}{}", d->name, v.id, v.item,
                              v.comp.empty() ? "" : ",", v.comp));
      if (v.node_position > 0)
        if (auto s = element_nodal_series(reader, v.id, v.node_position, seq->name)) {
          for (auto& p : *s) p.second += seq->offset;
          return *s;
        }
      Series s = reader.element_series(v.id, seq->name);
      for (auto& p : s) p.second += seq->offset;
      return s;
    }
    const auto lab = parse_nodal_item(v.label);
    if (lab && lab->column < 0) {
      // A vector sum: combine the three component series point by point.
      const char* names[2][3] = {{"UX", "UY", "UZ"}, {"ROTX", "ROTY", "ROTZ"}};
      const std::string base = lab->dataset == 'U' ? "" : std::string(1, lab->dataset);
      Series sum;
      for (int k = 0; k < 3; ++k) {
        const std::string comp = lab->dataset == 'U' ? names[lab->rotation_sum ? 1 : 0][k]
                                 : lab->dataset == 'R'
                                     ? std::string(lab->rotation_sum ? "M" : "F") + char('X' + k)
                                     : base + char('X' + k);
        Series s;
        try {
          s = reader.nodal_series(v.id, comp);
        } catch (const InputError&) {
          continue;
        }
        for (const auto& [time, x] : s) {
          const double t = time;  // clang 14 cannot capture a structured binding
          auto it = std::find_if(sum.begin(), sum.end(),
                                 [&](const auto& p) { return same_time(p.first, t); });
          if (it == sum.end())
            sum.emplace_back(t, x * x);
          else
            it->second += x * x;
        }
      }
      for (auto& p : sum) p.second = std::sqrt(p.second);
      std::sort(sum.begin(), sum.end());
      return sum;
    }
    return reader.nodal_series(v.id, v.label);
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
}

/// Values of a series at the axis times; 0 where it has none (APDL_SCRIPTING §C.0), noted.
std::vector<double> on_axis(DeckReader& r, const Command& c, const Series& s,
                            const std::vector<double>& times, const std::string& what) {
  std::vector<double> out(times.size(), 0.0);
  std::size_t j = 0, missing = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    while (j < s.size() && s[j].first < times[k] && !same_time(s[j].first, times[k])) ++j;
    if (j < s.size() && same_time(s[j].first, times[k]))
      out[k] = s[j].second;
    else
      ++missing;
  }
  if (missing == times.size() && !times.empty())
    r.fail(c, fmt::format("{} has no value at any stored time point", what));
  if (missing > 0)
    r.warn(c, fmt::format("{} has no value at {} of {} stored time points (0 there)", what, missing,
                          times.size()));
  return out;
}

/// Whether the results file has a harmonic analysis (complex displacements).
bool has_harmonic(const ResultsReader& reader) {
  const auto all = reader.analyses();
  return std::any_of(all.begin(), all.end(),
                     [](const auto& a) { return a.kind == ResultsKind::Harmonic; });
}

void fill(DeckReader& r, const Command& c, Post26Variable& v) {
  v.values = on_axis(r, c, series_of(r, c, v), post_state(r).times, v.name);
  v.imag.clear();
  const ResultsReader& reader = results(r, c);
  const auto lab = parse_nodal_item(v.label);
  if (v.kind != "NSOL" || !lab || lab->dataset != 'U' || lab->column < 0 || !has_harmonic(reader))
    return;
  // The imaginary part at the harmonic frequencies, 0 at the points of other analyses.
  const Series s = reader.nodal_series_imaginary(v.id, v.label);
  const auto& times = post_state(r).times;
  v.imag.assign(times.size(), 0.0);
  std::size_t j = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    while (j < s.size() && s[j].first < times[k] && !same_time(s[j].first, times[k])) ++j;
    if (j < s.size() && same_time(s[j].first, times[k])) v.imag[k] = s[j].second;
  }
}

/// Builds the time axis (the stored time points of the file within TIMERANGE) when the results
/// changed or TIMERANGE / STORE asked for it, and refills the results-based variables.
void refresh(DeckReader& r, const Command& c, bool force = false) {
  const ResultsReader& reader = results(r, c);
  PostState& ps = post_state(r);
  if (!force && ps.times_generation == r.solutions) return;
  std::vector<double> times;
  for (const auto& a : reader.analyses()) {
    if (a.kind == ResultsKind::Modal || a.kind == ResultsKind::Substructure ||
        a.kind == ResultsKind::Spectrum)
      continue;
    for (double t : reader.times(a.index)) {
      if (ps.timerange && (t < ps.timerange->first - 1e-12 * std::max(1.0, std::fabs(t)) ||
                           t > ps.timerange->second + 1e-12 * std::max(1.0, std::fabs(t))))
        continue;
      times.push_back(t);
    }
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), same_time), times.end());
  if (times.empty()) r.fail(c, fmt::format("no stored time points in {}", reader.path()));
  const bool changed = times != ps.times;
  ps.times = std::move(times);
  ps.times_generation = r.solutions;
  for (auto it = ps.variables.begin(); it != ps.variables.end();) {
    if (is_filled(it->second)) {
      fill(r, c, it->second);
    } else if (changed && it->second.values.size() != ps.times.size()) {
      r.warn(c, fmt::format("variable {} ({}) deleted: the time points changed", it->first,
                            it->second.name));
      it = ps.variables.erase(it);
      continue;
    }
    ++it;
  }
}

int variable_number(DeckReader& r, const Command& c, int field, bool result) {
  const PostState& ps = post_state(r);
  const std::string l = r.label(c, field);
  // PRVAR / PLVAR also accept a variable's name (lowest-numbered match).
  if (!l.empty() && !parse_fortran_number(l) && !r.params.get(l)) {
    if (l == "TIME") return 1;
    for (const auto& [n, v] : ps.variables)
      if (to_upper(v.name) == l) return n;
  }
  const int n = r.integer(c, field, 0);
  if (n < (result ? 2 : 1) || n > ps.numvar)
    r.fail(c, fmt::format("variable {} outside {}..{} (NUMVAR)", c.text(field), result ? 2 : 1,
                          ps.numvar));
  if (!result && n > 1 && ps.variables.count(n) == 0)
    r.fail(c, fmt::format("variable {} is not defined", n));
  return n;
}

void define(DeckReader& r, const Command& c, int n, Post26Variable v) {
  PostState& ps = post_state(r);
  refresh(r, c);
  if (is_filled(v)) fill(r, c, v);
  Log::info("{}:{}: {}: variable {} = {}", c.where.file, c.where.line, c.name, n, v.name);
  ps.variables[n] = std::move(v);
}

std::string default_name(const std::string& item, const std::string& comp) {
  return to_upper(item).substr(0, 4) + to_upper(comp).substr(0, 4);
}

void cmd_numvar(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const int nv = r.integer(c, 1, 10);
  if (nv < 1 || nv > 200) r.fail(c, fmt::format("NV {} outside 1..200", nv));
  if (!ps.variables.empty() && ps.variables.rbegin()->first > nv)
    r.fail(c, fmt::format("variable {} is defined: NV must be at least that",
                          ps.variables.rbegin()->first));
  ps.numvar = nv;
}

void cmd_nsol(DeckReader& r, const Command& c) {
  // NSOL,NVAR,NODE,Item,Comp,Name
  const int n = variable_number(r, c, 1, true);
  Post26Variable v;
  v.kind = "NSOL";
  results(r, c);
  v.id = nodes_of_field(r, c, 2).front();
  v.label = nodal_label_of(r.label(c, 3), r.label(c, 4));
  if (v.label.empty() || parse_nodal_item(v.label)->dataset == 'R')
    r.fail(c, fmt::format("item {},{} not supported (U, ROT, V, A with X, Y, Z or SUM)", c.text(3),
                          c.text(4)));
  v.name = c.blank(5) ? default_name(r.label(c, 3), r.label(c, 4)) : c.text(5);
  define(r, c, n, std::move(v));
}

void cmd_esol(DeckReader& r, const Command& c) {
  // ESOL,NVAR,ELEM,NODE,Item,Comp,Name. NODE blank or 0: the element value. With a NODE, the
  // element nodal value where the element stores them (PLANE182/183: extrapolated from the
  // integration points while elastic, copied from the nearest one once plastic, MAPDL's ERESX
  // default); other elements have element values only, used for the node with a warning.
  const int n = variable_number(r, c, 1, true);
  results(r, c);
  Post26Variable v;
  v.kind = "ESOL";
  v.id = r.integer(c, 2, 0);
  if (r.model.elements.count(v.id) == 0) r.fail(c, fmt::format("element {} is not defined", v.id));
  v.item = r.label(c, 4);
  v.comp = r.label(c, 5);
  if (v.item.empty()) r.fail(c, "Item missing");
  if (const int node = r.integer(c, 3, 0); node != 0) {
    const std::vector<int>& nodes = r.model.elements.at(v.id).nodes;
    const auto at = std::find(nodes.begin(), nodes.end(), node);
    if (at == nodes.end())
      r.fail(c, fmt::format("node {} is not a node of element {}", node, v.id));
    v.node_position = static_cast<int>(at - nodes.begin()) + 1;
    const ElementTypeDescriptor* d = find_element_type(element_type_name(r, v.id));
    const std::string nodal = fmt::format("SX@{}", v.node_position);
    if (d != nullptr &&
        std::find(d->result_names.begin(), d->result_names.end(), nodal) == d->result_names.end())
      r.warn(c, fmt::format("{} stores element values only: the value of element {} stands for "
                            "its node {}",
                            d->name, v.id, node));
  }
  v.name = c.blank(6) ? default_name(v.item, v.comp) : c.text(6);
  define(r, c, n, std::move(v));
}

void cmd_rforce(DeckReader& r, const Command& c) {
  // RFORCE,NVAR,NODE,Item,Comp,Name
  const int n = variable_number(r, c, 1, true);
  results(r, c);
  Post26Variable v;
  v.kind = "RFORCE";
  v.id = nodes_of_field(r, c, 2).front();
  v.label = nodal_label_of(r.label(c, 3), r.label(c, 4));
  if (v.label.empty() || parse_nodal_item(v.label)->dataset != 'R' ||
      parse_nodal_item(v.label)->column < 0)
    r.fail(c, fmt::format("item {},{}: F or M with X, Y or Z", c.text(3), c.text(4)));
  v.name = c.blank(5) ? v.label : c.text(5);
  define(r, c, n, std::move(v));
}

void cmd_gapf(DeckReader& r, const Command& c) {
  // GAPF,NVAR,NUM,Name: force of GP gap NUM (reduced and mode-superposition runs).
  const int n = variable_number(r, c, 1, true);
  Post26Variable v;
  v.kind = "GAPF";
  v.id = r.integer(c, 2, 0);
  v.name = c.blank(3) ? fmt::format("GAPF{}", v.id) : c.text(3);
  define(r, c, n, std::move(v));
}

double factor(DeckReader& r, const Command& c, int field) {
  const double f = r.real(c, field, 1.0);
  return f == 0.0 ? 1.0 : f;  // 0 or blank → 1 (§C.5)
}

void cmd_operation(DeckReader& r, const Command& c) {
  // ADD / PROD: IR,IA,IB,IC,Name,--,--,FACTA,FACTB,FACTC; QUOT: IR,IA,IB; ABS / SQRT: IR,IA;
  // DERIV: IR,IY,IX; INT1: IR,IY,IX,--,Name,--,--,FACTA,FACTB,CONST.
  refresh(r, c);
  const int ir = variable_number(r, c, 1, true);
  const std::string op = c.name;
  auto input = [&](int field) {
    const int n = variable_number(r, c, field, false);
    const auto it = post_state(r).variables.find(n);
    if (it != post_state(r).variables.end() && !it->second.imag.empty())
      r.fail(c, fmt::format("variable {} is complex (a harmonic analysis): {} of complex "
                            "variables is not supported",
                            n, op));
    return post26_values(r, c, n);
  };
  const auto a = input(2);
  const std::size_t n = a.size();
  std::vector<double> out(n, 0.0);
  const double fa = factor(r, c, 8), fb = factor(r, c, 9), fc = factor(r, c, 10);
  if (op == "ADD" || op == "PROD") {
    const auto b = c.blank(3) ? std::vector<double>() : input(3);
    const auto cc = c.blank(4) ? std::vector<double>() : input(4);
    for (std::size_t k = 0; k < n; ++k) {
      if (op == "ADD")
        out[k] = fa * a[k] + (b.empty() ? 0.0 : fb * b[k]) + (cc.empty() ? 0.0 : fc * cc[k]);
      else
        out[k] = fa * a[k] * (b.empty() ? 1.0 : fb * b[k]) * (cc.empty() ? 1.0 : fc * cc[k]);
    }
  } else if (op == "QUOT") {
    const auto b = input(3);
    bool zero = false;
    for (std::size_t k = 0; k < n; ++k) {
      zero = zero || b[k] == 0.0;
      out[k] = b[k] != 0.0 ? fa * a[k] / (fb * b[k]) : 0.0;
    }
    if (zero) r.warn(c, "division by zero: 0 there");
  } else if (op == "ABS") {
    for (std::size_t k = 0; k < n; ++k) out[k] = std::fabs(fa * a[k]);
  } else if (op == "SQRT") {
    bool negative = false;
    for (std::size_t k = 0; k < n; ++k) {
      negative = negative || fa * a[k] < 0.0;
      out[k] = fa * a[k] > 0.0 ? std::sqrt(fa * a[k]) : 0.0;
    }
    if (negative) r.warn(c, "square root of a negative value: 0 there");
  } else if (op == "DERIV") {
    // A blank IX is variable 1, the time (DERIV,5,2,,,VX is the velocity of variable 2).
    const auto x = c.blank(3) ? post26_values(r, c, 1) : input(3);
    for (std::size_t k = 1; k < n; ++k)
      if (!(x[k] > x[k - 1])) r.fail(c, "IX must increase strictly");
    // Interior: mean of the two adjacent slopes; ends extrapolated linearly (§C.5).
    std::vector<double> slope(n > 0 ? n - 1 : 0);
    for (std::size_t k = 0; k + 1 < n; ++k) slope[k] = (a[k + 1] - a[k]) / (x[k + 1] - x[k]);
    if (n == 2) out = {slope[0], slope[0]};
    for (std::size_t k = 1; k + 1 < n; ++k) out[k] = 0.5 * (slope[k - 1] + slope[k]);
    if (n >= 3) {
      out[0] = out[1] + (x[0] - x[1]) * (out[2] - out[1]) / (x[2] - x[1]);
      out[n - 1] =
          out[n - 2] + (x[n - 1] - x[n - 2]) * (out[n - 2] - out[n - 3]) / (x[n - 2] - x[n - 3]);
    }
    for (double& v : out) v *= fa;
  } else if (op == "INT1") {
    const auto x = c.blank(3) ? post26_values(r, c, 1) : input(3);  // blank IX: the time
    const double constant = r.real(c, 10, 0.0);  // CONST (not a factor: blank = 0)
    if (n > 0) out[0] = constant;
    for (std::size_t k = 1; k < n; ++k)
      out[k] = out[k - 1] + 0.5 * fa * (a[k] + a[k - 1]) * fb * (x[k] - x[k - 1]);
  }
  Post26Variable v;
  v.kind = op;
  v.name = c.blank(5) ? op : c.text(5);
  v.values = std::move(out);
  define(r, c, ir, std::move(v));
}

void cmd_filldata(DeckReader& r, const Command& c) {
  // FILLDATA,IR,LSTRT,LSTOP,LINC,VALUE,DVAL
  refresh(r, c);
  PostState& ps = post_state(r);
  const int ir = variable_number(r, c, 1, true);
  const int n = static_cast<int>(ps.times.size());
  const int start = r.integer(c, 2, 1), stop = r.integer(c, 3, n);
  const int inc = std::max(1, r.integer(c, 4, 1));
  if (start < 1 || stop > n || start > stop)
    r.fail(c, fmt::format("locations {}..{} outside 1..{}", start, stop, n));
  Post26Variable v = ps.variables.count(ir) ? ps.variables[ir] : Post26Variable{};
  if (v.values.size() != ps.times.size()) v.values.assign(ps.times.size(), 0.0);
  v.kind = "FILL";
  if (v.name.empty()) v.name = "FILL";
  double value = r.real(c, 5, 0.0);
  const double dval = r.real(c, 6, 0.0);
  for (int k = start; k <= stop; k += inc, value += dval)
    v.values[static_cast<std::size_t>(k - 1)] = value;
  ps.variables[ir] = std::move(v);
}

void cmd_timerange(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (c.last_given() == 0) {
    ps.timerange.reset();
  } else {
    ps.timerange = {r.real(c, 1, -1e300), r.real(c, 2, 1e300)};
    if (ps.timerange->first > ps.timerange->second) r.fail(c, "TMIN is larger than TMAX");
  }
  refresh(r, c, true);
}

void cmd_store(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1).empty() ? "MERGE" : r.label(c, 1);
  PostState& ps = post_state(r);
  if (l == "MERGE" || l == "APPEN" || l == "APPEND") {
    refresh(r, c, true);
  } else if (l == "NEW") {
    for (auto it = ps.variables.begin(); it != ps.variables.end();)
      it = is_filled(it->second) ? std::next(it) : ps.variables.erase(it);
    refresh(r, c, true);
  } else if (l == "ALLOC") {
    const int npts = r.integer(c, 2, 0);
    if (npts < 1) r.fail(c, "ALLOC needs NPTS ≥ 1");
    ps.variables.clear();
    ps.times.clear();
    for (int k = 1; k <= npts; ++k) ps.times.push_back(k);  // TIME = 1..NPTS
    ps.times_generation = r.solutions;
  } else {
    r.fail(c, fmt::format("Lab '{}' not supported (MERGE, NEW, APPEN, ALLOC)", c.text(1)));
  }
}

void cmd_prtime(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (c.last_given() == 0)
    ps.prtime.reset();
  else
    ps.prtime = {r.real(c, 1, -1e300), r.real(c, 2, 1e300)};
}

void cmd_nprint(DeckReader& r, const Command& c) {
  // NPRINT,N: the listing stride of PRVAR, every Nth stored point from the first. A value below
  // 1 (VM decks write NPRINT,.25) lists every point, as the default N = 1 does.
  const double n = r.real(c, 1, 1.0);
  if (!std::isfinite(n) || n > 1e9) r.fail(c, fmt::format("N {} is not a point count", n));
  post_state(r).nprint = std::max(1, static_cast<int>(n));
}

bool in_prtime(const PostState& ps, double t) {
  return !ps.prtime || (t >= ps.prtime->first - 1e-12 * std::max(1.0, std::fabs(t)) &&
                        t <= ps.prtime->second + 1e-12 * std::max(1.0, std::fabs(t)));
}

std::vector<int> listed_variables(DeckReader& r, const Command& c, int max_fields) {
  std::vector<int> out;
  for (int f = 1; f <= std::min(c.last_given(), max_fields); ++f)
    if (!c.blank(f)) out.push_back(variable_number(r, c, f, false));
  if (out.empty()) r.fail(c, "no variable given");
  return out;
}

std::string identifiers(const Post26Variable& v) {
  if (v.kind == "NSOL" || v.kind == "RFORCE") return fmt::format("{} {}", v.id, v.label);
  if (v.kind == "ESOL") return fmt::format("{} {}{}", v.id, v.item, v.comp);
  if (v.kind == "GAPF") return fmt::format("{}", v.id);
  return "";
}

void cmd_prvar(DeckReader& r, const Command& c) {
  refresh(r, c);
  const auto vars = listed_variables(r, c, 6);
  PostState& ps = post_state(r);
  // A complex variable (harmonic) lists two columns: real and imaginary parts, or amplitude and
  // phase (PRCPLX,1).
  std::string out = "\n ***** POST26 VARIABLE LISTING *****\n\n     TIME     ";
  std::vector<std::vector<double>> cols;
  std::string names;
  for (int n : vars) {
    const bool complex = n != 1 && !ps.variables.at(n).imag.empty();
    out += fmt::format("  {:>3} {:<9}", n, n == 1 ? "TIME" : ps.variables.at(n).kind);
    names += fmt::format("  {:>13}", n == 1 ? "TIME" : ps.variables.at(n).name);
    cols.push_back(post26_values(r, c, n));
    if (complex) {
      out += fmt::format("  {:>13}", "");
      names += fmt::format("  {:>13}", ps.amplitude_phase ? "PHASE" : "IMAG");
      cols.push_back(post26_second_part(r, c, n));
    }
  }
  out += "\n              " + names + "\n";
  for (std::size_t k = 0; k < ps.times.size(); k += static_cast<std::size_t>(ps.nprint)) {
    if (!in_prtime(ps, ps.times[k])) continue;
    out += " " + listing_number(ps.times[k], 12) + " ";
    for (const auto& col : cols) out += "  " + listing_number(col[k], 13);
    out += "\n";
  }
  print(r, out);
}

void cmd_extrem(DeckReader& r, const Command& c) {
  refresh(r, c);
  PostState& ps = post_state(r);
  std::vector<int> vars;
  if (c.last_given() == 0) {
    for (const auto& [n, v] : ps.variables) vars.push_back(n);
  } else {
    const int n1 = variable_number(r, c, 1, false);
    const int n2 = c.blank(2) ? n1 : variable_number(r, c, 2, false);
    for (int n = n1; n <= n2; n += std::max(1, r.integer(c, 3, 1)))
      if (n == 1 || ps.variables.count(n)) vars.push_back(n);
  }
  if (vars.empty()) r.fail(c, "no variable defined");
  std::string out =
      "\n ***** POST26 VARIABLE EXTREME VALUES *****\n\n  VARI  TYPE    IDENTIFIERS"
      "     NAME          MINIMUM      AT TIME        MAXIMUM      AT TIME"
      "           LAST      AT TIME\n";
  for (int n : vars) {
    const Extremes e = post26_extremes(r, c, n);
    const Post26Variable* v = n == 1 ? nullptr : &ps.variables.at(n);
    out += fmt::format("{:6d}  {:<6}  {:<14}  {:<10}", n, v ? v->kind : "TIME",
                       v ? identifiers(*v) : "", v ? v->name : "TIME");
    for (double x : {e.vmin, e.tmin, e.vmax, e.tmax, e.vlast, e.tlast})
      out += " " + listing_number(x, 13);
    out += "\n";
  }
  print(r, out);
}

void cmd_plvar(DeckReader& r, const Command& c) {
  refresh(r, c);
  PostState& ps = post_state(r);
  const auto vars = listed_variables(r, c, 10);
  const auto x = post26_values(r, c, ps.xvar);
  std::vector<GraphCurve> curves;
  for (int n : vars) {
    GraphCurve g;
    g.name = fmt::format("{} {}", n, n == 1 ? "TIME" : ps.variables.at(n).name);
    // All stored points (TIMERANGE limits those); PRTIME limits listings only, /XRANGE the axis.
    g.x = x;
    g.y = post26_values(r, c, n);
    curves.push_back(std::move(g));
  }
  GraphOptions o;
  o.header = {"impactfe", "POST26"};
  if (!r.model.title.empty()) o.header.insert(o.header.begin() + 1, r.model.title);
  o.x_label = !ps.x_label.empty() ? ps.x_label
              : ps.xvar == 1      ? "TIME"
                                  : ps.variables.at(ps.xvar).name;
  o.y_label = !ps.y_label.empty() ? ps.y_label : "VALUE";
  o.x_range = ps.x_range;
  o.y_range = ps.y_range;
  o.grid = ps.grid;
  write_graph(r, c, curves, o);
}

void cmd_axlab(DeckReader& r, const Command& c) {
  const std::string axis = r.label(c, 1);
  std::string text = c.text(2);
  for (int f = 3; f <= c.n_fields(); ++f) text += "," + c.text(f);  // commas in the label
  if (text.size() > 30) text.resize(30);
  PostState& ps = post_state(r);
  if (axis == "X")
    ps.x_label = text;
  else if (axis == "Y")
    ps.y_label = text;
  else
    r.fail(c, fmt::format("Axis '{}': X or Y", c.text(1)));
}

void cmd_range(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  auto& range = c.name == "/XRANGE" ? ps.x_range : ps.y_range;
  if (c.last_given() == 0 || r.label(c, 1) == "DEFAULT") {
    range.reset();
    return;
  }
  const double lo = r.real(c, 1, 0.0), hi = r.real(c, 2, 0.0);
  if (!(hi > lo)) r.fail(c, fmt::format("{}: MAX must exceed MIN", c.name));
  range = std::make_pair(lo, hi);
}

void cmd_grid(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  post_state(r).grid = !(l.empty() || l == "0" || l == "OFF");
}

void cmd_xvar(DeckReader& r, const Command& c) {
  const int n = r.integer(c, 1, 1);
  post_state(r).xvar = n <= 1 ? 1 : variable_number(r, c, 1, false);
}

void cmd_varnam(DeckReader& r, const Command& c) {
  const int n = variable_number(r, c, 1, false);
  if (n == 1) r.fail(c, "variable 1 is TIME");
  post_state(r).variables.at(n).name = c.text(2);
}

void cmd_vget(DeckReader& r, const Command& c) {
  // VGET,Par,IR,TSTRT,KCPLX: variable IR from time TSTRT into the array Par.
  refresh(r, c);
  const PostState& ps = post_state(r);
  const int n = variable_number(r, c, 2, false);
  const auto values = post26_values(r, c, n);
  std::size_t first = 0;
  if (const auto t = r.opt_real(c, 3))
    while (first < ps.times.size() && ps.times[first] < *t && !same_time(ps.times[first], *t))
      ++first;
  if (c.blank(1)) r.fail(c, "Par missing");
  assign_vector(r, c, c.text(1),
                std::vector<double>(values.begin() + static_cast<long>(first), values.end()));
}

void cmd_vput(DeckReader& r, const Command& c) {
  // VPUT,Par,IR,TSTRT,KCPLX,Name: the array Par into variable IR from time TSTRT.
  refresh(r, c);
  PostState& ps = post_state(r);
  const int ir = variable_number(r, c, 2, true);
  std::size_t first = 0;
  if (const auto t = r.opt_real(c, 3))
    while (first < ps.times.size() && ps.times[first] < *t && !same_time(ps.times[first], *t))
      ++first;
  if (c.blank(1)) r.fail(c, "Par missing");
  const auto in = read_vector(r, c, c.text(1), static_cast<int>(ps.times.size() - first));
  Post26Variable v;
  v.kind = "VPUT";
  v.name = c.blank(5) ? "VPUT" : c.text(5);
  v.values.assign(ps.times.size(), 0.0);
  std::copy(in.begin(), in.end(), v.values.begin() + static_cast<long>(first));
  ps.variables[ir] = std::move(v);
}

}  // namespace

std::vector<double> post26_values(DeckReader& r, const Command& c, int n) {
  refresh(r, c);
  PostState& ps = post_state(r);
  if (n == 1) return ps.times;
  const auto it = ps.variables.find(n);
  if (it == ps.variables.end()) r.fail(c, fmt::format("POST26 variable {} is not defined", n));
  const Post26Variable& v = it->second;
  if (v.imag.empty() || !ps.amplitude_phase) return v.values;
  std::vector<double> amplitude(v.values.size());
  for (std::size_t k = 0; k < amplitude.size(); ++k)
    amplitude[k] = std::hypot(v.values[k], v.imag[k]);
  return amplitude;
}

std::vector<double> post26_second_part(DeckReader& r, const Command& c, int n) {
  refresh(r, c);
  PostState& ps = post_state(r);
  const auto it = ps.variables.find(n);
  if (n == 1 || it == ps.variables.end())
    return std::vector<double>(ps.times.size(), 0.0);  // TIME and real variables: 0
  const Post26Variable& v = it->second;
  if (v.imag.empty()) return std::vector<double>(v.values.size(), 0.0);
  if (!ps.amplitude_phase) return v.imag;
  std::vector<double> phase(v.values.size());
  for (std::size_t k = 0; k < phase.size(); ++k)
    phase[k] = std::atan2(v.imag[k], v.values[k]) * 180.0 / M_PI;
  return phase;
}

Extremes post26_extremes(DeckReader& r, const Command& c, int n) {
  const auto values = post26_values(r, c, n);
  const PostState& ps = post_state(r);
  Extremes e;
  bool any = false;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!in_prtime(ps, ps.times[k])) continue;
    const double v = values[k], t = ps.times[k];
    if (!any || v < e.vmin) e.vmin = v, e.tmin = t;
    if (!any || v > e.vmax) e.vmax = v, e.tmax = t;
    e.vlast = v;
    e.tlast = t;
    any = true;
  }
  if (!any) r.fail(c, "no stored time point inside PRTIME");
  return e;
}

double post26_value_at(DeckReader& r, const Command& c, int n, double t, bool second_part) {
  const auto values = second_part ? post26_second_part(r, c, n) : post26_values(r, c, n);
  const auto& times = post_state(r).times;
  if (t <= times.front()) return values.front();
  for (std::size_t k = 1; k < times.size(); ++k)
    if (t <= times[k])
      return values[k - 1] +
             (values[k] - values[k - 1]) * (t - times[k - 1]) / (times[k] - times[k - 1]);
  return values.back();
}

namespace {

void cmd_prcplx(DeckReader& r, const Command& c) {
  // PRCPLX,KEY: 0 real and imaginary parts, 1 amplitude and phase angle (degrees).
  const int key = r.integer(c, 1, 0);
  if (key != 0 && key != 1) r.fail(c, fmt::format("KEY {} must be 0 or 1", key));
  post_state(r).amplitude_phase = key == 1;
}

}  // namespace

void register_post26_commands(std::vector<CommandSpec>& t) {
  t.push_back({"PRCPLX", cmd_prcplx, kPost26});
  t.push_back({"NUMVAR", cmd_numvar, kPost26});
  t.push_back({"NSOL", cmd_nsol, kPost26});
  t.push_back({"ESOL", cmd_esol, kPost26});
  t.push_back({"RFORCE", cmd_rforce, kPost26});
  t.push_back({"GAPF", cmd_gapf, kPost26});
  for (const char* op : {"ADD", "PROD", "QUOT", "ABS", "SQRT", "DERIV", "INT1"})
    t.push_back({op, cmd_operation, kPost26});
  t.push_back({"FILLDATA", cmd_filldata, kPost26});
  t.push_back({"TIMERANGE", cmd_timerange, kPost26});
  t.push_back({"STORE", cmd_store, kPost26});
  t.push_back({"PRTIME", cmd_prtime, kPost26});
  t.push_back({"NPRINT", cmd_nprint, kPost26});
  t.push_back({"PRVAR", cmd_prvar, kPost26});
  t.push_back({"EXTREM", cmd_extrem, kPost26});
  t.push_back({"PLVAR", cmd_plvar, kPost26});
  t.push_back({"XVAR", cmd_xvar, kPost26});
  t.push_back({"VARNAM", cmd_varnam, kPost26});
  t.push_back({"VGET", cmd_vget, kPost26});
  t.push_back({"VPUT", cmd_vput, kPost26});
  t.push_back({"/AXLAB", cmd_axlab, kAnywhere});
  t.push_back({"/XRANGE", cmd_range, kAnywhere});
  t.push_back({"/YRANGE", cmd_range, kAnywhere});
  t.push_back({"/GRID", cmd_grid, kAnywhere});
}

}  // namespace impactfe::deck
