#include "results/svg_plot.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/errors.h"

namespace impactfe {

namespace {

// Canvas: the drawing area on the left, a text column (legends, contour scale) on the right.
constexpr double kWidth = 980.0;
constexpr double kHeight = 640.0;
constexpr double kPlotLeft = 20.0;
constexpr double kPlotTop = 70.0;
constexpr double kPlotSize = 550.0;
constexpr double kTextLeft = 600.0;

/// MAPDL's nine contour colours, blue (minimum) to red (maximum).
constexpr const char* kBands[9] = {"#0000ff", "#0078ff", "#00d2ff", "#00ffaa", "#00ff00",
                                   "#b4ff00", "#ffff00", "#ffa000", "#ff0000"};
constexpr const char* kCurveColours[10] = {"#1f3fbf", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                           "#17becf", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"};

std::string header_svg(double width, double height) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"monospace\" font-size=\"12\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      width, height);
}

std::string text_svg(double x, double y, const std::string& text, const char* extra = "") {
  return fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\"{}>{}</text>\n", x, y, extra,
                     xml_escape(text));
}

/// Short number for labels: %g with 4 significant digits.
std::string short_number(double v) {
  if (std::fabs(v) < 1e-300) return "0";
  return fmt::format("{:.4g}", v);
}

/// Screen axes of a view: right and up unit vectors, and the direction (towards the viewer).
struct Screen {
  Eigen::Vector3d right, up, toward;
};

Screen screen_of(const PlotView& view) {
  Eigen::Vector3d d = view.direction;
  if (d.norm() == 0.0) d = Eigen::Vector3d::UnitZ();
  d.normalize();
  Eigen::Vector3d up = view.up;
  if (up.cross(d).norm() < 1e-9)
    up = std::fabs(d.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  Eigen::Vector3d right = up.cross(d).normalized();
  return Screen{right, d.cross(right).normalized(), d};
}

/// A shape with one value per point, drawn as small pieces coloured by the interpolated value:
/// a line in 8 segments, a polygon as a fan of triangles from its centroid, each split in 4.
template <typename ToScreen>
std::string shaded(const PlotShape& sh, const ContourScale& scale, const ToScreen& to_screen) {
  std::string out;
  const auto& p = sh.points;
  const auto& v = sh.point_values;
  if (sh.kind == PlotShape::Kind::Point) {
    const auto q = to_screen(p.front());
    return fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3.5\" fill=\"{}\"/>\n", q.x(),
                       q.y(), contour_colour(scale, v.front()));
  }
  if (sh.kind == PlotShape::Kind::Line) {
    constexpr int kSegments = 8;
    for (int k = 0; k < kSegments; ++k) {
      const double a = static_cast<double>(k) / kSegments, b = (k + 1.0) / kSegments;
      const auto qa = to_screen(Eigen::Vector3d(p.front() + a * (p.back() - p.front())));
      const auto qb = to_screen(Eigen::Vector3d(p.front() + b * (p.back() - p.front())));
      const double value = v.front() + 0.5 * (a + b) * (v.back() - v.front());
      out += fmt::format(
          "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" "
          "stroke=\"{}\" stroke-width=\"3\" stroke-linecap=\"round\"/>\n",
          qa.x(), qa.y(), qb.x(), qb.y(), contour_colour(scale, value));
    }
    return out;
  }
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double vc = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    centre += p[k];
    vc += v[k];
  }
  centre /= static_cast<double>(p.size());
  vc /= static_cast<double>(p.size());
  auto triangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      double value) {
    const auto qa = to_screen(a), qb = to_screen(b), qc = to_screen(c);
    const std::string colour = contour_colour(scale, value);
    out += fmt::format(
        "<polygon points=\"{:.2f},{:.2f} {:.2f},{:.2f} {:.2f},{:.2f}\" fill=\"{}\" "
        "stroke=\"{}\" stroke-width=\"0.5\"/>\n",
        qa.x(), qa.y(), qb.x(), qb.y(), qc.x(), qc.y(), colour, colour);
  };
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::size_t j = (k + 1) % p.size();
    const Eigen::Vector3d m0 = 0.5 * (p[k] + p[j]), m1 = 0.5 * (p[j] + centre),
                          m2 = 0.5 * (centre + p[k]);
    const double w0 = 0.5 * (v[k] + v[j]), w1 = 0.5 * (v[j] + vc), w2 = 0.5 * (vc + v[k]);
    triangle(p[k], m0, m2, (v[k] + w0 + w2) / 3.0);
    triangle(m0, p[j], m1, (w0 + v[j] + w1) / 3.0);
    triangle(m2, m1, centre, (w2 + w1 + vc) / 3.0);
    triangle(m0, m1, m2, (w0 + w1 + w2) / 3.0);
  }
  // The element outline over the shading.
  std::string pts;
  for (const auto& x : p) {
    const auto q = to_screen(x);
    pts += fmt::format("{:.2f},{:.2f} ", q.x(), q.y());
  }
  out += fmt::format(
      "<polygon points=\"{}\" fill=\"none\" stroke=\"#333333\" "
      "stroke-width=\"0.8\"/>\n",
      pts);
  return out;
}

