#pragma once
/// Post-processing queries of `impactfe post`: time histories as CSV, modal frequencies, mode
/// shapes and a human summary of a results file.
#include <string>
#include <utility>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// One requested CSV column: a nodal quantity (NSOL), an element item (ESOL) or a GP gap force.
struct PostRequest {
  enum Kind { Nodal, Element, Gap, Contact, Part } kind = Nodal;
  int id = 0;  // node, element or 1-based gap number
  /// Upper-cased: UX..MZ (Nodal), item name (Element), empty (Gap), FX FY FZ (Contact), KE IE
  /// HE (Part).
  std::string label;
};

/// Parses "NODE,LAB", e.g. "2,UX" (LAB as accepted by ResultsReader::nodal_series).
PostRequest parse_nsol(const std::string& spec);
/// Parses "ELEM,ITEM", e.g. "6,SAXL".
PostRequest parse_esol(const std::string& spec);
/// Parses "NUM", the 1-based GP gap number.
PostRequest parse_gapf(const std::string& spec);
/// --rcforc N,FX: the force on the contact surface of explicit contact entity N.
PostRequest parse_rcforc(const std::string& spec);
/// --part N,KE|IE|HE: the kinetic, internal or hourglass energy of part N of an explicit run.
PostRequest parse_part_energy(const std::string& spec);

/// Column header of a request: N<node>_<LAB>, E<elem>_<ITEM> or GAP<n>.
std::string post_column_name(const PostRequest& request);
/// The (time, value) series of a request (ResultsReader merge rule).
std::vector<std::pair<double, double>> post_series(const ResultsReader& reader,
                                                   const PostRequest& request);

/// CSV "time,<col>,<col>..." with one row per stored time point where at least one requested
/// quantity exists (the union of the columns' times, ascending; same time = same_time()).
/// A column without a value at that time is left empty. Numbers are printf "%.10e".
/// A time stored twice in one series gives two rows.
std::string post_csv(const ResultsReader& reader, const std::vector<PostRequest>& requests);
/// "mode,frequency_hz" rows of the last modal analysis.
std::string frequencies_csv(const ResultsReader& reader);
/// "node,UX,UY,UZ,ROTX,ROTY,ROTZ" rows of 1-based `mode`; absent DOFs (NaN) are left empty.
std::string mode_shape_csv(const ResultsReader& reader, int mode);
/// Human summary: title, counts, and per analysis kind, status, time points, time range,
/// element families, gaps, modes and attributes.
std::string results_info(const ResultsReader& reader);

}  // namespace impactfe
