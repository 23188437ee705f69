// POST1 path operations (docs/post_processing.md, "Paths"): PATH, PPATH, PDEF, PCALC, PVECT,
// PDOT, PCROSS, PRPATH, PLPATH, PADELE and *GET,Par,PATH. A path is a polyline through points
// (nodes or locations); each segment is divided into nDiv parts in the coordinate system of its
// end point, and results are interpolated at the division points with the shape functions of
// the element each point lies in (geometry/point_location.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/text.h"
#include "deck/post1_path.h"
#include "deck/post1_print.h"
#include "geometry/point_location.h"
#include "results/svg_plot.h"

namespace impactfe::deck {

// Helpers in a named namespace: the unity build compiles this file with others.
namespace path_ops {

constexpr const char* kGeometryItems[] = {"XG", "YG", "ZG", "S"};

bool geometry_item(const std::string& label) {
  return std::find(std::begin(kGeometryItems), std::end(kGeometryItems), label) !=
         std::end(kGeometryItems);
}

PathDefinition& current_path(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const auto it = ps.paths.find(ps.current_path);
  if (it == ps.paths.end()) r.fail(c, "no path is defined (PATH, then PPATH)");
  return it->second;
}

/// The most interpolation points a path may have ((nPts − 1) nDiv + 1), a bound on its memory
/// and on the element search of each PDEF.
constexpr long long kMaxPathPoints = 100000;

/// Stores item `label` (replacing an item of that name), within the path's nSets items.
void store_item(DeckReader& r, const Command& c, PathDefinition& p, const std::string& label,
                std::vector<double> values) {
  if (label.empty()) r.fail(c, "the label of the path item is missing");
  if (!p.items.count(label)) {
    if (static_cast<int>(p.labels.size()) >= p.n_sets)
      r.fail(c, fmt::format("path {} holds {} items, its nSets (PATH field 3); PDEF,CLEAR frees "
                            "them",
                            p.name, p.n_sets));
    p.labels.push_back(label);
  }
  p.items[label] = std::move(values);
}

/// XG, YG, ZG and S of a complete path: each segment divided into n_div equal parts of the
/// coordinates of its end point's system (a straight line in a Cartesian system, an arc or helix
/// in a cylindrical one; the angle goes the short way round), S the length along the divisions.
void make_geometry(DeckReader& r, const Command& c, PathDefinition& p) {
  std::vector<double> xg, yg, zg, s;
  for (std::size_t k = 0; k + 1 < p.points.size(); ++k) {
    const PathPoint& a = p.points[k];
    const PathPoint& b = p.points[k + 1];
    const auto& systems = r.model.coordinate_systems;
    if (!systems.has(b.csys))
      r.fail(c, fmt::format("coordinate system {} of path point {} is not defined", b.csys, k + 2));
    const CoordinateSystem cs = systems.get(b.csys);
    const Vec3 ca = cs.from_global(a.x);
    Vec3 d = cs.from_global(b.x) - ca;
    if (cs.curvilinear())
      for (int i = 1; i < (cs.kind == CsysKind::Spherical ? 3 : 2); ++i)
        d[i] = std::remainder(d[i], 360.0);
    for (int j = k == 0 ? 0 : 1; j <= p.n_div; ++j) {
      const Vec3 x = cs.to_global(ca + d * (static_cast<double>(j) / p.n_div));
      const double step = xg.empty() ? 0.0 : (x - Vec3(xg.back(), yg.back(), zg.back())).norm();
      s.push_back(s.empty() ? 0.0 : s.back() + step);
      xg.push_back(x[0]);
      yg.push_back(x[1]);
      zg.push_back(x[2]);
    }
  }
  p.labels.clear();
  p.items.clear();
  store_item(r, c, p, "XG", xg);
  store_item(r, c, p, "YG", yg);
  store_item(r, c, p, "ZG", zg);
  store_item(r, c, p, "S", s);
}

// PATH,NAME,nPts,nSets,nDiv
void cmd_path(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const std::string name = to_upper(c.text(1));
  if (name.empty()) r.fail(c, "NAME missing");
  if (name == "STATUS" || name == "STAT") {
    std::string out = "\n PATH STATUS\n";
    for (const auto& [n, p] : ps.paths)
      out += fmt::format(" {:<8} points {:4}  items {:3} of {:3}  divisions {}{}\n", n,
                         p.points.size(), p.labels.size(), p.n_sets, p.n_div,
                         n == ps.current_path ? "  (current)" : "");
    print(r, out);
    return;
  }
  if (c.last_given() == 1) {
    if (!ps.paths.count(name)) r.fail(c, fmt::format("path {} is not defined", name));
    ps.current_path = name;
    return;
  }
  PathDefinition p;
  p.name = name;
  const int n_pts = r.integer(c, 2, 2);
  p.n_sets = r.integer(c, 3, 30);
  p.n_div = r.integer(c, 4, 20);
  if (n_pts < 2 || n_pts > 1000) r.fail(c, fmt::format("nPts = {}: 2 to 1000 points", n_pts));
  if (p.n_sets < 4) r.fail(c, fmt::format("nSets = {}: at least 4 (XG, YG, ZG, S)", p.n_sets));
  if (p.n_div < 1) r.fail(c, fmt::format("nDiv = {}: at least 1 division", p.n_div));
  if (static_cast<long long>(n_pts - 1) * p.n_div + 1 > kMaxPathPoints)
    r.fail(c, fmt::format("{} points x {} divisions: a path has at most {} interpolation points",
                          n_pts, p.n_div, kMaxPathPoints));
  p.points.resize(static_cast<std::size_t>(n_pts));
  ps.paths[name] = std::move(p);
  ps.current_path = name;
}

// FLST,NFIELD,NITEMS,ITYPE: the start of a picked list as the GUI logs it; FITEM,NFIELD,ITEM
// adds an item (a negative one: the range from the previous item). Nodes only (ITYPE 1), for
// PPATH,P51X.
void cmd_flst(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const int type = r.integer(c, 3, 0);
  if (type != 1)
    r.fail(c, fmt::format("ITYPE = {}: only a node list (1) is read, for PPATH,P51X", type));
  ps.picked_expected = r.integer(c, 2, 0);
  if (ps.picked_expected < 1 || ps.picked_expected > kMaxPathPoints)
    r.fail(c, fmt::format("NITEMS = {}: 1 to {} nodes", ps.picked_expected, kMaxPathPoints));
  ps.picked_nodes.clear();
}

void cmd_fitem(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (ps.picked_expected == 0) r.fail(c, "FITEM without FLST");
  const int item = r.integer(c, 2, 0);
  const auto room =
      static_cast<long long>(ps.picked_expected) - static_cast<long long>(ps.picked_nodes.size());
  if (item < 0 && !ps.picked_nodes.empty()) {
    const long long first = static_cast<long long>(ps.picked_nodes.back()) + 1;
    if (-static_cast<long long>(item) - first + 1 > room)
      r.fail(c, fmt::format("the range to {} exceeds the {} items FLST announced", -item,
                            ps.picked_expected));
    for (long long n = first; n <= -static_cast<long long>(item); ++n)
      ps.picked_nodes.push_back(static_cast<int>(n));
  } else if (item > 0) {
    if (room < 1)
      r.fail(c, fmt::format("more items than the {} FLST announced", ps.picked_expected));
    ps.picked_nodes.push_back(item);
  } else {
    r.fail(c, fmt::format("ITEM {} is not a node number", c.text(2)));
  }
}

// PPATH,POINT,NODE,X,Y,Z,CS
void cmd_ppath(DeckReader& r, const Command& c) {
  PathDefinition& p = current_path(r, c);
  if (r.label(c, 1) == "P") r.fail(c, "graphical picking (PPATH,P) is not available");
  if (r.label(c, 1) == "P51X") {
    // The GUI's log of picked path points: PPATH,P51X,1 with the nodes of FLST / FITEM as the
    // points 1, 2, ... in order.
    PostState& ps = post_state(r);
    if (ps.picked_nodes.empty()) r.fail(c, "P51X: no FLST / FITEM node list precedes it");
    if (r.integer(c, 2, 1) != 1) r.fail(c, "PPATH,P51X takes 1 in field 2 (points by node)");
    if (static_cast<int>(ps.picked_nodes.size()) != ps.picked_expected)
      r.fail(c, fmt::format("FLST announced {} items, FITEM gave {}", ps.picked_expected,
                            ps.picked_nodes.size()));
    if (ps.picked_nodes.size() > p.points.size())
      r.fail(c, fmt::format("{} picked nodes for the {} points of path {}", ps.picked_nodes.size(),
                            p.points.size(), p.name));
    for (std::size_t k = 0; k < ps.picked_nodes.size(); ++k) {
      const auto n = r.model.nodes.find(ps.picked_nodes[k]);
      if (n == r.model.nodes.end())
        r.fail(c, fmt::format("node {} is not defined", ps.picked_nodes[k]));
      p.points[k] = {true, n->first, n->second.x,
                     c.blank(6) ? r.model.coordinate_systems.active : r.integer(c, 6, 0)};
      if (!r.model.coordinate_systems.has(p.points[k].csys))
        r.fail(c, fmt::format("CS {} is not a defined coordinate system", p.points[k].csys));
    }
    ps.picked_nodes.clear();
    ps.picked_expected = 0;
    if (p.complete()) make_geometry(r, c, p);
    return;
  }
  const int k = r.integer(c, 1, 0);
  if (k < 1 || k > static_cast<int>(p.points.size()))
    r.fail(c, fmt::format("POINT {} outside 1..{} (nPts of path {})", k, p.points.size(), p.name));
  PathPoint& point = p.points[static_cast<std::size_t>(k - 1)];
  point.node = r.integer(c, 2, 0);
  if (point.node > 0) {
    const auto n = r.model.nodes.find(point.node);
    if (n == r.model.nodes.end()) r.fail(c, fmt::format("node {} is not defined", point.node));
    point.x = n->second.x;
  } else {
    point.node = 0;
    point.x = Vec3(r.real(c, 3, 0.0), r.real(c, 4, 0.0), r.real(c, 5, 0.0));
  }
  point.csys = c.blank(6) ? r.model.coordinate_systems.active : r.integer(c, 6, 0);
  if (!r.model.coordinate_systems.has(point.csys))
    r.fail(c, fmt::format("CS {} is not a defined coordinate system", point.csys));
  point.defined = true;
  if (p.complete()) make_geometry(r, c, p);
}

/// An old-style combined label ("SX", "UY", "ROTZ", "SEQV", "EPELXY") split into Item and Comp.
std::pair<std::string, std::string> split_combined(const std::string& label) {
  for (const char* item : {"ROT", "EPEL", "EPPL", "EPCR", "EPTO", "EPTH"})
    if (label.size() > std::string(item).size() && label.rfind(item, 0) == 0)
      return {item, label.substr(std::string(item).size())};
  if (label.size() > 1 &&
      (label[0] == 'U' || label[0] == 'S' || label[0] == 'V' || label[0] == 'A'))
    return {label.substr(0, 1), label.substr(1)};
  return {label, ""};
}

/// One path point's place in the mesh: an element and the shape-function values of its nodes.
struct PointInElement {
  int element = 0;
  std::vector<int> nodes;
  std::vector<double> weights;
};

/// The cell of element e as its nodes define it: a quadratic cell with a midside node missing
/// (0) is located by its corners.
VtkCell located_cell(const DeckReader& r, int e, std::vector<int>& nodes) {
  VtkCell cell = element_cell(r, e);
  const CellTopology& t = cell_topology(cell);
  const auto& all = r.model.elements.at(e).nodes;
  if (static_cast<int>(all.size()) < t.n_nodes()) return VtkCell::PolyVertex;
  nodes.assign(all.begin(), all.begin() + t.n_nodes());
  if (std::find(nodes.begin(), nodes.end(), 0) != nodes.end()) {
    cell = t.linear;
    nodes.resize(static_cast<std::size_t>(t.corner_nodes));
  }
  if (std::find(nodes.begin(), nodes.end(), 0) != nodes.end()) return VtkCell::PolyVertex;
  return cell;
}

/// The element (selected, of the highest dimension, lowest number first) each path point lies
/// in; element 0 for a point outside them. Only elements whose box meets the path's box are
/// tried.
std::vector<PointInElement> locate_points(DeckReader& r, const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& x : points) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  struct Candidate {
    int dimension;
    int element;
    VtkCell cell;
    std::vector<int> nodes;
    std::vector<Vec3> x;
  };
  std::vector<Candidate> candidates;
  for (int e : selected_elements(r)) {
    Candidate cand{0, e, VtkCell::PolyVertex, {}, {}};
    cand.cell = located_cell(r, e, cand.nodes);
    if (!geometry::locatable_cell(cand.cell)) continue;
    Vec3 elo = Vec3::Constant(1e300), ehi = Vec3::Constant(-1e300);
    for (int n : cand.nodes) {
      cand.x.push_back(r.model.nodes.at(n).x);
      elo = elo.cwiseMin(cand.x.back());
      ehi = ehi.cwiseMax(cand.x.back());
    }
    const double margin = 1e-6 * (ehi - elo).norm();
    if ((ehi.array() + margin < lo.array()).any() || (elo.array() - margin > hi.array()).any())
      continue;
    cand.dimension = cell_topology(cand.cell).dimension;
    candidates.push_back(std::move(cand));
  }
  std::stable_sort(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.dimension > b.dimension; });
  std::vector<PointInElement> out(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    for (const Candidate& cand : candidates) {
      const auto w = geometry::shape_values_at(cand.cell, cand.x, points[k], 1e-6);
      if (!w) continue;
      out[k] = {cand.element, cand.nodes, *w};
      break;
    }
  return out;
}

std::vector<Vec3> path_points(DeckReader& r, const Command& c, const PathDefinition& p) {
  const auto& x = path_item(r, c, p, "XG");
  const auto& y = path_item(r, c, p, "YG");
  const auto& z = path_item(r, c, p, "ZG");
  std::vector<Vec3> out(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) out[k] = Vec3(x[k], y[k], z[k]);
  return out;
}

void warn_outside(DeckReader& r, const Command& c, const std::vector<PointInElement>& where,
                  std::size_t unvalued) {
  const auto outside = static_cast<std::size_t>(
      std::count_if(where.begin(), where.end(), [](const auto& w) { return w.element == 0; }));
  if (outside > 0)
    r.warn(c, fmt::format("{} of the path's {} points lie outside the selected elements: the "
                          "item is 0 there",
                          outside, where.size()));
  if (unvalued > 0)
    r.warn(c, fmt::format("{} path points lie in elements without the item: 0 there", unvalued));
}

/// Element-table column `label` at the path points: each element's value (NOAV) or, at each
/// node, the mean of the values of the selected elements at the node, interpolated (AVG).
std::vector<double> etable_on_path(DeckReader& r, const Command& c, const PathDefinition& p,
                                   const std::string& label, bool average) {
  const auto& table = post_state(r).etable;
  const auto col = std::find_if(table.begin(), table.end(),
                                [&](const EtableColumn& t) { return t.label == label; });
  if (col == table.end()) r.fail(c, fmt::format("ETAB: no element table column '{}'", label));
  const auto where = locate_points(r, path_points(r, c, p));
  std::map<int, std::pair<double, int>> nodal;  // node → (sum, count), AVG
  if (average)
    for (int e : selected_elements(r)) {
      const auto v = col->values.find(e);
      if (v == col->values.end()) continue;
      for (int n : r.model.elements.at(e).nodes) {
        auto& acc = nodal[n];
        acc.first += v->second;
        ++acc.second;
      }
    }
  std::vector<double> out(where.size(), 0.0);
  std::size_t unvalued = 0;
  for (std::size_t k = 0; k < where.size(); ++k) {
    const path_ops::PointInElement& w = where[k];
    if (w.element == 0) continue;
    if (!average) {
      const auto v = col->values.find(w.element);
      if (v == col->values.end())
        ++unvalued;
      else
        out[k] = v->second;
      continue;
    }
    for (std::size_t i = 0; i < w.nodes.size(); ++i) {
      const auto acc = nodal.find(w.nodes[i]);
      if (acc != nodal.end()) out[k] += w.weights[i] * acc->second.first / acc->second.second;
    }
  }
  warn_outside(r, c, where, unvalued);
  return out;
}

// PDEF,Lab,Item,Comp,Avglab (also the older PDEF,INTR,Lab,Item with a combined label).
void cmd_pdef(DeckReader& r, const Command& c) {
  PathDefinition& p = current_path(r, c);
  std::string lab = r.label(c, 1);
  if (lab == "CLEAR") {
    std::vector<std::string> keep;
    for (const auto& l : p.labels)
      if (geometry_item(l)) keep.push_back(l);
    for (auto it = p.items.begin(); it != p.items.end();)
      it = geometry_item(it->first) ? std::next(it) : p.items.erase(it);
    p.labels = keep;
    return;
  }
  if (lab == "STAT" || lab == "STATUS") {
    std::string out = fmt::format("\n PATH {} ITEMS\n", p.name);
    for (const auto& l : p.labels) out += fmt::format(" {}\n", l);
    print(r, out);
    return;
  }
  int f = 1;
  if (lab == "INTR") {  // PDEF,INTR,Lab,Item: interpolation named as an operation
    f = 2;
    lab = r.label(c, 2);
  }
  complete_path(r, c);
  if (lab.empty()) r.fail(c, "Lab missing");
  if (geometry_item(lab)) r.fail(c, fmt::format("Lab {} is a path geometry item", lab));
  std::string item = r.label(c, f + 1), comp = r.label(c, f + 2);
  const std::string avg = r.label(c, f + 3);
  if (!avg.empty() && avg != "AVG" && avg != "NOAV")
    r.fail(c, fmt::format("Avglab '{}': AVG or NOAV", c.text(f + 3)));
  const bool average = avg != "NOAV";
  if (item.empty()) r.fail(c, "Item missing");
  if (item == "ETAB") {
    store_item(r, c, p, lab, etable_on_path(r, c, p, comp.empty() ? lab : comp, average));
    return;
  }
  if (comp.empty()) std::tie(item, comp) = split_combined(item);
  store_item(r, c, p, lab, interpolate_on_path(r, c, p, item, comp, average));
}

// PCALC,Oper,LabR,Lab1,Lab2,FACT1,FACT2,CONST
void cmd_pcalc(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  const std::string op = r.label(c, 1), res = r.label(c, 2);
  const auto factor = [&](int i) {
    const double v = r.real(c, i, 0.0);
    return v == 0.0 ? 1.0 : v;  // blank or 0 → 1
  };
  const double f1 = factor(5), f2 = factor(6), k = r.real(c, 7, 0.0);
  const std::vector<double> a = path_item(r, c, p, r.label(c, 3));
  const bool needs_b = op == "MULT" || op == "DIV" || op == "DERI" || op == "INTG";
  std::vector<double> b(a.size(), 0.0);
  if (!c.blank(4))
    b = path_item(r, c, p, r.label(c, 4));
  else if (needs_b)
    r.fail(c, fmt::format("PCALC,{}: Lab2 missing", op));
  std::vector<double> out(a.size(), 0.0);
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (op == "ADD")
      out[i] = f1 * a[i] + (c.blank(4) ? 0.0 : f2 * b[i]) + k;
    else if (op == "MULT")
      out[i] = f1 * a[i] * b[i];
    else if (op == "DIV")
      out[i] = b[i] == 0.0 ? 0.0 : f1 * a[i] / b[i];
    else if (op == "EXP")
      out[i] = f1 * std::exp(a[i]) + (c.blank(4) ? 0.0 : f2 * std::exp(b[i]));
    else if (op == "SIN")
      out[i] = f2 * std::sin(f1 * a[i]);
    else if (op == "COS")
      out[i] = f2 * std::cos(f1 * a[i]);
    else if (op == "ASIN" || op == "ACOS") {
      const double x = f1 * a[i];
      if (std::fabs(x) > 1.0)
        r.fail(c,
               fmt::format("PCALC,{}: argument {} at path point {} outside [-1, 1]", op, x, i + 1));
      out[i] = f2 * (op == "ASIN" ? std::asin(x) : std::acos(x));
    } else if (op == "LOG") {
      const double x = f1 * a[i];
      if (!(x > 0.0))
        r.fail(c, fmt::format("PCALC,LOG: argument {} at path point {} is not positive", x, i + 1));
      out[i] = f2 * std::log(x);
    } else if (op == "DERI") {
      // d(Lab1)/d(Lab2): central differences inside, one-sided at the ends.
      const std::size_t i0 = i == 0 ? 0 : i - 1, i1 = i + 1 == n ? i : i + 1;
      const double db = b[i1] - b[i0];
      out[i] = i1 == i0 || db == 0.0 ? 0.0 : f1 * (a[i1] - a[i0]) / db;
    } else if (op == "INTG") {
      // ∫ Lab1 d(Lab2) from the first point, by the trapezoidal rule.
      out[i] = i == 0 ? 0.0 : out[i - 1] + f1 * 0.5 * (a[i] + a[i - 1]) * (b[i] - b[i - 1]);
    } else {
      r.fail(c, fmt::format("Oper '{}': ADD, MULT, DIV, EXP, DERI, INTG, SIN, COS, ASIN, ACOS, LOG",
                            c.text(1)));
    }
  }
  store_item(r, c, p, res, std::move(out));
}

