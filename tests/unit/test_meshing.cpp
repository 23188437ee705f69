// Meshing of solid-model entities (APDL_MODELING §3, §4): element and node counts, positive
// Jacobians, conforming shared boundaries, BLOCK + VMESH equal to the same model written node by
// node, spacing ratios, triangles, sweeps, copies, clearing and numbering.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "deck/deck_reader.h"
#include "elements/element.h"
#include "geometry/mapped_mesh.h"

namespace impactfe::test_meshing {
namespace {

Model read(const std::string& text) {
  return read_deck_text(text, "mesh_test.inp", DeckOptions{}).model;
}

/// A position as an integer key (coordinates rounded to 1e-6).
std::array<long long, 3> key(const Vec3& x) {
  return {std::llround(x(0) * 1e6), std::llround(x(1) * 1e6), std::llround(x(2) * 1e6)};
}

/// Elements as sets of corner positions (connectivity up to numbering).
std::set<std::set<std::array<long long, 3>>> element_shapes(const Model& m) {
  std::set<std::set<std::array<long long, 3>>> out;
  for (const auto& [id, e] : m.elements) {
    std::set<std::array<long long, 3>> s;
    for (int n : e.nodes) s.insert(key(m.nodes.at(n).x));
    out.insert(s);
  }
  return out;
}

/// Number of distinct node positions (equal to the node count when no nodes coincide).
std::size_t distinct_positions(const Model& m) {
  std::set<std::array<long long, 3>> s;
  for (const auto& [id, n] : m.nodes) s.insert(key(n.x));
  return s.size();
}

/// Every hexahedron: positive volume and positive corner Jacobians (edge triple products; not
/// for a disk mapped on four arcs, whose corner elements have a 180° angle), and the element
/// builds (2x2x2 Gauss Jacobians checked by the element).
void expect_valid_hexes(const Model& m, bool corners = true) {
  ElementBuildContext build{m, [](const ElementRecord&) { return std::string(); }};
  static const int edges[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                  {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  for (const auto& [id, e] : m.elements) {
    ASSERT_EQ(e.nodes.size(), 8u);
    std::vector<Vec3> x;
    for (int n : e.nodes) x.push_back(m.nodes.at(n).x);
    EXPECT_GT(geometry::hexahedron_volume(x), 0.0) << "element " << id;
    for (int c = 0; c < 8; ++c) {
      const Vec3 a = x[static_cast<std::size_t>(edges[c][0])] - x[static_cast<std::size_t>(c)];
      const Vec3 b = x[static_cast<std::size_t>(edges[c][1])] - x[static_cast<std::size_t>(c)];
      const Vec3 d = x[static_cast<std::size_t>(edges[c][2])] - x[static_cast<std::size_t>(c)];
      // The edge lists are ordered so that a right-handed corner gives a positive product.
      const double j = a.cross(b).dot(d);
      if (corners) EXPECT_GT(j, 0.0) << "element " << id << " corner " << c;
    }
    EXPECT_NO_THROW(create_element(build, e)) << "element " << id;
  }
}

const char* kBrick = "/PREP7\nET,1,SOLID185\nMP,EX,1,2.1E5\nMP,PRXY,1,0.3\n";

TEST(Meshing, BlockVmeshCountsAndValidHexahedra) {
  const Model m = read(std::string(kBrick) +
                       "BLOCK,0,100,0,20,0,10\nESIZE,5\nMSHKEY,1\nMSHAPE,0,3D\nVMESH,ALL\n");
  EXPECT_EQ(m.elements.size(), 20u * 4u * 2u);
  EXPECT_EQ(m.nodes.size(), 21u * 5u * 3u);
  EXPECT_EQ(distinct_positions(m), m.nodes.size());
  // Numbering from 1 upward with no gaps (a fresh model).
  EXPECT_EQ(m.nodes.rbegin()->first, static_cast<int>(m.nodes.size()));
  EXPECT_EQ(m.elements.rbegin()->first, static_cast<int>(m.elements.size()));
  expect_valid_hexes(m);
  // Ownership: every node belongs to exactly one entity of the block.
  std::size_t owned = 0;
  for (const auto& [id, k] : m.solid.keypoints) owned += k.node != 0 ? 1 : 0;
  for (const auto& [id, l] : m.solid.lines) owned += l.nodes.size() - 2;
  for (const auto& [id, a] : m.solid.areas) owned += a.interior_nodes.size();
  for (const auto& [id, v] : m.solid.volumes) owned += v.interior_nodes.size();
  EXPECT_EQ(owned, m.nodes.size());
  EXPECT_EQ(m.solid.volumes.at(1).elements.size(), m.elements.size());
}

TEST(Meshing, BlockVmeshEqualsTheNodeByNodeModel) {
  const Model meshed = read(std::string(kBrick) + "BLOCK,0,100,0,20,0,10\nESIZE,5\nVMESH,1\n");
  // The same 20 x 4 x 2 bricks with N, FILL, NGEN, E, EGEN.
  const Model by_node = read(std::string(kBrick) +
                             "N,1,0,0,0\nN,21,100,0,0\nFILL\nNGEN,5,21,1,21,1,0,5\n"
                             "NGEN,3,105,1,105,1,0,0,5\nE,1,2,23,22,106,107,128,127\n"
                             "EGEN,20,1,1\nEGEN,4,21,1,20\nEGEN,2,105,1,80\n");
  ASSERT_EQ(by_node.elements.size(), meshed.elements.size());
  ASSERT_EQ(by_node.nodes.size(), meshed.nodes.size());
  std::set<std::array<long long, 3>> a, b;
  for (const auto& [id, n] : meshed.nodes) a.insert(key(n.x));
  for (const auto& [id, n] : by_node.nodes) b.insert(key(n.x));
  EXPECT_EQ(a, b);
  EXPECT_EQ(element_shapes(meshed), element_shapes(by_node));
}

TEST(Meshing, AdjacentBlocksShareTheirFaceAfterMerging) {
  const std::string two = std::string(kBrick) + "BLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\n";
  // Without merging the blocks are separate: the touching face is meshed twice.
  const Model apart = read(two + "ESIZE,0.25\nVMESH,ALL\n");
  EXPECT_EQ(apart.nodes.size(), 2u * 125u);
  EXPECT_EQ(distinct_positions(apart), 225u);
  for (const char* join : {"NUMMRG,KP\n", "VGLUE,1,2\n"}) {
    const Model m = read(two + join + "ESIZE,0.25\nVMESH,ALL\n");
    EXPECT_EQ(m.solid.keypoints.size(), 12u) << join;
    EXPECT_EQ(m.solid.areas.size(), 11u) << join;
    EXPECT_EQ(m.elements.size(), 128u) << join;
    EXPECT_EQ(m.nodes.size(), 9u * 5u * 5u) << join;
    EXPECT_EQ(distinct_positions(m), m.nodes.size()) << join;
    expect_valid_hexes(m);
  }
}

// V numbers a volume's new areas as the brick's faces 1-6 (bottom, the sides I-J ... L-I, the
// top last), skipping a face it shares with a volume before it; BLOCK numbers bottom, top, then
// the sides.
TEST(Meshing, AreaNumbersOfVAndBlock) {
  const Model m = read(std::string(kBrick) +
                       "K,1\nK,2,1\nK,3,1,1\nK,4,0,1\nK,5,0,0,1\nK,6,1,0,1\nK,7,1,1,1\n"
                       "K,8,0,1,1\nK,9,2\nK,10,2,1\nK,11,2,0,1\nK,12,2,1,1\n"
                       "V,1,2,3,4,5,6,7,8\nV,2,9,10,3,6,11,12,7\n");
  ASSERT_EQ(m.solid.areas.size(), 11u);  // the face x = 1 is shared
  auto keypoints = [&](int area) {
    const std::vector<int>& k = m.solid.areas.at(area).keypoints;
    return std::set<int>(k.begin(), k.end());
  };
  EXPECT_EQ(keypoints(1), (std::set<int>{1, 2, 3, 4}));
  EXPECT_EQ(keypoints(2), (std::set<int>{1, 2, 6, 5}));
  EXPECT_EQ(keypoints(3), (std::set<int>{2, 3, 7, 6}));
  EXPECT_EQ(keypoints(4), (std::set<int>{3, 4, 8, 7}));
  EXPECT_EQ(keypoints(5), (std::set<int>{4, 1, 5, 8}));
  EXPECT_EQ(keypoints(6), (std::set<int>{5, 6, 7, 8}));
  EXPECT_EQ(keypoints(7), (std::set<int>{2, 9, 10, 3}));
  EXPECT_EQ(keypoints(10), (std::set<int>{10, 3, 7, 12}));  // the shared face (2 3 7 6) skipped
  EXPECT_EQ(keypoints(11), (std::set<int>{6, 11, 12, 7}));
  const Model block = read(std::string(kBrick) + "BLOCK,0,1,0,1,0,1\n");
  auto z_of_area = [&](int area) {
    std::set<double> z;
    for (int k : block.solid.areas.at(area).keypoints) z.insert(block.solid.keypoints.at(k).x(2));
    return z;
  };
  EXPECT_EQ(z_of_area(1), (std::set<double>{0.0}));
  EXPECT_EQ(z_of_area(2), (std::set<double>{1.0}));
}

// ARSYM reflects areas (with their lines and keypoints) about the plane normal to an axis of
// the active Cartesian system; an arc stays an arc; NUMMRG,KPOI merges the keypoints on the
// plane, and the two halves mesh conformingly. A meshed pattern's reflection is meshed.
TEST(Meshing, ArsymReflectsAreasAndArcs) {
  const std::string half = std::string(kBrick) +
                           "ET,1,SHELL63\nR,1,0.1\nK,1\nK,2,2\nK,3,0,2\nL,1,2\n"
                           "LARC,2,3,1,2\nL,3,1\nAL,1,2,3\nLOCAL,11,0,0,1\nARSYM,Y,1\nCSYS,0\n";
  const Model m = read(half + "NUMMRG,KPOI\n");
  ASSERT_EQ(m.solid.areas.size(), 2u);
  EXPECT_EQ(m.solid.keypoints.size(), 4u);  // K1 and K3 met their images and were merged
  std::set<std::array<long long, 3>> reflected;
  for (const auto& [id, k] : m.solid.keypoints) reflected.insert(key(k.x));
  EXPECT_TRUE(reflected.count(key(Vec3(0, 2, 0))));  // K1 (0, 0) about y = 1
  EXPECT_TRUE(reflected.count(key(Vec3(2, 2, 0))));  // K2 (2, 0)
  EXPECT_TRUE(reflected.count(key(Vec3(0, 0, 0))));  // K3 (0, 2) onto K1: merged
  // The reflected arc: a quarter circle about (0, 2) through (2, 2) and (0, 0); its mid-point.
  const Model meshed = read(half + "NUMMRG,KPOI\nESIZE,,8\nAMESH,ALL\n");
  bool on_arc = false;
  const Vec3 mid(std::sqrt(2.0), 2.0 - std::sqrt(2.0), 0.0);
  for (const auto& [id, n] : meshed.nodes) on_arc = on_arc || (n.x - mid).norm() < 1e-9;
  EXPECT_TRUE(on_arc);
  // Ncomp 2 (the legacy number of Y, Verification Manual decks) reflects the same way.
  std::string legacy = half;
  legacy.replace(legacy.find("ARSYM,Y,1"), 9, "ARSYM,2,1");
  std::set<std::array<long long, 3>> same;
  for (const auto& [id, k] : read(legacy + "NUMMRG,KPOI\n").solid.keypoints) same.insert(key(k.x));
  EXPECT_EQ(same, reflected);
  // A meshed pattern: the reflected area is meshed with the pattern's element attributes, its
  // nodes the mirror images of the pattern's; moving a meshed pattern (IMOVE = 1) is refused.
  const std::string meshed_triangle = std::string(kBrick) +
                                      "ET,1,PLANE182\nET,2,PLANE182\nK,1\nK,2,1\nK,3,1,1\n"
                                      "A,1,2,3\nTYPE,2\nESIZE,0.5\nAMESH,1\nTYPE,1\n";
  const Model one = read(meshed_triangle);
  const Model two = read(meshed_triangle + "ARSYM,X,1\n");
  EXPECT_EQ(two.elements.size(), 2 * one.elements.size());
  std::set<std::array<long long, 3>> mirrored, all;
  for (const auto& [id, n] : one.nodes) mirrored.insert(key(Vec3(-n.x.x(), n.x.y(), n.x.z())));
  for (const auto& [id, n] : two.nodes) all.insert(key(n.x));
  for (const auto& p : mirrored) EXPECT_TRUE(all.count(p));
  for (const auto& [id, e] : two.elements) EXPECT_EQ(e.type, 2);  // the pattern's TYPE
  try {
    read(meshed_triangle + "ARSYM,X,1,,,,,1\n");
    FAIL() << "a meshed pattern was moved to its reflection";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ARSYM: moving a meshed pattern"), std::string::npos)
        << e.what();
  }
}

TEST(Meshing, SectypeWithoutAnIdTakesTheNextOne) {
  // SECID blank or 0: one above the highest section id defined (SECTYPE notes).
  const Model m = read(
      "/PREP7\nSECTYPE,3,SHELL\nSECDATA,0.1\nSECTYPE,,SHELL\nSECDATA,0.2\n"
      "SECTYPE,0,SHELL\nSECDATA,0.3\n");
  ASSERT_EQ(m.sections.size(), 3u);
  EXPECT_TRUE(m.sections.count(3) && m.sections.count(4) && m.sections.count(5));
  EXPECT_THROW(read("/PREP7\nSECTYPE,-1,SHELL\n"), InputError);
}

TEST(Meshing, AdjacentAreasAreConforming) {
  const Model m = read(
      "/PREP7\nET,1,SHELL181\nMP,EX,1,1E7\nSECTYPE,1,SHELL\nSECDATA,0.1\n"
      "K,1,0,0\nK,2,1,0\nK,3,3,0\nK,4,0,1\nK,5,1,1\nK,6,3,1\n"
      "A,1,2,5,4\nA,2,3,6,5\nLESIZE,ALL,,,4\nAMESH,ALL\n");
  EXPECT_EQ(m.solid.lines.size(), 7u);  // the middle line is shared
  EXPECT_EQ(m.elements.size(), 32u);
  EXPECT_EQ(m.nodes.size(), 9u * 5u);
  EXPECT_EQ(distinct_positions(m), m.nodes.size());
  // Element normals follow the area (counter-clockwise keypoints: +Z).
  for (const auto& [id, e] : m.elements) {
    const Vec3 a = m.nodes.at(e.nodes[0]).x, b = m.nodes.at(e.nodes[1]).x,
               c = m.nodes.at(e.nodes[2]).x;
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);
  }
}

TEST(Meshing, CylindricalAreaNodesLieOnTheCylinder) {
  // Lines "straight in CSYS 1" between keypoints of equal radius are arcs.
  const Model m = read(
      "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,1E7\nLOCAL,11,1,5,5,0\n"
      "K,1,10,0,0\nK,2,10,90,0\nK,3,10,90,20\nK,4,10,0,20\nA,1,2,3,4\nESIZE,2\nAMESH,1\n");
  for (const auto& [id, n] : m.nodes)
    EXPECT_NEAR(std::hypot(n.x.x() - 5, n.x.y() - 5), 10.0, 1e-9) << "node " << id;
  // Quarter circumference 15.7 / 2 → 8 divisions; length 20 / 2 → 10.
  EXPECT_EQ(m.elements.size(), 8u * 10u);
}

TEST(Meshing, LineSpacingRatio) {
  // LESIZE SPACE = 8 over 4 divisions: h_i = h_1 2^(i-1), h_1 = 10 / 15.
  const Model m = read(
      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,1\nK,1\nK,2,10\nL,1,2\n"
      "LESIZE,1,,,4,8\nLMESH,1\n");
  ASSERT_EQ(m.elements.size(), 4u);
  std::vector<double> x;
  for (int n : m.solid.lines.at(1).nodes) x.push_back(m.nodes.at(n).x.x());
  const std::vector<double> expected = {0, 10.0 / 15, 30.0 / 15, 70.0 / 15, 10};
  ASSERT_EQ(x.size(), expected.size());
  for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x[k], expected[k], 1e-12);
}

TEST(Meshing, QuadraticLineNodesNumberedAlongTheLine) {
  // LMESH of BEAM189 numbers the keypoint nodes first, then every interior node, corner and
  // midside, in order along the line, as MAPDL does: vm70 reads node 10 of 8 elements on a
  // 240-long line as the midspan (x = 120).
  const Model m = read(
      "/PREP7\nET,1,BEAM189\nSECTYPE,1,BEAM,RECT\nSECDATA,1,1\nMP,EX,1,1\nK,1\nK,2,240\n"
      "L,1,2\nESIZE,,8\nLMESH,1\n");
  ASSERT_EQ(m.nodes.size(), 17u);
  EXPECT_NEAR(m.nodes.at(2).x.x(), 240.0, 1e-12);
  for (int n = 3; n <= 17; ++n) EXPECT_NEAR(m.nodes.at(n).x.x(), 15.0 * (n - 2), 1e-9) << n;
  // Element 1: I = node 1, J = node 4 (x = 30), midside K = node 3 (x = 15).
  const auto& e = m.elements.begin()->second.nodes;
  EXPECT_EQ(e[0], 1);
  EXPECT_EQ(e[1], 4);
  EXPECT_EQ(e[2], 3);
}

TEST(Meshing, PcircAreasAboutTheWorkingPlaneOrigin) {
  const std::string head = "/PREP7\nET,1,PLANE182\nMP,EX,1,1\n";
  // A quarter sector moved with the working plane (vm272: WPOFF,0,16 then PCIRC,8,,180,270).
  const Model q = read(head + "WPOFF,0,16\nPCIRC,8,,180,270\n");
  ASSERT_EQ(q.solid.areas.size(), 1u);
  std::vector<Vec3> kps;
  for (const auto& [id, k] : q.solid.keypoints) kps.push_back(k.x);
  ASSERT_EQ(kps.size(), 3u);
  EXPECT_TRUE(kps[0].isApprox(Vec3(0, 16, 0), 1e-12));
  EXPECT_TRUE(kps[1].isApprox(Vec3(-8, 16, 0), 1e-12));
  EXPECT_NEAR((kps[2] - Vec3(0, 8, 0)).norm(), 0.0, 1e-12);
  // An annular sector, radii in either order: keypoints at R = 1 and 2.
  const Model a = read(head + "PCIRC,2,1,0,90\n");
  ASSERT_EQ(a.solid.keypoints.size(), 4u);
  for (const auto& [id, k] : a.solid.keypoints) {
    const double r = k.x.norm();
    EXPECT_TRUE(std::abs(r - 1) < 1e-12 || std::abs(r - 2) < 1e-12) << r;
  }
  // Lines 1 and 3 are the arcs, 2 and 4 the radial edges (MAPDL's numbering: vmr029-t9-185
  // gives lines 2 and 4 one division through the thickness).
  ASSERT_EQ(a.solid.lines.size(), 4u);
  for (int id = 1; id <= 4; ++id) {
    const auto& l = a.solid.lines.at(id);
    const Vec3 p = a.solid.keypoints.at(l.kp1).x, q = a.solid.keypoints.at(l.kp2).x;
    const bool radial = std::abs(std::atan2(p.y(), p.x()) - std::atan2(q.y(), q.x())) < 1e-9;
    EXPECT_EQ(radial, id % 2 == 0) << "line " << id;
  }
  // A full solid circle: four 90° arcs bound one area, which meshes.
  const Model full = read(head + "PCIRC,3\nESIZE,,4\nAMESH,ALL\n");
  EXPECT_EQ(full.solid.lines.size(), 4u);
  EXPECT_EQ(full.solid.areas.size(), 1u);
  EXPECT_FALSE(full.elements.empty());
}

TEST(Meshing, TrianglesOnThreeAndFourSidedAreas) {
  const std::string head = "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,1E7\nMSHAPE,1,2D\nESIZE,,4\n";
  const Model tri = read(head + "K,1\nK,2,1\nK,3,0,1\nA,1,2,3\nAMESH,1\n");
  EXPECT_EQ(tri.elements.size(), 16u);  // n² triangles
  EXPECT_EQ(tri.nodes.size(), 15u);     // (n+1)(n+2)/2
  for (const auto& [id, e] : tri.elements) EXPECT_EQ(e.nodes[2], e.nodes[3]);
  // A keypoint repeated next to itself is one corner (vm141: A,1,2,5,5 is a triangle); another
  // repeat is refused.
  const Model repeated = read(head + "K,1\nK,2,1\nK,3,0,1\nA,1,2,3,3\nAMESH,1\n");
  EXPECT_EQ(element_shapes(repeated), element_shapes(tri));
  EXPECT_THROW(read(head + "K,1\nK,2,1\nK,3,0,1\nA,1,2,1,3\n"), InputError);
  const Model quad = read(head + "RECTNG,0,2,0,1\nAMESH,ALL\n");
  EXPECT_EQ(quad.elements.size(), 2u * 4u * 4u);
  // Mapped quadrilaterals (MSHKEY,1) refuse a 3-sided area; free meshing (the default) meshes
  // it (tests/unit/test_free_meshing.cpp).
  EXPECT_THROW(
      read("/PREP7\nET,1,SHELL63\nR,1,0.1\nK,1\nK,2,1\nK,3,0,1\nA,1,2,3\nMSHKEY,1\nAMESH,1\n"),
      InputError);
}

TEST(Meshing, UnmappableDivisionsMeshFreeUnlessMapped) {
  // Opposite sides given 4 and 2 divisions cannot map: free meshing (MSHKEY,0, the default)
  // meshes the area with those divisions on its lines; MSHKEY,1 refuses it.
  const std::string deck =
      "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,1E7\nK,1\nK,2,2\nK,3,2,1\nK,4,0,1\nA,1,2,3,4\n"
      "LESIZE,1,,,4\nLESIZE,3,,,2\n";
  const Model free = read(deck + "AMESH,1\n");
  EXPECT_GT(free.elements.size(), 0u);
  std::size_t on_bottom = 0;
  for (const auto& [id, n] : free.nodes) on_bottom += std::abs(n.x(1)) < 1e-12 ? 1 : 0;
  EXPECT_EQ(on_bottom, 5u);  // line 1 (K1-K2) in 4 divisions
  EXPECT_THROW(read(deck + "MSHKEY,1\nAMESH,1\n"), InputError);
}

TEST(Meshing, FullCylinderVolume) {
  const Model m = read(std::string(kBrick) + "CYLIND,1,,0,2,0,360\nESIZE,0.5\nVMESH,ALL\n");
  // Four 90° arcs of length π/2 → 4 divisions each (4 x 4 grid on each disk), 4 layers.
  EXPECT_EQ(m.solid.volumes.at(1).areas.size(), 6u);
  EXPECT_EQ(m.elements.size(), 4u * 4u * 4u);
  expect_valid_hexes(m, false);
  for (const auto& [id, n] : m.nodes) EXPECT_LE(std::hypot(n.x.x(), n.x.y()), 1.0 + 1e-9);
}

TEST(Meshing, ExtrusionOfAMeshedAreaAndRevolution) {
  const Model ext = read(
      "/PREP7\nET,1,SHELL181\nET,2,SOLID185\nMP,EX,1,1\nSECTYPE,1,SHELL\nSECDATA,0.1\n"
      "RECTNG,0,2,0,1\nESIZE,0.5\nAMESH,1\nTYPE,2\nEXTOPT,ESIZE,3\nEXTOPT,ACLEAR,1\n"
      "VEXT,1,,,0,0,1.5\n");
  EXPECT_EQ(ext.elements.size(), 4u * 2u * 3u);  // the shells were cleared
  for (const auto& [id, e] : ext.elements) EXPECT_EQ(e.type, 2);
  expect_valid_hexes(ext);
  const Model rev =
      read(std::string(kBrick) +
           "K,1,1,0,0\nK,2,2,0,0\nK,3,2,0,1\nK,4,1,0,1\nA,1,2,3,4\n"
           "K,10,0,0,0\nK,11,0,0,1\nVROTAT,1,,,,,,10,11,180\nESIZE,0.25\nVMESH,ALL\n");
  EXPECT_EQ(rev.solid.volumes.size(), 2u);  // two 90° segments
  expect_valid_hexes(rev);
  for (const auto& [id, n] : rev.nodes) {
    const double r = std::hypot(n.x.x(), n.x.y());
    EXPECT_GE(r, 1.0 - 1e-9);
    EXPECT_LE(r, 2.0 + 1e-9);
  }
}

TEST(Meshing, ClearingDeletesTheMeshAndKeepsSharedBoundaries) {
  Model m = read(std::string(kBrick) +
                 "BLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\nNUMMRG,KP\nESIZE,0.5\nVMESH,ALL\n"
                 "VCLEAR,2\n");
  EXPECT_EQ(m.elements.size(), 8u);
  EXPECT_EQ(m.nodes.size(), 27u);  // volume 1's nodes, incl. the shared face
  m = read(std::string(kBrick) + "BLOCK,0,1,0,1,0,1\nESIZE,0.5\nVMESH,ALL\nVCLEAR,ALL\n");
  EXPECT_TRUE(m.elements.empty());
  EXPECT_TRUE(m.nodes.empty());
}

TEST(Meshing, CopiesAndCompressedNumbering) {
  const Model m = read(
      "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,1E7\nRECTNG,0,1,0,1\nESIZE,0.5\nAMESH,1\n"
      "AGEN,3,1,,,2,0,0\n");
  EXPECT_EQ(m.solid.areas.size(), 3u);
  EXPECT_EQ(m.elements.size(), 12u);
  EXPECT_EQ(m.nodes.size(), 27u);
  const Model moved = read(
      "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,1E7\nRECTNG,0,1,0,1\nESIZE,0.5\nAMESH,1\n"
      "AGEN,,1,,,0,0,5,,,1\n");
  for (const auto& [id, n] : moved.nodes) EXPECT_DOUBLE_EQ(n.x.z(), 5.0);
  const Model compressed = read("/PREP7\nK,3,1\nK,7,2\nK,10,3\nNUMCMP,KP\n");
  EXPECT_EQ(compressed.solid.keypoints.size(), 3u);
  EXPECT_DOUBLE_EQ(compressed.solid.keypoints.at(2).x.x(), 2.0);
  // KGEN with KINC numbers the copies.
  const Model kgen = read("/PREP7\nK,1\nK,2,1\nKGEN,3,1,2,1,0,1,0,10\n");
  EXPECT_EQ(kgen.solid.keypoints.size(), 6u);
  EXPECT_DOUBLE_EQ(kgen.solid.keypoints.at(22).x.y(), 2.0);
}

TEST(Meshing, NodesMergeAndElementsFollow) {
  const Model m = read(std::string(kBrick) +
                       "BLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\nESIZE,0.5\nVMESH,ALL\n"
                       "NUMMRG,NODE\nNUMCMP,NODE\n");
  EXPECT_EQ(m.nodes.size(), 45u);
  EXPECT_EQ(distinct_positions(m), 45u);
  EXPECT_EQ(m.nodes.rbegin()->first, 45);
  for (const auto& [id, e] : m.elements)
    for (int n : e.nodes) EXPECT_EQ(m.nodes.count(n), 1u);
  expect_valid_hexes(m);
  // MAPDL reads NUMMRG's label by its first four characters (VM178: NUMMRG,NODES).
  const Model nodes = read(std::string(kBrick) +
                           "BLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\nESIZE,0.5\nVMESH,ALL\n"
                           "NUMMRG,NODES\n");
  EXPECT_EQ(nodes.nodes.size(), 45u);
}

TEST(Meshing, SelectionOfEntitiesAndTheirNodes) {
  const Model m = read(std::string(kBrick) +
                       "BLOCK,0,4,0,2,0,1\nESIZE,1\nVMESH,ALL\n"
                       "ASEL,S,LOC,X,4\nNSLA,S,1\nNSEL,R,LOC,Z,1\n");
  // The x = 4 face: 3 x 2 nodes; on it, the z = 1 edge: 3 nodes.
  int selected = 0;
  for (const auto& [id, n] : m.nodes) {
    if (!m.selection.nodes.selected(id)) continue;
    ++selected;
    EXPECT_NEAR(n.x.x(), 4.0, 1e-12);
    EXPECT_NEAR(n.x.z(), 1.0, 1e-12);
  }
  EXPECT_EQ(selected, 3);
  int areas = 0;
  for (const auto& [id, a] : m.solid.areas) areas += m.selection.areas.selected(id) ? 1 : 0;
  EXPECT_EQ(areas, 1);
  const Model lines =
      read(std::string(kBrick) + "BLOCK,0,4,0,2,0,1\nLSEL,S,LENGTH,,4\nKSLL,S\nLSEL,S,LOC,Z,0.5\n");
  int n_lines = 0, n_kps = 0;
  for (const auto& [id, l] : lines.solid.lines) n_lines += lines.selection.lines.selected(id);
  for (const auto& [id, k] : lines.solid.keypoints) n_kps += lines.selection.keypoints.selected(id);
  EXPECT_EQ(n_lines, 4);  // the vertical edges (centroid z = 0.5)
  EXPECT_EQ(n_kps, 8);    // the keypoints of the four 4-long lines
}

TEST(Meshing, AreaNodesAreNumberedLineByLine) {
  // vm42: A,1,3,4,2 makes line 1 from keypoint 1 to 3; its end nodes come first (1 at keypoint
  // 1, 2 at keypoint 3), then its interior nodes, then line 2's (keypoint 4 first), as MAPDL
  // numbers them (the deck reads its crown point B as node 2). Keypoint order would put node 2
  // at keypoint 2.
  const Model m = read(
      "/PREP7\nET,1,SHELL181\nK,1,0,0\nK,2,0,1\nK,3,2,0\nK,4,2,1\nA,1,3,4,2\n"
      "ESIZE,,4\nAMESH,1\n");
  EXPECT_TRUE(m.nodes.at(1).x.isApprox(Vec3(0, 0, 0)));
  EXPECT_TRUE(m.nodes.at(2).x.isApprox(Vec3(2, 0, 0)));
  EXPECT_TRUE(m.nodes.at(3).x.isApprox(Vec3(0.5, 0, 0)) ||
              m.nodes.at(3).x.isApprox(Vec3(1.5, 0, 0)));
  EXPECT_TRUE(m.nodes.at(6).x.isApprox(Vec3(2, 1, 0)));
  EXPECT_EQ(m.nodes.size(), 25u);
}

TEST(Meshing, MalformedModellingInputIsAnInputError) {
  auto message = [](const std::string& text) {
    try {
      read(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("/PREP7\nET,1,SHELL63\nR,1,0.1\nK,1\nK,2,1\nK,3,2,1\nK,4,1,2\nK,5,0,1\n"
                    "A,1,2,3,4,5\nMSHKEY,1\nAMESH,1\n")
                .find("area 1 has 5 sides"),
            std::string::npos);
  EXPECT_NE(message("/PREP7\nESIZE,-1\n").find("must be positive"), std::string::npos);
  EXPECT_NE(message("/PREP7\nK,1\nK,2,1\nL,1,2\nLESIZE,1,-0.5\n").find("must be positive"),
            std::string::npos);
  EXPECT_NE(message("/PREP7\nK,1\nL,1,7\n").find("keypoint 7 is not defined"), std::string::npos);
  EXPECT_NE(message("/PREP7\nK,1\nK,2,1\nK,3,1,1\nK,4,0,1\nA,1,2,3,4\nK,2,5\n")
                .find("keypoint 2 is used by line"),
            std::string::npos);
  EXPECT_NE(message(std::string(kBrick) + "BLOCK,0,1,0,1,0,1\nMSHKEY,1\nMSHAPE,1,3D\nVMESH,1\n")
                .find("tetrahedra are meshed free"),
            std::string::npos);
  EXPECT_NE(message("/PREP7\nBLOCK,0,1,0,1,0,1\nVSBV,1,2\n").find("boolean"), std::string::npos);
}

}  // namespace
}  // namespace impactfe::test_meshing
