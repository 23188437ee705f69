#pragma once
/// POST1's view of a results file: the numbered data sets (APDL_SCRIPTING §D.1), the data of one
/// set (or of a time between two sets), and the item look-ups the POST1 / POST26 / *GET
/// commands share: nodal labels, element items by MAPDL sequence number (SMISC,1, LS,1, S,EQV
/// through the element registry) and element volumes.
#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// One data set: a stored time point of a static, transient or expansion analysis (t = 0 of a
/// transient is not a set, as in MAPDL), or a mode of a modal analysis. The time points of a
/// reduced transient are sets only when no expansion pass follows it (then its slave DOFs are
/// absent).
struct ResultSet {
  int number = 0;     // cumulative, 1-based
  int analysis = 0;   // 1-based /analysis_<k>
  int point = -1;     // 0-based time point of the analysis (-1 for a mode)
  int mode = 0;       // 1-based mode (0 for a time point)
  double time = 0.0;  // time, or frequency in Hz for a mode
  int load_step = 1;
  int substep = 1;  // the mode number for a mode
  ResultsKind kind = ResultsKind::Static;
};

/// The sets of a results file in file order.
std::vector<ResultSet> result_sets(const ResultsReader& reader);

/// The data of the current POST1 set.
struct SetData {
  ResultSet set;           // for an interpolated set: number 0 and the requested time
  TimePoint point;         // U (the mode shape of a mode), V, A, R and the element tables
  double frequency = 0.0;  // Hz, modes only
  bool interpolated = false;
  bool reduced = false;  // reduced-transient set: slave DOFs and element results not computed
  /// Element id → (family name, row) of point.element_results.
  std::map<int, std::pair<std::string, int>> element_rows;
};

/// False when OUTRES did not write the nodal array `dataset` ('U', 'V', 'A') of node row `row`
/// at this set: the row is all NaN while another node of the array has a value, or U is
/// absent altogether (a node that has DOFs always has a finite displacement when written).
bool nodal_row_written(const SetData& data, char dataset, int row);

/// Reads one set.
SetData read_set(const ResultsReader& reader, const ResultSet& set);
/// Linear interpolation between two sets at time t (APDL_SCRIPTING §D.1: items missing from
/// either set become absent).
SetData interpolate_sets(const SetData& a, const SetData& b, double t);
/// Scales every result of the set by `factor` (SET Fact); status items are left as they are.
void scale_set(SetData& data, double factor);

/// A nodal result label: UX..ROTZ, VX..VZ, AX..AZ, FX..MZ, and the vector sums USUM, VSUM, ASUM,
/// RSUM (ROT SUM). nullopt when unknown.
struct NodalLabel {
  char dataset = 'U';  // U V A R
  int column = 0;      // 0..5, or -1 for the sum of columns 0..2 (3..5 when rotation_sum)
  bool rotation_sum = false;
};
std::optional<NodalLabel> parse_nodal_item(const std::string& label);
/// Maps MAPDL's Item,Comp of NSOL / *GET NODE / PRNSOL (U,X  ROT,Z  V,SUM  A,Y  RF,FX  U,  ...)
/// to a label of parse_nodal_item ("" when unknown).
std::string nodal_label_of(const std::string& item, const std::string& comp);

/// Value of a nodal label at a row of the set; NaN when not stored. Sums treat absent
/// components as zero (and are NaN only when all three are absent).
double nodal_value(const SetData& data, int row, const NodalLabel& label);

/// Value of MAPDL's element item Item,Comp (SMISC,1, LS,1, S,EQV, or a stored name such as
/// FORC) for element `element` of ANSYS type `type_name`: nullopt when that element type has no
/// such item, NaN when it has it but the set holds no value.
std::optional<double> element_item(const SetData& data, int element, const std::string& type_name,
                                   const std::string& item, const std::string& comp);

}  // namespace impactfe