/// The unit tangent of the path at each point (the chord through its neighbours).
std::vector<Vec3> path_tangents(const std::vector<Vec3>& x) {
  std::vector<Vec3> t(x.size(), Vec3::Zero());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t i0 = i == 0 ? 0 : i - 1, i1 = i + 1 == x.size() ? i : i + 1;
    const Vec3 d = x[i1] - x[i0];
    if (d.norm() > 0.0) t[i] = d.normalized();
  }
  return t;
}

// PVECT,Oper,LabXR,LabYR,LabZR: NORM, TANG, RADI in the active (Cartesian) system.
void cmd_pvect(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  const std::string op = r.label(c, 1);
  const CoordinateSystem cs = r.model.coordinate_systems.active_system();
  if (cs.curvilinear())
    r.fail(c, fmt::format("the active coordinate system {} is not Cartesian",
                          r.model.coordinate_systems.active));
  const std::vector<Vec3> x = path_points(r, c, p);
  const std::vector<Vec3> t = path_tangents(x);
  std::array<std::vector<double>, 3> v;
  for (auto& comp : v) comp.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    Vec3 g;
    if (op == "NORM") {
      g = t[i].cross(cs.axes.col(2));
      if (g.norm() > 0.0) g.normalize();
    } else if (op == "TANG") {
      g = t[i];
    } else if (op == "RADI") {
      g = x[i] - cs.origin;
    } else {
      r.fail(c, fmt::format("Oper '{}': NORM, TANG or RADI", c.text(1)));
    }
    const Vec3 local = cs.axes.transpose() * g;
    for (int j = 0; j < 3; ++j) v[j][i] = local[j];
  }
  for (int j = 0; j < 3; ++j)
    if (!c.blank(2 + j)) store_item(r, c, p, r.label(c, 2 + j), v[j]);
}

