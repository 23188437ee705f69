#pragma once
/// `impactfe report`: one self-contained HTML page (no network when it opens) that shows a
/// results file: run summary, energy balance, time histories like the thesis figures, gap status
/// timeline, modal table and a 3-D deformed-shape view. The page is a template, a style sheet
/// and one script bundle (uPlot + three.js + the page code, bundled at build time from the npm
/// registry and compiled into the binary), plus the data of the run as JSON. docs/report.md.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// What the report shows; every choice left empty is made automatically.
struct ReportOptions {
  /// Nodes of the time-history figures (--node). Empty: per body (mesh part connected without
  /// gap elements), the node with the largest response and the moving nodes of gap elements.
  std::vector<int> nodes;
  /// Elements of the stress figure (--element). Empty: the most stressed element of each
  /// element family that has stresses.
  std::vector<int> elements;
  /// Result labels (--item): nodal directions (UX UY UZ; VZ, AZ, ... select the same direction)
  /// and element items (SEQV, SAXL, FORC, ...). Empty: the directions whose peak displacement
  /// is at least 10 % of the largest, and the family's stress items.
  std::vector<std::string> items;
  /// At most this many points per curve (min/max-preserving sampling of longer histories).
  int max_points = 2000;
  /// At most this many time frames in the 3-D view (evenly spaced, the last one included).
  int max_frames = 300;
};

/// Min/max-preserving down-sampling of a time series (sorted by time) to at most `max_points`
/// points (>= 4): the first and last points are kept, the interior is cut into equal-count
/// buckets and each bucket keeps its smallest and largest value in time order, so peaks survive.
std::vector<std::pair<double, double>> sample_min_max(
    const std::vector<std::pair<double, double>>& series, int max_points);

/// Little-endian float32 values as base64 (NaN stays NaN): half the size of decimal text.
std::string float32_base64(const std::vector<double>& values);

/// The data of the page as JSON (schema: docs/report.md). Throws InputError for an unknown
/// node, element or item in `options`.
std::string report_data_json(const ResultsReader& reader, const ReportOptions& options);

/// The whole page: template + style + script bundle + data (the data's "</" escaped).
std::string report_html(const ResultsReader& reader, const ReportOptions& options);

/// Writes report_html() to `path`; returns the number of bytes written. Throws InputError when
/// the file cannot be written.
std::uintmax_t write_report(const ResultsReader& reader, const ReportOptions& options,
                            const std::string& path);

}  // namespace impactfe
