#pragma once
/// `impactfe export`: the results for ParaView, streamed one time point at a time (the whole
/// history is never in memory). Mesh, frames and the merge of analyses: results/vtk_frames.h;
/// layouts and how to open them: docs/results_file.md ("ParaView").
#include <string>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// What an export wrote (for the command's message and the tests).
struct ExportSummary {
  std::vector<std::string> files;  // main file first (the .vtkhdf or the .pvd)
  int frames = 0;
  std::size_t points = 0;
  std::size_t cells = 0;
  std::vector<int> skipped_elements;  // elements that could not be drawn (a node is missing)
  unsigned long long bytes = 0;       // total size of the files written
};

/// One VTKHDF file (format version 2.0, transient UnstructuredGrid with a `Steps` group): the
/// mesh once, point data U ROT V A RF RM (3 components) and cell data (every element result
/// item, plus element_id, type_id, mat_id) per frame, times in Steps/Values, compressed
/// (shuffle + deflate). Its time steps need ParaView 5.12 / VTK 9.3 or later: older readers know
/// VTKHDF 1.0 only and show the first step.
ExportSummary export_vtkhdf(const ResultsReader& reader, const std::string& path);

/// Binary VTK XML files: <out_dir>/<stem>_<nnnnn>.vtu per frame (appended raw data, zlib
/// compressed) and <out_dir>/<stem>.pvd listing them with their times. Same arrays as above.
/// `impactfe export`'s default: every ParaView opens the .pvd with all its time steps, and
/// VTK 9.1 (Debian) reads every .vtu.
ExportSummary export_vtu_series(const ResultsReader& reader, const std::string& out_dir,
                                const std::string& stem);

}  // namespace impactfe