// PDOT,LabR,Lab1X,Lab1Y,Lab1Z,Lab2X,Lab2Y,Lab2Z and PCROSS,LabXR,LabYR,LabZR,Lab1X..Lab2Z.
void cmd_vector_product(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  const bool cross = c.name == "PCROSS";
  const int first = cross ? 4 : 2;
  std::array<std::vector<double>, 6> in;
  for (int j = 0; j < 6; ++j) in[j] = path_item(r, c, p, r.label(c, first + j));
  const std::size_t n = in[0].size();
  std::array<std::vector<double>, 3> out;
  for (auto& o : out) o.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a(in[0][i], in[1][i], in[2][i]), b(in[3][i], in[4][i], in[5][i]);
    if (cross) {
      const Vec3 v = a.cross(b);
      for (int j = 0; j < 3; ++j) out[j][i] = v[j];
    } else {
      out[0][i] = a.dot(b);
    }
  }
  for (int j = 0; j < (cross ? 3 : 1); ++j) store_item(r, c, p, r.label(c, 1 + j), out[j]);
}

/// The items PRPATH / PLPATH name (fields 1..6).
std::vector<std::string> named_items(DeckReader& r, const Command& c, const PathDefinition& p) {
  std::vector<std::string> labels;
  for (int f = 1; f <= std::min(6, c.n_fields()); ++f)
    if (!c.blank(f)) {
      path_item(r, c, p, r.label(c, f));
      labels.push_back(r.label(c, f));
    }
  if (labels.empty()) r.fail(c, "no path item named (Lab1..Lab6)");
  return labels;
}

