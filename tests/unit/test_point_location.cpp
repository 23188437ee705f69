// The inverse isoparametric map (geometry/point_location.h) of every cell kind: elements mapped
// from their reference cells by an affine map, then located at points given in natural
// coordinates. Checks independent of the implementation's shape functions: the values are 1 at
// the node a point coincides with and 0 at the others, sum to 1, reproduce the point (linear
// completeness) and, for the quadratic cells, a quadratic field exactly. Points outside the
// cell, and off a shell facet's plane, are refused; a wedge given as a collapsed brick locates.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "elements/cell_topology.h"
#include "elements/quadratic_shapes.h"
#include "geometry/point_location.h"

namespace impactfe::test_point_location {
namespace {

using geometry::shape_values_at;

/// Reference-cell node positions in each cell's node order (cell_topology.h).
std::vector<Vec3> reference_nodes(VtkCell cell) {
  switch (cell) {
    case VtkCell::Triangle:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    case VtkCell::QuadraticTriangle:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}};
    case VtkCell::Quad:
      return {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    case VtkCell::QuadraticQuad:
      return {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
              {0, -1, 0},  {1, 0, 0},  {0, 1, 0}, {-1, 0, 0}};
    case VtkCell::Tetra:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case VtkCell::Hexahedron:
      return {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
              {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    case VtkCell::QuadraticTetra:
      return quadratic_shape_nodes_xi(QuadraticShape::Tet10);
    case VtkCell::QuadraticHexahedron:
      return quadratic_shape_nodes_xi(QuadraticShape::Hex20);
    default:
      return {};
  }
}

/// A skewed, stretched affine map (an area cell stays in the x-y plane).
Vec3 affine(const Vec3& xi, bool area) {
  Eigen::Matrix3d a;
  a << 2.0, 0.3, 0.2, -0.4, 1.5, 0.1, 0.1, 0.2, 0.8;
  Vec3 x = a * xi + Vec3(10.0, -3.0, 2.0);
  if (area) x[2] = 0.0;
  return x;
}

const VtkCell kCells[] = {VtkCell::Triangle,
                          VtkCell::Quad,
                          VtkCell::QuadraticTriangle,
                          VtkCell::QuadraticQuad,
                          VtkCell::Tetra,
                          VtkCell::Hexahedron,
                          VtkCell::QuadraticTetra,
                          VtkCell::QuadraticHexahedron};

std::vector<Vec3> mapped(VtkCell cell) {
  const bool area = cell_topology(cell).dimension == 2;
  std::vector<Vec3> x;
  for (const Vec3& xi : reference_nodes(cell)) x.push_back(affine(xi, area));
  return x;
}

TEST(PointLocation, ANodeHasValueOneThereAndZeroElsewhere) {
  for (VtkCell cell : kCells) {
    const auto x = mapped(cell);
    for (std::size_t k = 0; k < x.size(); ++k) {
      const auto w = shape_values_at(cell, x, x[k]);
      ASSERT_TRUE(w) << "cell " << static_cast<int>(cell) << " node " << k;
      for (std::size_t i = 0; i < x.size(); ++i)
        EXPECT_NEAR((*w)[i], i == k ? 1.0 : 0.0, 1e-10) << static_cast<int>(cell);
    }
  }
}

TEST(PointLocation, InteriorPointsReproduceLinearAndQuadraticFields) {
  for (VtkCell cell : kCells) {
    const auto& t = cell_topology(cell);
    const bool area = t.dimension == 2;
    const bool simplex = cell == VtkCell::Triangle || cell == VtkCell::QuadraticTriangle ||
                         cell == VtkCell::Tetra || cell == VtkCell::QuadraticTetra;
    const Vec3 xi = simplex ? Vec3(0.2, 0.3, area ? 0.0 : 0.1) : Vec3(0.3, -0.6, area ? 0.0 : 0.7);
    const auto x = mapped(cell);
    const Vec3 p = affine(xi, area);
    const auto w = shape_values_at(cell, x, p);
    ASSERT_TRUE(w) << static_cast<int>(cell);
    double sum = 0.0, quadratic = 0.0;
    Vec3 q = Vec3::Zero();
    for (std::size_t i = 0; i < x.size(); ++i) {
      sum += (*w)[i];
      q += (*w)[i] * x[i];
      quadratic += (*w)[i] * x[i][0] * x[i][1];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << static_cast<int>(cell);
    EXPECT_NEAR((q - p).norm(), 0.0, 1e-10) << static_cast<int>(cell);
    if (t.midside_nodes > 0)  // x y is quadratic: exact on an affine quadratic cell
      EXPECT_NEAR(quadratic, p[0] * p[1], 1e-9) << static_cast<int>(cell);
  }
}

TEST(PointLocation, PointsOutsideAreRefused) {
  for (VtkCell cell : kCells) {
    const bool area = cell_topology(cell).dimension == 2;
    const auto x = mapped(cell);
    // Beyond the first corner, away from the centre; and far away.
    const Vec3 outside = affine(Vec3(-1.2, -1.2, area ? 0.0 : -1.2), area);
    EXPECT_FALSE(shape_values_at(cell, x, outside)) << static_cast<int>(cell);
    EXPECT_FALSE(shape_values_at(cell, x, Vec3(1e3, 1e3, 0.0))) << static_cast<int>(cell);
  }
  // Just across the hexahedron's face ξ = 1 (a hundredth of the cell), but inside its box.
  const auto x = mapped(VtkCell::Hexahedron);
  EXPECT_FALSE(shape_values_at(VtkCell::Hexahedron, x, affine(Vec3(1.01, 0.0, 0.0), false)));
  EXPECT_TRUE(shape_values_at(VtkCell::Hexahedron, x, affine(Vec3(1.0, 0.0, 0.0), false)));
}

TEST(PointLocation, WedgeAsCollapsedBrick) {
  // Corners K = L and O = P: a wedge of the unit cube's lower-left triangle prism.
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 1, 1}};
  const auto w = shape_values_at(VtkCell::Hexahedron, x, Vec3(0.2, 0.3, 0.5));
  ASSERT_TRUE(w);
  Vec3 q = Vec3::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) q += (*w)[i] * x[i];
  EXPECT_NEAR((q - Vec3(0.2, 0.3, 0.5)).norm(), 0.0, 1e-10);
  EXPECT_FALSE(shape_values_at(VtkCell::Hexahedron, x, Vec3(0.6, 0.6, 0.5)));  // past x + y = 1
}

TEST(PointLocation, ShellFacetInSpace) {
  // A quadrilateral in the plane x + y + z = 1 (tilted); its centre locates, a point off the
  // plane by a thousandth of its size does not.
  const std::vector<Vec3> x = {{1, 0, 0}, {0, 1, 0}, {-1, 1, 1}, {0, 0, 1}};
  const Vec3 centre = 0.25 * (x[0] + x[1] + x[2] + x[3]);
  const auto w = shape_values_at(VtkCell::Quad, x, centre);
  ASSERT_TRUE(w);
  for (double v : *w) EXPECT_NEAR(v, 0.25, 1e-12);
  const Vec3 normal = Vec3(1, 1, 1).normalized();
  EXPECT_FALSE(shape_values_at(VtkCell::Quad, x, centre + 2e-3 * normal));
}

}  // namespace
}  // namespace impactfe::test_point_location