/// Where the model lands on the plot square: the screen point of the centre and the scale
/// (/FOCUS, /DIST, or the extent of everything drawn).
struct PlotFrame {
  double cx = 0.0, cy = 0.0, scale = 1.0;
  Eigen::Vector2d to_screen(const Screen& s, const Eigen::Vector3d& p) const {
    return Eigen::Vector2d(kPlotLeft + 0.5 * kPlotSize + scale * (s.right.dot(p) - cx),
                           kPlotTop + 0.5 * kPlotSize - scale * (s.up.dot(p) - cy));
  }
};

PlotFrame frame_of(const std::vector<PlotLayer>& layers, const Screen& s, const PlotView& view) {
  // Extent of everything drawn, on screen axes and in space (for the default focus).
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(xmin), hi = -lo;
  for (const auto& layer : layers)
    for (const auto& shape : layer.shapes)
      for (const auto& p : shape.points) {
        xmin = std::min(xmin, s.right.dot(p));
        xmax = std::max(xmax, s.right.dot(p));
        ymin = std::min(ymin, s.up.dot(p));
        ymax = std::max(ymax, s.up.dot(p));
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  if (!std::isfinite(xmin)) xmin = xmax = ymin = ymax = 0.0, lo = hi = Eigen::Vector3d::Zero();
  Eigen::Vector3d focus = 0.5 * (lo + hi);
  for (int k = 0; k < 3; ++k)
    if (view.focus[k]) focus[k] = *view.focus[k];
  double cx = s.right.dot(focus), cy = s.up.dot(focus);
  double half = 0.0;
  if (view.distance && *view.distance > 0.0) {
    half = *view.distance;
  } else {
    half = 0.55 * std::max({xmax - xmin, ymax - ymin, 1e-12});
    if (!view.focus[0] && !view.focus[1] && !view.focus[2]) {
      cx = 0.5 * (xmin + xmax);
      cy = 0.5 * (ymin + ymax);
    } else {
      half = 1.1 * std::max({std::fabs(xmax - cx), std::fabs(xmin - cx), std::fabs(ymax - cy),
                             std::fabs(ymin - cy), 1e-12});
    }
  }
  return PlotFrame{cx, cy, 0.5 * kPlotSize / half};
}

/// One layer's shapes, far from the viewer first (painter's order).
template <typename ToScreen>
std::string layer_svg(const PlotLayer& layer, const Screen& s,
                      const std::optional<ContourScale>& contour, const ToScreen& to_screen) {
  const bool undeformed = layer.style == PlotLayer::Style::Undeformed;
  const bool edges = layer.style == PlotLayer::Style::Edges;
  const char* stroke = undeformed || edges ? "#888888" : "#1f3fbf";
  const char* dash = edges ? " stroke-dasharray=\"4 3\"" : "";
  std::vector<const PlotShape*> order;
  for (const auto& shape : layer.shapes) order.push_back(&shape);
  auto depth = [&](const PlotShape* sh) {
    double d = 0.0;
    for (const auto& p : sh->points) d += s.toward.dot(p);
    return sh->points.empty() ? 0.0 : d / static_cast<double>(sh->points.size());
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](const PlotShape* a, const PlotShape* b) { return depth(a) < depth(b); });
  std::string out = "<g>\n";
  for (const PlotShape* sh : order) {
    if (contour && sh->point_values.size() == sh->points.size() && !sh->points.empty()) {
      out += shaded(*sh, *contour, to_screen);
      continue;
    }
    const std::string colour =
        sh->value && contour ? contour_colour(*contour, *sh->value) : std::string(stroke);
    std::string pts;
    for (const auto& p : sh->points) {
      const auto q = to_screen(p);
      pts += fmt::format("{:.2f},{:.2f} ", q.x(), q.y());
    }
    if (sh->kind == PlotShape::Kind::Point) {
      const auto q = to_screen(sh->points.front());
      out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\"/>\n", q.x(),
                         q.y(), undeformed || edges ? 2.5 : 3.5, colour);
    } else if (sh->kind == PlotShape::Kind::Line) {
      out += fmt::format(
          "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{}/>\n", pts,
          colour, sh->value ? 3.0 : 1.5, dash);
    } else {
      const std::string fill =
          sh->value && contour ? colour : (undeformed || edges ? "none" : "#dfe6f7");
      out +=
          fmt::format("<polygon points=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"1\"{}/>\n",
                      pts, fill, sh->value && contour ? "#333333" : stroke, dash);
    }
  }
  out += "</g>\n";
  return out;
}