/// The points PRANGE leaves for listing and drawing: every increment-th point with S in range.
std::vector<std::size_t> points_in_range(DeckReader& r, const Command& c, const PathDefinition& p) {
  const auto& s = path_item(r, c, p, "S");
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if ((p.s_min && s[i] < *p.s_min - 1e-12 * std::fabs(s.back())) ||
        (p.s_max && s[i] > *p.s_max + 1e-12 * std::fabs(s.back())))
      continue;
    out.push_back(i);
  }
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < out.size(); k += static_cast<std::size_t>(p.increment))
    kept.push_back(out[k]);
  return kept;
}

// PRANGE,LINC,VMIN,VMAX,XVAR
void cmd_prange(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  p.increment = r.integer(c, 1, 1);
  if (p.increment < 1) r.fail(c, fmt::format("LINC = {}: at least 1", p.increment));
  p.s_min = r.opt_real(c, 2);
  p.s_max = r.opt_real(c, 3);
  p.x_item = c.blank(4) ? "S" : r.label(c, 4);
  path_item(r, c, p, p.x_item);
}

// PRPATH,Lab1..Lab6: the items against S (the PRANGE part of the path).
void cmd_prpath(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  const std::vector<std::string> labels = named_items(r, c, p);
  std::string out = fmt::format("\n PRINT ALONG PATH {}. DSYS= 0\n\n {:>12}", p.name, "S");
  for (const auto& l : labels) out += fmt::format(" {:>12}", l);
  out += "\n";
  const auto& s = path_item(r, c, p, "S");
  for (std::size_t i : points_in_range(r, c, p)) {
    out += " " + listing_number(s[i]);
    for (const auto& l : labels) out += " " + listing_number(p.items.at(l)[i]);
    out += "\n";
  }
  print(r, out);
}

