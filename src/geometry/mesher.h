#pragma once
/// Meshing of solid-model entities (APDL_MODELING §4): KMESH (point elements), LMESH (line
/// elements), AMESH (mapped quadrilaterals on 4-sided areas, triangles on 3- and 4-sided areas
/// with MSHAPE,1), VMESH / VSWEEP (mapped hexahedra on 6-faced volumes) and xCLEAR.
///
/// Lower-dimensional boundaries are meshed first and shared: a line or area that already has
/// nodes is reused, so adjacent regions are conforming. New nodes and elements are numbered
/// from max(NUMSTR, max + 1) upward; within one command the keypoint nodes come first, then
/// the line nodes by line number, the area nodes by area number, the interior last (§4.6). Each
/// entity records the nodes and elements it created (ownership maps, §4.7).
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/model.h"

namespace impactfe {
struct ElementTypeDescriptor;
}

namespace impactfe::geometry {

/// A free (Gmsh) area mesh: `nodes` holds all its nodes, boundary first, and the grid has no
/// lattice (n1 = n2 = 0); its faces are those of the elements on it.
inline bool free_grid(const AreaGrid& g) {
  return !g.nodes.empty() && g.n1 == 0;
}

/// Largest node or element number meshing may give (the deck's kMaxEntityNumber).
inline constexpr long long kMaxMeshNumber = 2'000'000'000;

/// The current element attribute pointers (TYPE, MAT, REAL, SECNUM, ESYS) used for entities
/// without their own xATT attributes.
struct MeshPointers {
  int type = 1;
  int mat = 1;
  int real = 1;
  int secnum = 0;
  int esys = 0;
  /// Most nodes and elements the model may hold (DeckOptions::max_nodes / max_elements): a
  /// mesh that would exceed them is refused before it is built (issue 12, resource bounds).
  std::size_t max_nodes = 10'000'000;
  std::size_t max_elements = 10'000'000;
};

class Mesher {
 public:
  Mesher(Model& model, const MeshPointers& current, const SourceLocation& where);

  void mesh_keypoint(int id);
  void mesh_line(int id);
  void mesh_area(int id);
  /// VMESH (source = target = 0) or VSWEEP (source/target areas of the sweep; 0 = automatic).
  /// Tetrahedral element types and MSHAPE,1,3D go to the free mesher (mesh_volume_free).
  void mesh_volume(int id, int source = 0, int target = 0);
  /// Whether AMESH of the area goes to the free mesher: it is not mappable (not 3- or 4-sided,
  /// or 3-sided with quadrilaterals asked) and MSHKEY is not 1 (mapped only).
  bool area_needs_free_mesh(int id) const;

  // ---- free meshing through Gmsh (free_mesher.cpp) -------------------------------------------
  /// AMESH of a non-mappable area: triangles (MSHAPE,1) or quadrilaterals by recombination
  /// (MSHAPE,0, with triangles where recombination leaves them), boundary lines meshed first.
  void mesh_area_free(int id);
  /// VMESH with tetrahedra: the unmeshed areas of the volume are meshed with triangles, then
  /// the volume bounded by its area meshes is filled with tetrahedra.
  void mesh_volume_free(int id);

  /// xCLEAR: deletes the elements of the entity and the nodes it owns that no element uses and
  /// no other meshed entity needs; boundary entities meshed only for it are cleared too.
  void clear_keypoint(int id);
  void clear_line(int id);
  void clear_area(int id);
  void clear_volume(int id);

  /// Elements created by this mesher, in creation order.
  const std::vector<int>& created_elements() const { return created_elements_; }
  /// Divisions a line would get now (meshed lines: their division count), for LSEL,NDIV.
  int line_divisions(int id) const;

  // ---- used by the volume mesher (volume_mesher.cpp) ----------------------------------------
  struct Attributes {
    int type = 1;
    int mat = 1;
    int real = 1;
    int secnum = 0;
    int esys = 0;
  };
  /// The entity's attributes, falling back on the current pointers; checks the element type.
  Attributes resolve(const EntityAttributes& own) const;
  const ElementTypeDescriptor& descriptor(int type) const;
  /// Plans equal divisions for each class of lines (opposite sides of a mapped region):
  /// fixed counts (meshed lines, LESIZE/L NDIV) must agree; otherwise the largest soft count
  /// (sizes, ESIZE, DESIZE) is used for all. `what` names the region in errors.
  void plan_divisions(const std::vector<std::vector<int>>& classes, const std::string& what,
                      std::optional<double> area_size);
  /// Creates the nodes of a line (and of its keypoints) when it has none.
  /// With `midsides` (a quadratic line element meshing a line that has no nodes yet), the
  /// midside nodes are created in turn with the corner nodes, numbered in order along the line as
  /// MAPDL numbers them (vm70 reads node 10 as the midspan of 8 BEAM189 elements); `midsides`
  /// receives them by corner pair.
  void line_nodes(int id, std::optional<double> area_size = std::nullopt,
                  std::map<std::pair<int, int>, int>* midsides = nullptr);
  /// Creates the nodes of an area (lines first) when it has none; `triangles` asks for the
  /// triangular lattice on a 3-sided area.
  void area_nodes(int id, bool triangles);
  int add_node(const Vec3& x);
  /// An element of the attributes' type on `nodes`: the corners of its cell (missing corners
  /// repeat the last); a cell with midside nodes gets one at the middle of each edge, shared
  /// with the elements that have the same edge (midside_node).
  int add_element(const Attributes& attr, std::vector<int> nodes);
  /// The midside node of the edge between nodes a and b: the one an existing element has there,
  /// else a new node at mid-edge (kept in created_midside_nodes).
  int midside_node(int a, int b);
  /// Makes the midside nodes of the edges between consecutive nodes of a meshed line lie on
  /// the line (an arc's at its middle angle), not on the chord.
  void index_line_edges(int line);
  /// Midside nodes created by this mesher, in creation order (the meshed entity owns them).
  std::vector<int> take_created_midside_nodes() {
    return std::exchange(created_midside_nodes_, {});
  }
  /// Signed line joining keypoints a and b inside `lines` (0 when none).
  int line_joining(const std::vector<int>& lines, int a, int b) const;
  [[noreturn]] void fail(const std::string& message) const;
  /// Fails when `n` more nodes would exceed MeshPointers::max_nodes (`what`: for the message).
  void check_new_nodes(double n, const std::string& what) const;