/// The text column: the contour legend, then each layer's legend lines.
std::string legend_svg(const std::vector<PlotLayer>& layers,
                       const std::optional<ContourScale>& contour) {
  std::string out;
  double y = kPlotTop + 10.0;
  if (contour) {
    out += text_svg(kTextLeft, y, contour->title);
    y += 8.0;
    for (int b = 8; b >= 0; --b) {
      const double v0 = contour->min + (contour->max - contour->min) * b / 9.0;
      const double v1 = contour->min + (contour->max - contour->min) * (b + 1) / 9.0;
      out += fmt::format("<rect x=\"{}\" y=\"{:.1f}\" width=\"18\" height=\"16\" fill=\"{}\"/>\n",
                         kTextLeft, y, kBands[b]);
      out += text_svg(kTextLeft + 24.0, y + 12.0,
                      fmt::format("{} to {}", short_number(v0), short_number(v1)));
      y += 18.0;
    }
    out += text_svg(kTextLeft, y + 14.0, "MN " + short_number(contour->min));
    out += text_svg(kTextLeft, y + 29.0, "MX " + short_number(contour->max));
    y += 50.0;
  }
  for (const auto& layer : layers) {
    for (const auto& line : layer.legend) {
      if (y > kHeight - 8.0) break;
      out += text_svg(kTextLeft, y, line);
      y += 14.0;
    }
  }
  return out;
}

}  // namespace

std::string contour_colour(const ContourScale& scale, double value) {
  if (!std::isfinite(value)) return "#000000";
  const double span = scale.max - scale.min;
  int band = 4;
  if (span > 0.0) band = static_cast<int>(std::floor(9.0 * (value - scale.min) / span));
  return kBands[std::clamp(band, 0, 8)];
}

std::string ModelPicture::svg(const PlotView& view) const {
  const Screen s = screen_of(view);
  const PlotFrame frame = frame_of(layers_, s, view);
  const auto to_screen = [&](const Eigen::Vector3d& p) { return frame.to_screen(s, p); };
  std::string out = header_svg(kWidth, kHeight);
  double y = 18.0;
  for (const auto& line : header_) {
    out += text_svg(kPlotLeft, y, line);
    y += 15.0;
  }
  out += fmt::format(
      "<clipPath id=\"plot\"><rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{2}\"/></clipPath>\n"
      "<rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{2}\" fill=\"none\" stroke=\"#999\"/>\n"
      "<g clip-path=\"url(#plot)\" stroke-linejoin=\"round\">\n",
      kPlotLeft, kPlotTop, kPlotSize);
  for (const auto& layer : layers_) out += layer_svg(layer, s, contour_, to_screen);
  out += "</g>\n";
  out += legend_svg(layers_, contour_);
  out += "</svg>\n";
  return out;
}

std::vector<double> nice_ticks(double lo, double hi) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / 6.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (f * mag >= raw) {
      step = f * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
    ticks.push_back(std::fabs(t) < 1e-12 * step ? 0.0 : t);
  return ticks;
}