// PLPATH,Lab1..Lab6: an x-y graph of the items against S.
void cmd_plpath(DeckReader& r, const Command& c) {
  PathDefinition& p = complete_path(r, c);
  PostState& ps = post_state(r);
  std::vector<GraphCurve> curves;
  const std::vector<std::size_t> shown = points_in_range(r, c, p);
  const auto& x = path_item(r, c, p, p.x_item);
  for (const auto& l : named_items(r, c, p)) {
    GraphCurve g{l, {}, {}};
    for (std::size_t i : shown) {
      g.x.push_back(x[i]);
      g.y.push_back(p.items.at(l)[i]);
    }
    curves.push_back(std::move(g));
  }
  GraphOptions o;
  o.header = {"impactfe", fmt::format("POST1 PATH {}", p.name)};
  if (!r.model.title.empty()) o.header.insert(o.header.begin() + 1, r.model.title);
  o.x_label = p.x_item == "S" ? "DIST" : p.x_item;
  o.y_label = "VALUE";
  o.grid = ps.grid;
  write_graph(r, c, curves, o);
}

// PLPAGM: path items drawn on the model's picture; listed as ignored (graphics only).
void cmd_plpagm(DeckReader& r, const Command& c) {
  complete_path(r, c);
  r.ignore(c);
}