 private:
  int keypoint_node(int id);
  int soft_divisions(const Line& line, std::optional<double> area_size) const;
  int fixed_divisions(const Line& line) const;
  void delete_elements(std::vector<int>& elements);
  void delete_nodes(std::vector<int> nodes);
  bool area_needed(int area) const;
  bool line_needed(int line) const;
  bool keypoint_needed(int kp) const;
  void release_line(int id);
  void release_area(int id);
  void release_keypoint(int id);
  // Mapped hexahedral meshing of a brick-like volume (volume_mesher.cpp), in this order.
  struct VolumeBlock;
  /// Its areas, lines and corners from the source area (checks that it is brick-like).
  VolumeBlock volume_block(int id, int source, int target);
  /// Divisions, the nodes of its keypoints, lines and areas, and the empty node lattice.
  void volume_block_nodes(VolumeBlock& block);
  /// The area meshes into the lattice.
  void copy_face_grids(VolumeBlock& block);
  /// The bricks of the filled lattice, I J K L counter-clockwise seen from M N O P.
  std::vector<int> volume_block_elements(const VolumeBlock& block, const Attributes& attr);

  /// Free triangle/quadrilateral mesh of the unmeshed ones among `areas` through a Gmsh model
  /// of them: sets their grids (free_grid) and returns their faces (corner nodes oriented by
  /// the area's loop; a triangle's fourth entry is 0).
  std::map<int, std::vector<std::array<int, 4>>> free_area_nodes(const std::vector<int>& areas,
                                                                 bool quads);
  /// About how many nodes a free mesh of area `id` makes, from its size and its boundary
  /// divisions (checked against the limits before Gmsh meshes).
  double estimated_free_nodes(int id) const;
  /// free_area_nodes' Gmsh model: the plane or filling surface of area `a` on its loops (the
  /// curves exist); `loop_tag` numbers the curve loops.
  void add_free_surface(int a, double longest, int& loop_tag) const;
  /// free_area_nodes' mesh back from Gmsh: the curve nodes onto the keypoints' and lines'
  /// nodes, new nodes inside the areas, and the areas' faces.
  void read_free_area_mesh(const std::vector<int>& todo, const std::set<int>& lines,
                           const std::set<int>& kps,
                           std::map<int, std::vector<std::array<int, 4>>>& faces_of,
                           std::map<int, std::vector<int>>& interior_of);
  /// The triangles of the areas of volume `id` (free meshed now, or meshed before).
  std::vector<std::array<int, 3>> volume_boundary_triangles(int id);
  /// Gmsh's tetrahedra inside the closed triangulation `triangles` of volume `id`: its new
  /// (interior) nodes and the tetrahedra, positive volume.
  void fill_with_tetrahedra(int id, const std::vector<std::array<int, 3>>& triangles,
                            std::vector<int>& interior, std::vector<std::array<int, 4>>& tets);
  /// Unit normal of an area by its loop direction (the normal of its area elements).
  Vec3 area_normal(int id) const;
  /// Faces of an area meshed before: its area elements, else the faces of the volumes' elements
  /// that lie on it.
  std::vector<std::array<int, 4>> existing_area_faces(int area) const;

  Model& model_;
  SolidModel& solid_;
  MeshPointers current_;
  SourceLocation where_;
  std::map<int, int> planned_;  // line -> divisions decided for this command
  double longest_line_ = 0.0;
  std::vector<int> created_elements_;
  std::optional<std::map<std::pair<int, int>, int>> midside_index_;  // corner pair -> midside
  std::vector<int> created_midside_nodes_;
  std::map<std::pair<int, int>, int> line_edges_;  // consecutive nodes of a line -> the line
};

}  // namespace impactfe::geometry
