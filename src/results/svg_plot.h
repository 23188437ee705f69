#pragma once
/// The pictures of the POST1 / POST26 plot commands as small, self-contained SVG files: a model
/// drawing (PLDISP deformed shapes, PLNSOL / PLESOL / PLETAB contours; several plots overlaid
/// on one picture under /NOERASE) and an x-y graph (PLVAR). Orthographic projection on the
/// screen plane of the /VIEW direction; no window is ever opened.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace impactfe {

/// The viewing settings a projection needs (/VIEW, /VUP, /FOCUS, /DIST).
struct PlotView {
  Eigen::Vector3d direction{0.0, 0.0, 1.0};  // from the focus point towards the viewer
  Eigen::Vector3d up{0.0, 1.0, 0.0};         // screen up (/VUP), projected on the screen plane
  /// Focus point components given by /FOCUS (the others: centre of the drawing).
  std::optional<double> focus[3];
  /// /DIST: half-size of the visible window (model units); automatic fit when absent.
  std::optional<double> distance;
};

/// One drawn element: a point (mass), a polyline (spar, spring, gap), or a polygon (shell, brick
/// face). Contour drawings give it a value (flat fill / line colour).
struct PlotShape {
  enum class Kind { Point, Line, Polygon } kind = Kind::Line;
  std::vector<Eigen::Vector3d> points;
  std::optional<double> value;       // one value for the whole shape (element results)
  std::vector<double> point_values;  // or one per point (nodal results), shaded in between
};

/// The drawing of one plot command; /NOERASE stacks several layers on one picture.
struct PlotLayer {
  std::vector<PlotShape> shapes;
  enum class Style { Deformed, Undeformed, Edges } style = Style::Deformed;
  std::vector<std::string> legend;  // text lines shown beside the picture (STEP=1 ITER=6 ...)
};

/// Colour scale of a contour picture (9 bands between min and max, as MAPDL's legend).
struct ContourScale {
  std::string title;  // e.g. "UY", "SEQV (AVG)"
  double min = 0.0;
  double max = 0.0;
};

/// A model picture: header lines, layers and an optional contour legend.
class ModelPicture {
 public:
  explicit ModelPicture(std::vector<std::string> header) : header_(std::move(header)) {}
  void add_layer(PlotLayer layer) { layers_.push_back(std::move(layer)); }
  void set_contour(const ContourScale& scale) { contour_ = scale; }
  std::size_t n_layers() const { return layers_.size(); }
  /// The SVG text of the picture seen through `view`.
  std::string svg(const PlotView& view) const;

 private:
  std::vector<std::string> header_;
  std::vector<PlotLayer> layers_;
  std::optional<ContourScale> contour_;
};

/// The colour of a value on a contour scale (9 bands, blue → red; "#000000" when non-finite).
std::string contour_colour(const ContourScale& scale, double value);

/// One curve of an x-y graph.
struct GraphCurve {
  std::string name;
  std::vector<double> x;
  std::vector<double> y;
};

/// Axes and labels of an x-y graph (/AXLAB, /XRANGE, /YRANGE, /GRID, /TITLE).
struct GraphOptions {
  std::vector<std::string> header;
  std::string x_label = "TIME";
  std::string y_label = "VALUE";
  std::optional<std::pair<double, double>> x_range;
  std::optional<std::pair<double, double>> y_range;
  bool grid = false;
};

/// The SVG text of an x-y graph of the curves (PLVAR).
std::string xy_graph_svg(const std::vector<GraphCurve>& curves, const GraphOptions& options);

/// "Nice" axis ticks covering [lo, hi] (steps 1, 2, 5 × 10^k, about 5–10 ticks).
std::vector<double> nice_ticks(double lo, double hi);

/// Writes `text` to `path` (InputError naming the file when it cannot be written).
void write_text_file(const std::string& path, const std::string& text);

/// `text` with the characters XML and HTML reserve (& < > ") written as entities.
std::string xml_escape(const std::string& text);

}  // namespace impactfe
