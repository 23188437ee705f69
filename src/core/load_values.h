#pragma once
/// Load values that are not plain numbers at a DOF: time functions (`%TABLE%` loads,
/// APDL_MODELING §5.5) and pressures on element faces (SF/SFE/SFA, §5.1-§5.4).
#include <array>
#include <compare>
#include <string>
#include <vector>

namespace impactfe {

/// A load history v(t): piecewise linear through (time_i, value_i), constant beyond the ends
/// (APDL_MODELING §5.5). The deck's TABLE parameters with primary variable TIME become one of
/// these (Model::time_functions, by table name).
struct TimeFunction {
  std::vector<double> time;  // ascending
  std::vector<double> value;
  /// Value at time t. Precondition: at least one point.
  double at(double t) const;
};

/// One face of one element: element number and the element type's face number (1-based, the
/// MAPDL face numbering of the element, e.g. SOLID185 face 1 = J-I-L-K).
struct FaceKey {
  int element = 0;
  int face = 1;
  auto operator<=>(const FaceKey&) const = default;
};

/// A pressure on a face: values at the face's nodes in the face-node order (constant when all
/// equal), or a time function (`table` non-empty: the pressure at time t is the table's value,
/// the same at every node). Positive pressure acts into the face (APDL_MODELING §5.3).
struct SurfaceLoad {
  std::array<double, 4> values{};
  std::string table;
  bool tabular() const { return !table.empty(); }
};

}  // namespace impactfe
