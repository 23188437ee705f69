// Element shape measures (geometry/mesh_quality.h): the regular cells measure 1; a stretched
// brick its edge ratio; sheared and collapsed cells the sine of their worst corner over the
// regular cell's; an inverted brick -1; a quadratic cell with straight edges a Jacobian ratio
// of 1 and a folded one infinity; and the report of AMESH / VMESH with its warning.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/log.h"
#include "deck/deck_reader.h"
#include "elements/cell_topology.h"
#include "geometry/mesh_quality.h"

namespace impactfe::test_mesh_quality {
namespace {

using geometry::element_shape;
using geometry::ElementShape;

std::vector<int> numbers(int n) {
  std::vector<int> out;
  for (int i = 1; i <= n; ++i) out.push_back(i);
  return out;
}

/// The corners of the box [0,a]x[0,b]x[0,c] in MAPDL's brick order.
std::vector<Vec3> box(double a, double b, double c) {
  return {{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}, {0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}};
}

ElementShape shape(VtkCell cell, const std::vector<int>& nodes, const std::vector<Vec3>& x) {
  const auto s = element_shape(cell_topology(cell), nodes, x);
  EXPECT_TRUE(s.has_value());
  return s.value_or(ElementShape{});
}

/// A quadratic cell's nodes: the corners, then each edge's midpoint moved by `shift` for edge 0.
std::vector<Vec3> with_midsides(VtkCell cell, std::vector<Vec3> x,
                                const Vec3& shift = Vec3::Zero()) {
  const CellTopology& t = cell_topology(cell);
  for (std::size_t k = 0; k < t.edges.size(); ++k)
    x.push_back(0.5 * (x[t.edges[k][0]] + x[t.edges[k][1]]) + (k == 0 ? shift : Vec3::Zero()));
  return x;
}

TEST(MeshQuality, CubeAndRegularTetrahedronMeasureOne) {
  const ElementShape cube = shape(VtkCell::Hexahedron, numbers(8), box(2, 2, 2));
  EXPECT_NEAR(cube.edge_ratio, 1.0, 1e-14);
  EXPECT_NEAR(cube.scaled_jacobian, 1.0, 1e-14);
  EXPECT_FALSE(cube.jacobian_ratio.has_value());
  const std::vector<Vec3> tet = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  // Right-handed order: swap two corners if this one is left-handed.
  const double volume = (tet[1] - tet[0]).dot((tet[2] - tet[0]).cross(tet[3] - tet[0]));
  const std::vector<Vec3> ordered =
      volume > 0 ? tet : std::vector<Vec3>{tet[0], tet[2], tet[1], tet[3]};
  const ElementShape regular = shape(VtkCell::Tetra, numbers(4), ordered);
  EXPECT_NEAR(regular.edge_ratio, 1.0, 1e-14);
  EXPECT_NEAR(regular.scaled_jacobian, 1.0, 1e-12);
}

TEST(MeshQuality, StretchedBrickHasItsEdgeRatioAndRightCorners) {
  const ElementShape s = shape(VtkCell::Hexahedron, numbers(8), box(10, 1, 2));
  EXPECT_NEAR(s.edge_ratio, 10.0, 1e-12);
  EXPECT_NEAR(s.scaled_jacobian, 1.0, 1e-12);
}

TEST(MeshQuality, InvertedBrickIsMinusOne) {
  std::vector<Vec3> x = box(1, 1, 1);
  for (int i = 4; i < 8; ++i) x[i].z() = -1.0;  // M..P below I..L: every corner left-handed
  EXPECT_NEAR(shape(VtkCell::Hexahedron, numbers(8), x).scaled_jacobian, -1.0, 1e-12);
}

TEST(MeshQuality, ShearedQuadrilateralMeasuresTheSineOfItsSharpestCorner) {
  const double angle = M_PI / 6.0;  // 30 degree rhombus
  const std::vector<Vec3> x = {{0, 0, 0},
                               {1, 0, 0},
                               {1 + std::cos(angle), std::sin(angle), 0},
                               {std::cos(angle), std::sin(angle), 0}};
  const ElementShape s = shape(VtkCell::Quad, numbers(4), x);
  EXPECT_NEAR(s.scaled_jacobian, std::sin(angle), 1e-12);
  // Numbered clockwise, the same quadrilateral is measured about its own normal: the same value.
  const std::vector<Vec3> clockwise = {x[0], x[3], x[2], x[1]};
  EXPECT_NEAR(shape(VtkCell::Quad, numbers(4), clockwise).scaled_jacobian, std::sin(angle), 1e-12);
}

TEST(MeshQuality, CollapsedCornersAreMeasuredAsTheCellTheyMake) {
  // A triangle given as a quadrilateral (K = L): right isosceles, worst corner 45 degrees.
  const std::vector<Vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}};
  const ElementShape t = shape(VtkCell::Quad, {1, 2, 3, 3}, tri);
  EXPECT_NEAR(t.scaled_jacobian, std::sin(M_PI / 4) / (std::sqrt(3.0) / 2), 1e-12);
  EXPECT_NEAR(t.edge_ratio, std::sqrt(2.0), 1e-12);
  // An equilateral wedge (K = L, O = P) of unit edges: 1.
  const double h = std::sqrt(3.0) / 2;
  const std::vector<Vec3> wedge = {{0, 0, 0}, {1, 0, 0}, {0.5, h, 0}, {0.5, h, 0},
                                   {0, 0, 1}, {1, 0, 1}, {0.5, h, 1}, {0.5, h, 1}};
  EXPECT_NEAR(shape(VtkCell::Hexahedron, {1, 2, 3, 3, 4, 5, 6, 6}, wedge).scaled_jacobian, 1.0,
              1e-12);
  // A pyramid (M = N = O = P) with equilateral sides: 1 at its base corners.
  const Vec3 apex(0.5, 0.5, 1.0 / std::sqrt(2.0));
  const std::vector<Vec3> pyramid = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     apex,      apex,      apex,      apex};
  EXPECT_NEAR(shape(VtkCell::Hexahedron, {1, 2, 3, 4, 5, 5, 5, 5}, pyramid).scaled_jacobian, 1.0,
              1e-12);
  // Corners collapsed below a volume: no shape.
  EXPECT_FALSE(
      element_shape(cell_topology(VtkCell::Hexahedron), {1, 1, 1, 1, 2, 2, 2, 2}, box(1, 1, 1))
          .has_value());
}

