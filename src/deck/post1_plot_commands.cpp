// POST1 pictures (APDL_SCRIPTING §D.10): PLDISP, PLNSOL, PLESOL, PLETAB written as SVG files
// <jobname>NNN.svg in the working directory (no window), and the view settings they honour:
// /VIEW, /VUP, /FOCUS, /DIST, /AUTO, /DSCALE, /NOERASE, /ERASE, ERASE, /SHOW. Under /NOERASE
// each plot is drawn over the previous picture (thesis Fig. 5-1-2: the pendulum's positions).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "deck/post1_print.h"
#include "deck/post_support.h"
#include "elements/cell_topology.h"
#include "elements/element_registry.h"
#include "results/svg_plot.h"

namespace impactfe::deck {

namespace {

/// The drawn shapes of the selected elements with node positions from `at`.
std::vector<PlotShape> element_shapes(DeckReader& r, const std::vector<int>& elements,
                                      const std::function<Vec3(int)>& at) {
  std::vector<PlotShape> shapes;
  for (int id : elements)
    for (const auto& piece : cell_pieces(element_cell(r, id), r.model.elements.at(id).nodes)) {
      PlotShape s;
      s.kind = piece.kind == CellPiece::Kind::Point  ? PlotShape::Kind::Point
               : piece.kind == CellPiece::Kind::Line ? PlotShape::Kind::Line
                                                     : PlotShape::Kind::Polygon;
      for (int n : piece.nodes) s.points.push_back(at(n));
      shapes.push_back(std::move(s));
    }
  return shapes;
}

Vec3 displacement(DeckReader& r, const Command& c, const SetData& set, int node) {
  const int row = node_row(results(r, c).node_ids(), node);
  Vec3 u = Vec3::Zero();
  if (row < 0) return u;
  for (int k = 0; k < 3; ++k) {
    const double v = set.point.displacement(row, k);
    if (std::isfinite(v)) u[k] = v;
  }
  return u;
}

/// /DSCALE: the given multiplier, else 1 for a large-deflection analysis, else the factor that
/// shows the largest displacement as 5 % of the model size (MAPDL's AUTO).
double display_scale(DeckReader& r, const Command& c, const SetData& set,
                     const std::vector<int>& nodes, double& dmax) {
  dmax = 0.0;
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (int n : nodes) {
    dmax = std::max(dmax, displacement(r, c, set, n).norm());
    lo = lo.cwiseMin(r.model.node(n).x);
    hi = hi.cwiseMax(r.model.node(n).x);
  }
  const PostState& ps = post_state(r);
  if (ps.dscale) return *ps.dscale;
  if (r.model.options.large_deflection || dmax == 0.0) return 1.0;
  return 0.05 * std::max((hi - lo).norm(), 1e-30) / dmax;
}

std::string compact(double v) {
  return fmt::format("{:.4g}", v);
}

/// Draws a layer: on the picture kept by /NOERASE, or on a new one; rewrites the file.
void draw(DeckReader& r, const Command& c, std::vector<std::string> header, PlotLayer layer,
          std::optional<PlotLayer> undeformed, std::optional<ContourScale> contour) {
  PostState& ps = post_state(r);
  if (!ps.picture || !ps.noerase) {
    const std::string base = ps.show_name.empty() ? r.model.jobname : ps.show_name;
    ps.picture_path = fmt::format("{}{:03d}.svg", base, ps.n_pictures++);
    if (!r.model.title.empty()) header.insert(header.begin() + 1, r.model.title);
    ps.picture = std::make_unique<ModelPicture>(std::move(header));
  }
  if (undeformed) ps.picture->add_layer(std::move(*undeformed));
  ps.picture->add_layer(std::move(layer));
  if (contour) ps.picture->set_contour(*contour);
  try {
    write_text_file(ps.picture_path, ps.picture->svg(ps.view));
  } catch (const InputError& e) {
    r.fail(c, e.what());
  }
  Log::info("{}:{}: {}: picture {} ({} layer{})", c.where.file, c.where.line, c.name,
            ps.picture_path, ps.picture->n_layers(), ps.picture->n_layers() == 1 ? "" : "s");
}

/// The deformed layer of the selected elements, its undeformed companion for KUND 1/2, and the
/// legend line STEP= ITER= TIME= DMAX= DSCA= of the set.
struct Deformed {
  PlotLayer layer;
  std::optional<PlotLayer> undeformed;
  std::vector<int> elements;
  std::function<Vec3(int)> position;  // deformed position of a node
};

Deformed deformed_layer(DeckReader& r, const Command& c, int kund_field) {
  const SetData& set = current_set(r, c);
  Deformed d;
  d.elements = require_selected_elements(r, c);
  std::vector<int> nodes;
  for (int e : d.elements)
    for (int n : r.model.elements.at(e).nodes) nodes.push_back(n);
  double dmax = 0.0;
  const double scale = display_scale(r, c, set, nodes, dmax);
  d.position = [&r, &c, &set, scale](int n) {
    return Vec3(r.model.node(n).x + scale * displacement(r, c, set, n));
  };
  d.layer.shapes = element_shapes(r, d.elements, d.position);
  d.layer.legend.push_back(fmt::format("STEP={} {}={} {}={} DMAX={} DSCA={}", set.set.load_step,
                                       set.set.mode > 0 ? "MODE" : "ITER", set.set.substep,
                                       set.set.mode > 0 ? "FREQ" : "TIME", compact(set.set.time),
                                       compact(dmax), compact(scale)));
  const int kund = r.integer(c, kund_field, 0);
  if (kund < 0 || kund > 2) r.fail(c, fmt::format("KUND {} must be 0, 1 or 2", kund));
  if (kund > 0) {
    PlotLayer u;
    u.style = kund == 1 ? PlotLayer::Style::Undeformed : PlotLayer::Style::Edges;
    u.shapes = element_shapes(r, d.elements, [&](int n) { return r.model.node(n).x; });
    d.undeformed = std::move(u);
  }
  return d;
}

void cmd_pldisp(DeckReader& r, const Command& c) {
  Deformed d = deformed_layer(r, c, 1);
  draw(r, c, {"impactfe", "POST1 DISP"}, std::move(d.layer), std::move(d.undeformed), {});
}

/// Contour pictures: each shape gets its element's value (`element_value`) or its nodes' values
/// (`node_value` of the element at the node, shaded in between); the scale spans the values
/// drawn.
void contour_picture(DeckReader& r, const Command& c, const std::string& what,
                     const std::function<std::optional<double>(int element)>& element_value,
                     const std::function<std::optional<double>(int element, int node)>& node_value,
                     int kund_field) {
  Deformed d = deformed_layer(r, c, kund_field);
  std::vector<PlotShape> shapes;
  ContourScale scale{what, 1e300, -1e300};
  auto extend = [&](double v) {
    scale.min = std::min(scale.min, v);
    scale.max = std::max(scale.max, v);
  };
  for (int e : d.elements) {
    const std::optional<double> ev = element_value ? element_value(e) : std::nullopt;
    for (const auto& piece : cell_pieces(element_cell(r, e), r.model.elements.at(e).nodes)) {
      PlotShape sh;
      sh.kind = piece.kind == CellPiece::Kind::Point  ? PlotShape::Kind::Point
                : piece.kind == CellPiece::Kind::Line ? PlotShape::Kind::Line
                                                      : PlotShape::Kind::Polygon;
      bool complete = static_cast<bool>(node_value);
      for (int n : piece.nodes) {
        sh.points.push_back(d.position(n));
        if (!node_value) continue;
        const auto v = node_value(e, n);
        complete = complete && v && std::isfinite(*v);
        sh.point_values.push_back(v.value_or(0.0));
      }
      if (complete) {
        for (double v : sh.point_values) extend(v);
      } else {
        sh.point_values.clear();
        if (ev && std::isfinite(*ev)) {
          sh.value = ev;
          extend(*ev);
        }
      }
      shapes.push_back(std::move(sh));
    }
  }
  if (scale.min > scale.max) r.fail(c, fmt::format("no selected element has {} values", what));
  post_state(r).contour_range = std::make_pair(scale.min, scale.max);
  d.layer.shapes = std::move(shapes);
  draw(r, c, {"impactfe", "POST1 " + what}, std::move(d.layer), std::move(d.undeformed), scale);
}

void cmd_plnsol(DeckReader& r, const Command& c) {
  // PLNSOL,Item,Comp,KUND,Fact: nodal values (element items averaged at the nodes).
  const NodalItem item = nodal_item(r, c, r.label(c, 1), r.label(c, 2));
  if (item.labels.size() != 1)
    r.fail(c, fmt::format("{}: give one component in Comp (e.g. X, SUM, EQV)", item.heading));
  std::map<int, std::optional<double>> at_node;
  contour_picture(
      r, c, item.labels[0], {},
      [&](int, int node) {
        if (at_node.count(node) == 0) at_node[node] = nodal_item_value(r, c, item, 0, node);
        return at_node[node];
      },
      3);
}

void cmd_plesol(DeckReader& r, const Command& c) {
  // PLESOL,Item,Comp,KUND,Fact: each element's own values, not averaged across elements (MAPDL's
  // discontinuous contours): for the stresses and strains its values at its nodes, extrapolated
  // where the element has them; other items flat per element.
  const std::string item = r.label(c, 1), comp = r.label(c, 2);
  if (item.empty()) r.fail(c, "Item missing");
  const bool per_node = (item == "S" || item == "EPEL" || item == "EPPL" || item == "EPCR") &&
                        !comp.empty() && comp != "COMP" && comp != "PRIN";
  std::optional<NodalItem> nodal;
  if (per_node) nodal = nodal_item(r, c, item, comp);
  contour_picture(
      r, c, comp.empty() ? item : item + "," + comp,
      [&](int e) { return element_result(r, c, e, item, comp); },
      per_node ? std::function<std::optional<double>(int, int)>([&](int e, int node) {
        return element_item_value_at_node(r, c, *nodal, 0, e, node);
      })
               : std::function<std::optional<double>(int, int)>(),
      3);
}

void cmd_pletab(DeckReader& r, const Command& c) {
  // PLETAB,Itlab,Avglab: an element-table column, flat per element (Avglab NOAV; AVG is drawn
  // flat too, with a note).
  const std::string lab = r.label(c, 1);
  const PostState& ps = post_state(r);
  const auto col = std::find_if(ps.etable.begin(), ps.etable.end(),
                                [&](const EtableColumn& e) { return e.label == lab; });
  if (col == ps.etable.end()) r.fail(c, fmt::format("no element-table column '{}'", c.text(1)));
  if (r.label(c, 2) == "AVG")
    Log::info("{}:{}: PLETAB: AVG drawn as element values", c.where.file, c.where.line);
  const auto values = col->values;
  contour_picture(
      r, c, lab,
      [&](int e) -> std::optional<double> {
        const auto it = values.find(e);
        if (it == values.end()) return std::nullopt;
        return it->second;
      },
      {}, 0);
}

void cmd_dscale(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 2);
  PostState& ps = post_state(r);
  if (l.empty() || l == "AUTO" || l == "0")
    ps.dscale.reset();
  else if (l == "OFF")
    ps.dscale = 0.0;
  else
    ps.dscale = r.real(c, 2, 1.0);
}

void cmd_view(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (r.label(c, 2) == "WP") r.fail(c, "/VIEW,,WP (working plane view) is not supported");
  const Vec3 d(r.real(c, 2, 0.0), r.real(c, 3, 0.0), r.real(c, 4, 0.0));
  ps.view.direction = d.norm() > 0.0 ? d : Vec3(0.0, 0.0, 1.0);
}

void cmd_vup(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 2).empty() ? "Y" : r.label(c, 2);
  const bool neg = l[0] == '-';
  const std::string axis = neg ? l.substr(1) : l;
  if (axis != "X" && axis != "Y" && axis != "Z")
    r.fail(c, fmt::format("'{}': X, Y, Z, -X, -Y or -Z", c.text(2)));
  Vec3 up = Vec3::Zero();
  up[axis[0] - 'X'] = neg ? -1.0 : 1.0;
  post_state(r).view.up = up;
}

