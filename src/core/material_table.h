#pragma once
/// Nonlinear material data tables (TB, TBTEMP, TBDATA, TBPT; APDL_MODELING §6.3), parsed and
/// stored for the material laws that use them. A solve whose elements use a table of a law not
/// implemented yet stops with a clear message (deck validation).
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace impactfe {

struct MaterialTable {
  std::string label;   // TB Lab: PLAS, BISO, BKIN, MISO, KINH, MKIN, ELASTIC, FRIC, DISCRETE
  std::string option;  // TBOPT: BISO, BKIN, MISO, KINH (PLAS); ISOT (ELASTIC); ISO (FRIC)
  int mat = 1;
  int n_temperatures = 1;  // NTEMP
  int n_points = 0;        // NPTS
  /// One entry per temperature (TBTEMP; a single 0.0 entry when none was given): the constants
  /// of TBDATA (position 1 first) and the points (x, y) of TBPT in ascending x.
  struct Temperature {
    double temperature = 0.0;
    std::vector<double> constants;
    std::vector<std::pair<double, double>> points;
  };
  std::vector<Temperature> temperatures;
  SourceLocation where;  // the TB command
};

}  // namespace impactfe