// PADELE,DELOPT: deletes the current path (ALL: every path).
void cmd_padele(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const std::string opt = r.label(c, 1);
  if (opt == "ALL") {
    ps.paths.clear();
  } else if (opt.empty() || opt == "PATH") {
    ps.paths.erase(ps.current_path);
  } else {
    r.fail(c, fmt::format("DELOPT '{}': ALL or PATH", c.text(1)));
  }
  ps.current_path = ps.paths.empty() ? "" : ps.paths.begin()->first;
}

}  // namespace path_ops

PathDefinition& complete_path(DeckReader& r, const Command& c) {
  PathDefinition& p = path_ops::current_path(r, c);
  for (std::size_t k = 0; k < p.points.size(); ++k)
    if (!p.points[k].defined)
      r.fail(c, fmt::format("point {} of path {} is not defined (PPATH)", k + 1, p.name));
  return p;
}

const std::vector<double>& path_item(DeckReader& r, const Command& c, const PathDefinition& path,
                                     const std::string& label) {
  const auto it = path.items.find(label);
  if (it == path.items.end()) {
    std::string items;
    for (const auto& l : path.labels) items += (items.empty() ? "" : " ") + l;
    r.fail(c, fmt::format("path {} has no item '{}' (items: {})", path.name, label, items));
  }
  return it->second;
}

