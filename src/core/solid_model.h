#pragma once
/// The solid model of a deck (APDL_MODELING §3, §4): keypoints, lines, areas and volumes with
/// their numbers, attributes (xATT), mesh-size controls and the mesh each one generated (the
/// ownership maps of §4.7), plus the loads given on solid entities (§5.6). Plain data: the
/// geometry and meshing algorithms live in src/geometry.
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/coordinate_system.h"
#include "core/dof.h"
#include "core/errors.h"
#include "core/load_values.h"

namespace impactfe {

/// MAT, REAL, TYPE, ESYS, SECNUM given by KATT/LATT/AATT/VATT; 0 = none (the current pointer is
/// used at mesh time).
struct EntityAttributes {
  int mat = 0;
  int real = 0;
  int type = 0;
  int esys = 0;
  int secnum = 0;
};

struct Keypoint {
  int id = 0;
  Vec3 x = Vec3::Zero();  // global Cartesian
  EntityAttributes attr;
  std::optional<double> size;  // KESIZE
  int node = 0;                // node at the keypoint once meshed (0: none)
  std::vector<int> elements;   // point elements of KMESH
};

/// A line runs "straight in `path`": its points are the linear interpolation, in the
/// coordinates of that system, of its end keypoints (a straight segment in a Cartesian system,
/// an arc or helix in a cylindrical one). L uses the active system, LSTR the global Cartesian
/// one, LARC and the circular primitives a cylindrical system about the arc's axis.
struct Line {
  int id = 0;
  int kp1 = 0;
  int kp2 = 0;
  CoordinateSystem path;
  /// End coordinates in `path` (θ of kp2 continued from kp1 so the arc takes the intended way).
  Vec3 c1 = Vec3::Zero();
  Vec3 c2 = Vec3::Zero();
  // Division controls (LESIZE, or NDIV/SPACE of L).
  int ndiv = 0;                 // > 0: that many divisions
  std::optional<double> size;   // element edge length
  std::optional<double> angle;  // degrees per division on arcs (ANGSIZ)
  double space = 1.0;           // last/first ratio (> 0) or middle/end (< 0)
  EntityAttributes attr;
  int orientation_kb = 0;  // LATT KB, KE: beam orientation keypoints
  int orientation_ke = 0;
  // Mesh: nodes in order kp1 → kp2 including both end nodes (empty: no nodes yet), and the
  // line elements of LMESH.
  std::vector<int> nodes;
  std::vector<int> elements;
};

/// Mapped mesh of an area: a structured node grid. Quadrilateral grid: (n1 + 1) x (n2 + 1)
/// nodes, index i + j (n1 + 1), i from corner 0 toward corner 1, j from corner 0 toward the last
/// corner. Triangular lattice of a 3-sided area (n1 = n2 = n): rows j = 0..n of n − j + 1 nodes,
/// corner 0 at (0, 0), corner 1 at (n, 0), corner 2 at (0, n).
struct AreaGrid {
  int n1 = 0;
  int n2 = 0;
  bool triangular = false;
  std::vector<int> nodes;
  bool empty() const { return nodes.empty(); }
  int at(int i, int j) const;
};

struct Area {
  int id = 0;
  /// Boundary loop: line numbers, negative when the line runs against the loop direction.
  std::vector<int> lines;
  /// Corner keypoints in loop order (keypoints[k] starts lines[k]).
  std::vector<int> keypoints;
  EntityAttributes attr;
  std::optional<double> size;  // AESIZE
  AreaGrid grid;               // nodes (empty: not meshed)
  std::vector<int> interior_nodes;
  std::vector<int> elements;  // area elements of AMESH
};

struct Volume {
  int id = 0;
  std::vector<int> areas;
  EntityAttributes attr;
  std::vector<int> interior_nodes;
  std::vector<int> elements;
};

/// Global meshing controls (§4.1, §4.2, EXTOPT of §4.5).
struct MeshControls {
  double esize = 0.0;  // ESIZE SIZE (0: none)
  int esize_ndiv = 0;  // ESIZE NDIV (used when SIZE is 0)
  struct Desize {
    int minl = 3;
    int minh = 2;
    int mxel = 15;
    double angl = 15.0;
    double angh = 28.0;
  } desize;
  int shape_2d = 0;  // MSHAPE: 0 quadrilaterals, 1 triangles
  int shape_3d = 0;  // 0 hexahedra, 1 tetrahedra
  int key = 0;       // MSHKEY: 0 free, 1 mapped, 2 mapped if possible
  bool free_warning_given = false;
  struct Extopt {
    bool on = false;            // EXTOPT,ON: pattern attributes, pattern mesh cleared
    int ndiv = 0;               // EXTOPT,ESIZE,NDIV
    double space = 1.0;         // EXTOPT,ESIZE,,SPACE
    bool aclear = false;        // EXTOPT,ACLEAR,1
    std::array<int, 3> attr{};  // EXTOPT,ATTR: MAT, REAL, ESYS (0 current, 1 pattern)
  } extopt;
};

/// Symmetry / antisymmetry conditions of DL and DA (§5.6).
enum class SymmetryKind { Symmetric, Antisymmetric };

/// A DOF load on a solid entity: constant or a time function (`table`).
struct SolidDofLoad {
  double value = 0.0;
  std::string table;
};

/// Loads on solid-model entities, copied to the mesh at every SOLVE (§5.6).
struct SolidLoads {
  std::map<std::pair<int, Dof>, SolidDofLoad> keypoint_constraints;  // DK
  std::map<std::pair<int, Dof>, SolidDofLoad> keypoint_forces;       // FK
  std::map<std::pair<int, Dof>, SolidDofLoad> line_constraints;      // DL
  std::map<std::pair<int, Dof>, SolidDofLoad> area_constraints;      // DA
  std::map<int, SymmetryKind> line_symmetry;                         // DL,,,SYMM|ASYM
  std::map<int, SymmetryKind> area_symmetry;                         // DA,,SYMM|ASYM
  std::map<std::pair<int, int>, SurfaceLoad> area_pressures;         // SFA (area, LKEY)
  // What the last transfer wrote into the mesh loads (removed before the next transfer, so that
  // deleted or changed solid loads do not linger on the mesh).
  std::set<DofKey> transferred_constraints;
  std::set<DofKey> transferred_forces;
  std::set<FaceKey> transferred_pressures;
  bool empty() const {
    return keypoint_constraints.empty() && keypoint_forces.empty() && line_constraints.empty() &&
           area_constraints.empty() && line_symmetry.empty() && area_symmetry.empty() &&
           area_pressures.empty();
  }
};

/// Starting numbers for automatic numbering (NUMSTR, §3.7): 0 for NODE/ELEM means "max + 1".
struct NumberingStart {
  int node = 0;
  int elem = 0;
  int kp = 1;
  int line = 1;
  int area = 1;
  int volu = 1;
};

struct SolidModel {
  std::map<int, Keypoint> keypoints;
  std::map<int, Line> lines;
  std::map<int, Area> areas;
  std::map<int, Volume> volumes;
  MeshControls mesh;
  SolidLoads loads;
  NumberingStart numstr;
  bool empty() const {
    return keypoints.empty() && lines.empty() && areas.empty() && volumes.empty();
  }
};

}  // namespace impactfe
