#pragma once
/// The post-processing state of one deck session (DeckReader::post): the results file being
/// read, the current POST1 set, the element table, sort order, the last sums, the plot settings
/// and the POST26 variables. Shared by the POST1 / POST26 / *GET handler files.
#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/coordinate_system.h"
#include "results/result_sets.h"
#include "results/results_file.h"
#include "results/svg_plot.h"

namespace impactfe::deck {

/// One ETABLE column: filled from the set current when it was defined (or at ETABLE,REFL).
struct EtableColumn {
  std::string label;
  std::string item;  // upper case, as given (SMISC, LS, S, VOLU, FORC, ...)
  std::string comp;
  std::map<int, double> values;  // element → value, for the elements selected at fill time
};

/// One POST26 variable over PostState::times.
struct Post26Variable {
  std::string name;
  /// NSOL, ESOL, RFORCE, GAPF (filled from the results: STORE refills them), or the operation
  /// or FILLDATA / VPUT that computed it.
  std::string kind;
  int id = 0;         // node / element / gap
  std::string label;  // resolved nodal label (UY) or element item (SMISC,1 → stored FORC)
  std::string item;   // element Item and Comp as given (ESOL)
  std::string comp;
  /// ESOL: position (1-based) in the element's node list of its NODE field; 0 for the element
  /// value (NODE blank or 0).
  int node_position = 0;
  std::vector<double> values;
  /// Imaginary parts (NSOL displacements of a harmonic analysis; 0 at time points of other
  /// analyses); empty for a real variable.
  std::vector<double> imag;
};

/// Last NSORT / ESORT (*GET,Par,SORT,0,MAX|MIN|IMAX|IMIN).
struct SortResult {
  double max = 0.0, min = 0.0;
  int imax = 0, imin = 0;
};

/// One point of a path (PPATH): a node's position or a location, and the coordinate system in
/// which the path runs from the previous point to this one.
struct PathPoint {
  bool defined = false;
  int node = 0;  // 0: given by its coordinates
  Vec3 x = Vec3::Zero();
  int csys = 0;
};

/// A path (PATH): its points, the number of divisions between adjacent points and the path
/// items (PDEF, PCALC, PVECT, ...) at its interpolation points, (points − 1) · divisions + 1 of
/// them. XG, YG, ZG (global coordinates) and S (distance along the path) are made when the last
/// point is defined.
struct PathDefinition {
  std::string name;
  int n_sets = 30;  // items the path may hold, XG YG ZG S included
  int n_div = 20;
  std::vector<PathPoint> points;
  std::vector<std::string> labels;  // items in definition order
  std::map<std::string, std::vector<double>> items;
  // PRANGE: the part of the path PRPATH lists and PLPATH draws (every `increment`-th point with
  // S in [s_min, s_max]) and PLPATH's x variable.
  int increment = 1;
  std::optional<double> s_min, s_max;
  std::string x_item = "S";

  bool complete() const {
    return !points.empty() &&
           std::all_of(points.begin(), points.end(), [](const PathPoint& p) { return p.defined; });
  }
};

struct PostState {
  // ---- results file -----------------------------------------------------------------------
  std::string file_command;  // FILE,Fname,Ext (post-only decks)
  std::string path;          // the file open in `reader`
  std::unique_ptr<ResultsReader> reader;
  std::size_t generation = static_cast<std::size_t>(-1);  // DeckReader::solutions at open
  std::vector<ResultSet> sets;

  // ---- POST1 ------------------------------------------------------------------------------
  std::optional<SetData> current;
  std::size_t current_generation = static_cast<std::size_t>(-1);
  std::vector<EtableColumn> etable;
  std::optional<std::vector<int>> node_order;     // NSORT (selected nodes, sorted)
  std::optional<std::vector<int>> element_order;  // ESORT
  std::optional<SortResult> sort;
  std::optional<std::array<double, 6>> fsum;  // FX FY FZ MX MY MZ of the last FSUM
  std::map<std::string, double> ssum;         // ETABLE label → last SSUM total
  std::string force_kind = "TOTAL";           // FORCE: TOTAL, STATIC, DAMP, INERT
  std::string shell_location = "TOP";         // SHELL: TOP, MID, BOT (the layer of shell S)
  // AVPRIN,KEY: 0 nodal principal stresses, SINT and SEQV from the averaged components, 1 the
  // averages of the elements' own values.
  int average_principal = 0;
  int layer = 0;  // LAYER: the layer of a layered shell whose surfaces SHELL picks (0: section)
  // RSYS,KCN: the system of the nodal vector results (U, ROT, V, A, reactions); nullopt = as
  // stored (global Cartesian, the nodal axes at a rotated node).
  std::optional<int> rsys;
  // RSYS,SOLU: element stress and strain components as the elements store them (their own
  // axes: shells), nodal vectors in the nodal axes.
  bool rsys_solution = false;
  // Element result axes at the current set (element_forces.h), keyed by element; cleared when
  // the current set changes (make_current).
  std::map<int, Mat3> result_axes;

  // ---- pictures ---------------------------------------------------------------------------
  PlotView view;
  std::optional<double> dscale;           // /DSCALE multiplier; nullopt = AUTO
  bool noerase = false;                   // /NOERASE: the next plot is drawn over the last picture
  std::string show_name;                  // /SHOW,Fname (picture file base name; default jobname)
  std::unique_ptr<ModelPicture> picture;  // the picture /NOERASE keeps drawing on
  std::string picture_path;
  int n_pictures = 0;
  // The least and greatest value of the last contour picture (PLNSOL, PLESOL, PLETAB) over what
  // it drew: *GET,Par,PLNSOL,0,MIN|MAX.
  std::optional<std::pair<double, double>> contour_range;

  // ---- paths (PATH, PPATH, PDEF, PCALC, ...) ------------------------------------------------
  std::map<std::string, PathDefinition> paths;
  std::string current_path;  // name of the path the path commands act on
  // FLST / FITEM: the node list a GUI-written PPATH,P51X takes its points from.
  std::vector<int> picked_nodes;
  int picked_expected = 0;

  // ---- POST26 -----------------------------------------------------------------------------
  int numvar = 10;
  std::vector<double> times;  // the stored time points inside TIMERANGE
  std::size_t times_generation = static_cast<std::size_t>(-1);
  std::map<int, Post26Variable> variables;  // 2..numvar (1 is TIME)
  std::optional<std::pair<double, double>> timerange;
  std::optional<std::pair<double, double>> prtime;
  int nprint = 1;  // NPRINT: PRVAR lists every Nth stored point, beginning with the first
  std::string x_label, y_label;  // /AXLAB
  std::optional<std::pair<double, double>> x_range, y_range;
  bool grid = false;
  int xvar = 1;
  bool amplitude_phase = false;  // PRCPLX,1: complex variables as amplitude and phase (degrees)
};

}  // namespace impactfe::deck
