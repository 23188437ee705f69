#pragma once
/// `impactfe export`: ASCII VTK XML unstructured grids (.vtu), one per stored time point, and a
/// ParaView collection (.pvd) listing them with their times.
#include <string>

#include "results/results_file.h"

namespace impactfe {

/// Writes <out_dir>/<stem>_a<k>_<nnnnn>.vtu for time point nnnnn (0-based) of every analysis k
/// and <out_dir>/<stem>.pvd (DataSet timestep = time, group = "analysis_<k>", part = k - 1).
/// Points are the node coordinates (ascending node id); cells come from the element node lists:
/// vertex (VTK 1) for 1-node elements, line (3) for 2-node elements, triangle (5) for a 4-node
/// shell with K = L, quad (9), hexahedron (12), poly-vertex (2) for anything else (e.g. MATRIX50).
/// Point data U, ROT, V, A, RF (reaction force) as 3-vectors; absent values (NaN) are written
/// as 0 because VTK ASCII readers do not accept NaN. Cell data: element_id, type_id, mat_id.
/// Creates out_dir if needed; returns the number of .vtu files written.
int export_vtu_series(const ResultsReader& reader, const std::string& out_dir,
                      const std::string& stem);

}  // namespace impactfe
