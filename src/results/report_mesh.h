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
    std::string name;        // e.g. "the SHELL63 part"
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
  std::vector<int> used_nodes;  // node indices referenced by some element, ascending
  std::set<int> gap_nodes;      // node indices of gap (COMBIN40) elements
  std::vector<Body> bodies;     // parts by their smallest node id, then the single nodes
};

/// Surfaces of shells (a 4-node shell with K = L is a triangle, a quadrilateral two) and bricks
/// (outer faces only: a face shared by two bricks is dropped; repeated nodes collapse), lines
/// of 2-node elements, points of 1-node elements and superelement nodes.
ReportMesh build_report_mesh(const ResultsReader& reader);

/// True for element types that act as gaps (COMBIN40): their nodes are picked for the nodal
/// figures and they do not join bodies.
bool is_gap_type(const std::string& type_name);

}  // namespace impactfe
