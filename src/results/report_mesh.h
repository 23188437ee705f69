#pragma once
/// The mesh of the `impactfe report` 3-D view (surface triangles, lines, points) and its parts
/// ("bodies": nodes connected by elements other than gaps, e.g. the helmet and the head).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

struct ReportMesh {
  struct Body {
    std::string name;        // e.g. "the SHELL63 type 1 mat 1 real 1 part"
    std::vector<int> nodes;  // 0-based node indices (rows of the results file's node arrays)
  };
  std::vector<int> element_ids;              // = reader.elements() order
  std::map<int, std::size_t> element_index;  // element id -> index in element_ids
  std::vector<int> triangles;                // node indices, 3 per triangle
  std::vector<int> triangle_element;         // element index per triangle
  std::vector<int> edges;                    // node indices, 2 per element edge of the surfaces
  std::vector<int> lines;                    // node indices, 2 per line
  std::vector<int> line_element;
  std::vector<int> points;  // node indices
  std::vector<int> point_element;
  /// Target facets (TARGE170), drawn see-through over the structure: node indices, 3 per
  /// triangle, and the element index of each triangle. Contact elements are not drawn.
  std::vector<int> overlay_triangles;
  std::vector<int> overlay_element;
  std::vector<int> used_nodes;  // node indices referenced by some element, ascending
  /// Node indices of the elements that are neither contact nor target: the view's extent (a
  /// rigid floor far larger than the model does not shrink it), ascending.
  std::vector<int> framed_nodes;
  std::set<int> gap_nodes;   // node indices of gap elements (ShapeRole::Gap)
  std::vector<Body> bodies;  // parts by their smallest node id, then the single nodes
};

/// The drawable pieces of each element's registered cell (elements/cell_topology.h):
/// polygons of area cells (a 4-node shell with K = L is a triangle; quadrilaterals are split in
/// two triangles), the outer faces of volume cells (a face two of them share is dropped;
/// repeated nodes collapse), lines, and points (1-node elements, superelement nodes); target
/// facets as overlay triangles; contact elements not at all.
ReportMesh build_report_mesh(const ResultsReader& reader);

/// True for element types whose shape role is a gap (COMBIN40, CONTA178): their nodes are
/// picked for the nodal figures and they do not join bodies.
bool is_gap_type(const std::string& type_name);

}  // namespace impactfe