TEST(MeshQuality, QuadraticCellsWithStraightEdgesHaveJacobianRatioOne) {
  const ElementShape hex = shape(VtkCell::QuadraticHexahedron, numbers(20),
                                 with_midsides(VtkCell::QuadraticHexahedron, box(1, 1, 1)));
  ASSERT_TRUE(hex.jacobian_ratio.has_value());
  EXPECT_NEAR(*hex.jacobian_ratio, 1.0, 1e-12);
  const std::vector<Vec3> tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const ElementShape t10 =
      shape(VtkCell::QuadraticTetra, numbers(10), with_midsides(VtkCell::QuadraticTetra, tet));
  ASSERT_TRUE(t10.jacobian_ratio.has_value());
  EXPECT_NEAR(*t10.jacobian_ratio, 1.0, 1e-12);
  const ElementShape q8 =
      shape(VtkCell::QuadraticQuad, numbers(8),
            with_midsides(VtkCell::QuadraticQuad, {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}));
  ASSERT_TRUE(q8.jacobian_ratio.has_value());
  EXPECT_NEAR(*q8.jacobian_ratio, 1.0, 1e-12);
}

TEST(MeshQuality, MidsideNodePastTheQuarterPointFoldsTheMap) {
  // Edge 0 of the unit cube runs I-J along x; its midside node moved towards I: at a quarter of
  // the edge the map's determinant vanishes at I, beyond it turns negative there.
  const auto ratio = [](double at) {
    const std::vector<Vec3> x =
        with_midsides(VtkCell::QuadraticHexahedron, box(1, 1, 1), Vec3(at - 0.5, 0, 0));
    const auto s = element_shape(cell_topology(VtkCell::QuadraticHexahedron), numbers(20), x);
    return s->jacobian_ratio.value();
  };
  EXPECT_LT(ratio(0.4), 10.0);
  EXPECT_GT(ratio(0.3), ratio(0.4));
  EXPECT_TRUE(std::isinf(ratio(0.2)));
}

TEST(MeshQuality, MeshingReportsTheShapesAndWarnsPastTheLimits) {
  std::vector<std::string> lines;
  Log::set_sink([&](LogLevel, const std::string& m) { lines.push_back(m); });
  Log::clear();
  // One brick 50 long and 1 wide: an edge ratio of 50, past the limit of 20.
  read_deck_text(
      "/PREP7\nET,1,SOLID185\nMP,EX,1,1\nMP,PRXY,1,0.3\nBLOCK,0,50,0,1,0,1\n"
      "ESIZE,,1\nMSHKEY,1\nVMESH,ALL\n",
      "stretched.inp", DeckOptions{});
  bool reported = false;
  for (const std::string& l : lines)
    reported = reported || l.find("VMESH: 1 element(s): edge ratio <= 50") != std::string::npos;
  EXPECT_TRUE(reported);
  ASSERT_EQ(Log::warnings().size(), 1u);
  EXPECT_NE(Log::warnings()[0].find("past the shape limits"), std::string::npos);
  // Cubes: reported, no warning.
  Log::clear();
  read_deck_text(
      "/PREP7\nET,1,SOLID185\nMP,EX,1,1\nMP,PRXY,1,0.3\nBLOCK,0,2,0,2,0,2\n"
      "ESIZE,1\nMSHKEY,1\nVMESH,ALL\n",
      "cubes.inp", DeckOptions{});
  EXPECT_TRUE(Log::warnings().empty());
  // A 30:1 brick and an inverted cube (its M..P below I..L): the inverted one is named as such,
  // the first past the limits is the stretched one.
  const geometry::MeshQuality bad = geometry::mesh_quality(
      read_deck_text("/PREP7\nET,1,SOLID185\nMP,EX,1,1\nMP,PRXY,1,0.3\n"
                     "N,1\nN,2,30\nN,3,30,1\nN,4,0,1\nN,5,0,0,1\nN,6,30,0,1\nN,7,30,1,1\n"
                     "N,8,0,1,1\nN,9,0,0,3\nN,10,1,0,3\nN,11,1,1,3\nN,12,0,1,3\n"
                     "N,13,0,0,2\nN,14,1,0,2\nN,15,1,1,2\nN,16,0,1,2\n"
                     "E,1,2,3,4,5,6,7,8\nE,9,10,11,12,13,14,15,16\n",
                     "bad.inp", DeckOptions{})
          .model,
      {1, 2});
  EXPECT_EQ(bad.inverted, 1);
  EXPECT_EQ(bad.first_inverted, 2);
  EXPECT_EQ(bad.first_past_limits, 1);
  Log::set_sink(nullptr);
  Log::clear();
}

}  // namespace
}  // namespace impactfe::test_mesh_quality