void cmd_focus(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  if (r.label(c, 2) == "AUTO" || c.last_given() <= 1) {
    for (auto& f : ps.view.focus) f.reset();
    return;
  }
  for (int k = 0; k < 3; ++k)
    if (!c.blank(2 + k)) ps.view.focus[k] = r.real(c, 2 + k, 0.0);
}

void cmd_dist(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const std::string l = r.label(c, 2);
  if (l.empty() || l == "AUTO") {
    ps.view.distance.reset();
    return;
  }
  const double v = r.real(c, 2, 0.0);
  if (v <= 0.0) r.fail(c, "DVAL must be positive");
  // KFACT 1: DVAL multiplies the current distance.
  ps.view.distance = r.integer(c, 3, 0) == 1 && ps.view.distance ? *ps.view.distance * v : v;
}

void cmd_auto(DeckReader& r, const Command&) {
  PostState& ps = post_state(r);
  for (auto& f : ps.view.focus) f.reset();
  ps.view.distance.reset();
}

void cmd_noerase(DeckReader& r, const Command& c) {
  post_state(r).noerase = c.name == "/NOERASE";
}

void cmd_erase(DeckReader& r, const Command&) {
  post_state(r).picture.reset();  // the next plot starts a new picture
}

void cmd_show(DeckReader& r, const Command& c) {
  PostState& ps = post_state(r);
  const std::string l = r.label(c, 1);
  static const char* kDevices[] = {"X11",   "X11C",   "3D",     "TERM", "OFF",   "PNG",
                                   "JPEG",  "TIFF",   "PSCR",   "HPGL", "HPGL2", "VRML",
                                   "WIN32", "WIN32C", "OPENGL", "SVG",  "DEFA",  "GRAPH"};
  ps.picture.reset();
  if (l.empty() || l == "CLOSE") return;
  if (std::find(std::begin(kDevices), std::end(kDevices), l) != std::end(kDevices)) {
    if (l != "SVG")
      Log::info("{}:{}: /SHOW,{}: pictures are written as SVG files", c.where.file, c.where.line,
                l);
    return;
  }
  ps.show_name = c.text(1);  // a file name: pictures <Fname>NNN.svg
  ps.n_pictures = 0;
}

}  // namespace

void register_post1_plot_commands(std::vector<CommandSpec>& t) {
  t.push_back({"PLDISP", cmd_pldisp, kPost1});
  t.push_back({"PLNSOL", cmd_plnsol, kPost1});
  t.push_back({"PLESOL", cmd_plesol, kPost1});
  t.push_back({"PLETAB", cmd_pletab, kPost1});
  t.push_back({"/DSCALE", cmd_dscale, kAnywhere});
  t.push_back({"/VIEW", cmd_view, kAnywhere});
  t.push_back({"/VUP", cmd_vup, kAnywhere});
  t.push_back({"/FOCUS", cmd_focus, kAnywhere});
  t.push_back({"/DIST", cmd_dist, kAnywhere});
  t.push_back({"/AUTO", cmd_auto, kAnywhere});
  t.push_back({"/NOERASE", cmd_noerase, kAnywhere});
  t.push_back({"/ERASE", cmd_noerase, kAnywhere});
  t.push_back({"ERASE", cmd_erase, kAnywhere});
  t.push_back({"/SHOW", cmd_show, kAnywhere});
}

}  // namespace impactfe::deck