std::vector<double> interpolate_on_path(DeckReader& r, const Command& c, const PathDefinition& path,
                                        const std::string& item, const std::string& comp,
                                        bool average) {
  return interpolate_at(r, c, path_ops::path_points(r, c, path), item, comp, average);
}

std::vector<double> interpolate_at(DeckReader& r, const Command& c, const std::vector<Vec3>& points,
                                   const std::string& item, const std::string& comp, bool average) {
  const NodalItem ni = nodal_item(r, c, item, comp);
  if (ni.labels.size() != 1)
    r.fail(c, fmt::format("{},{}: one component is interpolated at a time (e.g. S,X)", item, comp));
  const auto where = path_ops::locate_points(r, points);
  std::map<int, std::optional<double>> nodal;  // AVG values, each node once
  std::vector<double> out(where.size(), 0.0);
  std::size_t unvalued = 0;
  for (std::size_t k = 0; k < where.size(); ++k) {
    const path_ops::PointInElement& w = where[k];
    if (w.element == 0) continue;
    bool valued = true;
    for (std::size_t i = 0; i < w.nodes.size(); ++i) {
      std::optional<double> v;
      if (average || ni.element_item.empty()) {
        auto it = nodal.find(w.nodes[i]);
        if (it == nodal.end())
          it = nodal.emplace(w.nodes[i], nodal_item_value(r, c, ni, 0, w.nodes[i])).first;
        v = it->second;
      } else {
        v = element_item_value_at_node(r, c, ni, 0, w.element, w.nodes[i]);
      }
      if (v)
        out[k] += w.weights[i] * *v;
      else
        valued = false;
    }
    if (!valued) ++unvalued;
  }
  path_ops::warn_outside(r, c, where, unvalued);
  return out;
}

