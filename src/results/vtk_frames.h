#pragma once
/// What `impactfe export` writes, independent of the file format: one mesh (the model section's
/// nodes and elements as VTK cells) and one frame per distinct stored time, where a time present
/// in several analyses takes each value from the latest analysis that has it (an expansion pass
/// replaces the reduced run's values at its times; the merge rule of docs/results_file.md), so
/// there is never a second, overlapping mesh. Absent values stay NaN.
#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// The mesh: points are the nodes (ascending id); one cell per element whose nodes all exist.
struct VtkMesh {
  Eigen::MatrixXd points;            // n_points x 3
  std::vector<unsigned char> types;  // VTK cell type per cell (from the element registry)
  std::vector<long long> offsets;    // n_cells + 1, into connectivity
  std::vector<long long> connectivity;
  std::vector<int> element_ids, type_ids, mat_ids;
  std::vector<int> skipped_elements;  // elements that could not be drawn (a node is missing)
  /// Element results: every item name of any family (first-seen order) and, per family and
  /// element row, the cell index (-1 when the element is not drawn).
  std::vector<std::string> cell_items;

  std::size_t n_points() const { return static_cast<std::size_t>(points.rows()); }
  std::size_t n_cells() const { return types.size(); }
  /// Cell index of element `id`, -1 when it is not drawn.
  int cell_of(int id) const;
};

VtkMesh build_vtk_mesh(const ResultsReader& reader);

/// One output frame: a time and the stored points (analysis, index) at that time, in analysis
/// order (later ones override earlier ones where they have a value).
struct VtkFrame {
  double time = 0.0;
  std::vector<std::pair<int, int>> sources;
};

/// The frames of a file, sorted by time (only analyses with time points; modal results are not
/// frames).
std::vector<VtkFrame> vtk_frames(const ResultsReader& reader);

/// The arrays of one frame. Point arrays are n_points x 3 (row-major), cell arrays n_cells.
struct VtkFrameData {
  std::vector<std::pair<std::string, std::vector<double>>> point_arrays;  // U ROT V A RF RM
  std::vector<std::pair<std::string, std::vector<double>>> cell_arrays;   // mesh.cell_items
};

/// Reads the stored points of a frame (one time point of each source at a time) and merges
/// them: a later source's finite value replaces an earlier one.
VtkFrameData read_vtk_frame(const ResultsReader& reader, const VtkMesh& mesh,
                            const VtkFrame& frame);

/// Names of the point arrays, in the order read_vtk_frame returns them.
const std::vector<std::string>& vtk_point_array_names();

}  // namespace impactfe