std::string xy_graph_svg(const std::vector<GraphCurve>& curves, const GraphOptions& options) {
  constexpr double left = 90.0, top = 70.0, width = 620.0, height = 460.0;
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const auto& c : curves)
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      if (!std::isfinite(c.x[k]) || !std::isfinite(c.y[k])) continue;
      xmin = std::min(xmin, c.x[k]);
      xmax = std::max(xmax, c.x[k]);
      ymin = std::min(ymin, c.y[k]);
      ymax = std::max(ymax, c.y[k]);
    }
  if (!std::isfinite(xmin)) xmin = 0.0, xmax = 1.0, ymin = 0.0, ymax = 1.0;
  if (options.x_range) std::tie(xmin, xmax) = *options.x_range;
  if (options.y_range) std::tie(ymin, ymax) = *options.y_range;
  if (xmax <= xmin) xmax = xmin + (xmin != 0.0 ? std::fabs(xmin) : 1.0);
  if (ymax <= ymin) {
    const double pad = ymin != 0.0 ? 0.1 * std::fabs(ymin) : 1.0;
    ymin -= pad;
    ymax += pad;
  }
  if (!options.y_range) {
    const auto yt = nice_ticks(ymin, ymax);
    const double step = yt.size() > 1 ? yt[1] - yt[0] : 0.0;
    if (step > 0.0) {
      ymin = std::floor(ymin / step + 1e-9) * step;
      ymax = std::ceil(ymax / step - 1e-9) * step;
    }
  }
  auto sx = [&](double x) { return left + width * (x - xmin) / (xmax - xmin); };
  auto sy = [&](double y) { return top + height - height * (y - ymin) / (ymax - ymin); };

  std::string out = header_svg(kWidth, kHeight);
  double ty = 18.0;
  for (const auto& line : options.header) {
    out += text_svg(20.0, ty, line);
    ty += 15.0;
  }
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n", left,
      top, width, height);
  for (double t : nice_ticks(xmin, xmax)) {
    const double x = sx(t);
    if (options.grid)
      out += fmt::format(
          "<line x1=\"{0:.2f}\" y1=\"{1}\" x2=\"{0:.2f}\" y2=\"{2}\" stroke=\"#ddd\"/>\n", x, top,
          top + height);
    out += fmt::format(
        "<line x1=\"{0:.2f}\" y1=\"{1}\" x2=\"{0:.2f}\" y2=\"{2}\" stroke=\"black\"/>\n", x,
        top + height, top + height + 5.0);
    out += text_svg(x, top + height + 18.0, short_number(t), " text-anchor=\"middle\"");
  }
  for (double t : nice_ticks(ymin, ymax)) {
    const double y = sy(t);
    if (options.grid)
      out += fmt::format(
          "<line x1=\"{0}\" y1=\"{1:.2f}\" x2=\"{2}\" y2=\"{1:.2f}\" stroke=\"#ddd\"/>\n", left, y,
          left + width);
    out += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.2f}\" x2=\"{2}\" y2=\"{1:.2f}\" stroke=\"black\"/>\n",
        left - 5.0, y, left);
    out += text_svg(left - 8.0, y + 4.0, short_number(t), " text-anchor=\"end\"");
  }
  if (ymin < 0.0 && ymax > 0.0)
    out +=
        fmt::format("<line x1=\"{0}\" y1=\"{2:.2f}\" x2=\"{1}\" y2=\"{2:.2f}\" stroke=\"#888\"/>\n",
                    left, left + width, sy(0.0));
  out +=
      text_svg(left + 0.5 * width, top + height + 40.0, options.x_label, " text-anchor=\"middle\"");
  out += fmt::format(
      "<text x=\"24\" y=\"{0:.1f}\" text-anchor=\"middle\" transform=\"rotate(-90 24 {0:.1f})\">"
      "{1}</text>\n",
      top + 0.5 * height, xml_escape(options.y_label));
  out += fmt::format(
      "<clipPath id=\"graph\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n",
      left, top, width, height);
  out += "<g clip-path=\"url(#graph)\" fill=\"none\" stroke-width=\"1.6\">\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    std::string pts;
    for (std::size_t k = 0; k < curves[c].x.size(); ++k)
      if (std::isfinite(curves[c].x[k]) && std::isfinite(curves[c].y[k]))
        pts += fmt::format("{:.2f},{:.2f} ", sx(curves[c].x[k]), sy(curves[c].y[k]));
    out += fmt::format("<polyline points=\"{}\" stroke=\"{}\"/>\n", pts, kCurveColours[c % 10]);
  }
  out += "</g>\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const double y = top + 14.0 + 18.0 * static_cast<double>(c);
    out += fmt::format(
        "<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"{}\" "
        "stroke-width=\"2\"/>\n",
        left + width + 12.0, y - 4.0, left + width + 36.0, y - 4.0, kCurveColours[c % 10]);
    out += text_svg(left + width + 42.0, y, curves[c].name);
  }
  out += "</svg>\n";
  return out;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw InputError(fmt::format("cannot write '{}'", path));
  f << text;
  if (!f) throw InputError(fmt::format("cannot write '{}'", path));
}

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace impactfe