double get_path_value(DeckReader& r, const Command& c, const std::string& what,
                      const std::string& label, int point) {
  const PathDefinition& p = complete_path(r, c);
  const auto& v = path_item(r, c, p, label);
  if (what == "MAX") return *std::max_element(v.begin(), v.end());
  if (what == "MIN") return *std::min_element(v.begin(), v.end());
  if (what == "LAST") return v.back();
  if (what == "FIRST") return v.front();
  if (what == "ITEM") {
    if (point < 1 || point > static_cast<int>(v.size()))
      r.fail(c, fmt::format("*GET PATH ITEM,{},PATHPT,{}: the point must be 1..{}", label, point,
                            v.size()));
    return v[static_cast<std::size_t>(point - 1)];
  }
  r.fail(c, fmt::format("*GET PATH item '{}': MAX, MIN, LAST, FIRST or ITEM,Lab,PATHPT,n", what));
}

void register_post1_path_commands(std::vector<CommandSpec>& t) {
  t.push_back({"PATH", path_ops::cmd_path, kPost1});
  t.push_back({"PPATH", path_ops::cmd_ppath, kPost1});
  t.push_back({"FLST", path_ops::cmd_flst, kPost1});
  t.push_back({"FITEM", path_ops::cmd_fitem, kPost1});
  t.push_back({"PDEF", path_ops::cmd_pdef, kPost1});
  t.push_back({"PCALC", path_ops::cmd_pcalc, kPost1});
  t.push_back({"PVECT", path_ops::cmd_pvect, kPost1});
  t.push_back({"PDOT", path_ops::cmd_vector_product, kPost1});
  t.push_back({"PCROSS", path_ops::cmd_vector_product, kPost1});
  t.push_back({"PRANGE", path_ops::cmd_prange, kPost1});
  t.push_back({"PRPATH", path_ops::cmd_prpath, kPost1});
  t.push_back({"PLPATH", path_ops::cmd_plpath, kPost1});
  t.push_back({"PLPAGM", path_ops::cmd_plpagm, kPost1,
               "path items drawn on the model's picture: graphics only (PLPATH draws them as a "
               "graph)"});
  t.push_back({"PADELE", path_ops::cmd_padele, kPost1});
  register_post1_section_commands(t);
}

}  // namespace impactfe::deck
