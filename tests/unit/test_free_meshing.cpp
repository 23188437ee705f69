// Free meshing through Gmsh (geometry/free_mesher.cpp): tetrahedra in a block (total volume
// exact, every element with a positive volume and building, the element count growing with
// 1/ESIZE^3), degenerate SOLID185/SOLID186 tetrahedra, volumes meshed apart that share an
// area, free triangles and quadrilaterals on a five-sided area, reproducibility, refusals, and
// CAD files read by IGESIN (an IGES pair of annuli, a STEP quarter cylinder) against their CAD
// areas and volumes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <string>

#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/element.h"
#include "geometry/cad_import.h"
#include "geometry/gmsh_api.h"

namespace impactfe::test_free_meshing {
namespace {

namespace gmsh = geometry::gmsh;

const char* kHead = "/PREP7\nMP,EX,1,200E3\nMP,PRXY,1,0.3\n";

Model read(const std::string& text) {
  return read_deck_text(text, "free_mesh.inp", DeckOptions{}).model;
}

std::string message(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::array<long long, 3> key(const Vec3& x) {
  return {std::llround(x(0) * 1e6), std::llround(x(1) * 1e6), std::llround(x(2) * 1e6)};
}

/// Total volume of the elements (each built: the element checks its Jacobians) and the least
/// corner triple product (J − I) × (K − I) · (L − I) of the tetrahedra.
struct Totals {
  double volume = 0.0;
  double least_corner = 1e300;
};

Totals totals(const Model& m) {
  ElementBuildContext ctx{m, [](const ElementRecord&) { return std::string(); }};
  Totals t;
  for (const auto& [id, e] : m.elements) {
    const auto element = create_element(ctx, e);
    EXPECT_TRUE(element->volume().has_value());
    t.volume += element->volume().value_or(0.0);
    // Corners I J K L: positions 0 1 2 3 (tetrahedra) or 0 1 2 4 (degenerate bricks).
    const std::size_t l = e.nodes.size() == 8 || e.nodes.size() == 20 ? 4 : 3;
    const Vec3 xi = m.nodes.at(e.nodes[0]).x;
    t.least_corner = std::min(t.least_corner, (m.nodes.at(e.nodes[1]).x - xi)
                                                  .cross(m.nodes.at(e.nodes[2]).x - xi)
                                                  .dot(m.nodes.at(e.nodes[l]).x - xi));
  }
  return t;
}

TEST(FreeMeshing, Solid187BlockVolumeExactAndPositive) {
  const Model m = read(std::string(kHead) +
                       "ET,1,SOLID187\nBLOCK,0,3,0,2,0,1\nESIZE,0.5\n"
                       "VMESH,ALL\n");
  ASSERT_GT(m.elements.size(), 50u);
  for (const auto& [id, e] : m.elements) ASSERT_EQ(e.nodes.size(), 10u);
  const Totals t = totals(m);
  EXPECT_NEAR(t.volume, 6.0, 1e-10);
  EXPECT_GT(t.least_corner, 0.0);
  // No two nodes at one place (boundary nodes shared between areas, lines and the volume).
  std::set<std::array<long long, 3>> positions;
  for (const auto& [id, n] : m.nodes) positions.insert(key(n.x));
  EXPECT_EQ(positions.size(), m.nodes.size());
  // Every node belongs to an entity (the ownership maps VCLEAR uses).
  std::size_t owned = 0;
  for (const auto& [id, k] : m.solid.keypoints) owned += k.node != 0 ? 1 : 0;
  for (const auto& [id, l] : m.solid.lines) owned += l.nodes.size() - 2;
  for (const auto& [id, a] : m.solid.areas) owned += a.interior_nodes.size();
  for (const auto& [id, v] : m.solid.volumes) owned += v.interior_nodes.size();
  EXPECT_EQ(owned, m.nodes.size());
  // The lines got ESIZE's divisions: 6, 4 and 2 along X, Y, Z.
  std::multiset<std::size_t> divisions;
  for (const auto& [id, l] : m.solid.lines) divisions.insert(l.nodes.size() - 1);
  EXPECT_EQ(divisions.count(6), 4u);
  EXPECT_EQ(divisions.count(4), 4u);
  EXPECT_EQ(divisions.count(2), 4u);
}

TEST(FreeMeshing, ElementCountScalesWithEsize) {
  auto count = [](double h) {
    return read(std::string(kHead) + "ET,1,SOLID187\nBLOCK,0,2,0,2,0,2\nESIZE," +
                std::to_string(h) + "\nVMESH,ALL\n")
        .elements.size();
  };
  const double coarse = static_cast<double>(count(0.5));
  const double fine = static_cast<double>(count(0.25));
  // Halving the size: about 8 times the elements (Delaunay meshes: between 5 and 11).
  EXPECT_GT(fine / coarse, 5.0);
  EXPECT_LT(fine / coarse, 11.0);
}

TEST(FreeMeshing, ReproducibleMesh) {
  const std::string deck = std::string(kHead) +
                           "ET,1,SOLID187\nBLOCK,0,3,0,2,0,1\nESIZE,0.4\n"
                           "VMESH,ALL\n";
  const Model a = read(deck), b = read(deck);
  ASSERT_EQ(a.elements.size(), b.elements.size());
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (const auto& [id, e] : a.elements) EXPECT_EQ(e.nodes, b.elements.at(id).nodes);
  for (const auto& [id, n] : a.nodes) EXPECT_EQ(n.x, b.nodes.at(id).x);
}

TEST(FreeMeshing, DegenerateBricksWithMshape1) {
  for (const char* type : {"SOLID185", "SOLID186"}) {
    const Model m = read(std::string(kHead) + "ET,1," + type +
                         "\nBLOCK,0,2,0,1,0,1\nESIZE,0.5\nMSHAPE,1,3D\nVMESH,ALL\n");
    ASSERT_GT(m.elements.size(), 10u) << type;
    for (const auto& [id, e] : m.elements) {
      // I J K K L L L L
      EXPECT_EQ(e.nodes[2], e.nodes[3]);
      EXPECT_EQ(e.nodes[4], e.nodes[7]);
    }
    const Totals t = totals(m);
    EXPECT_NEAR(t.volume, 2.0, 1e-10) << type;
    EXPECT_GT(t.least_corner, 0.0) << type;
  }
}

TEST(FreeMeshing, VolumesMeshedApartShareTheirArea) {
  const Model m = read(std::string(kHead) +
                       "ET,1,SOLID187\nBLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\nNUMMRG,KP\n"
                       "ESIZE,0.25\nVMESH,1\nVMESH,2\n");
  std::set<std::array<long long, 3>> positions;
  for (const auto& [id, n] : m.nodes) positions.insert(key(n.x));
  EXPECT_EQ(positions.size(), m.nodes.size());  // the shared area's nodes are the same
  EXPECT_NEAR(totals(m).volume, 2.0, 1e-10);
}

const char* kPentagon =
    "ET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA,0.1\n"
    "K,1,0,0\nK,2,2,0\nK,3,2,1\nK,4,1,2\nK,5,0,1\nA,1,2,3,4,5\nESIZE,0.25\n";

TEST(FreeMeshing, FiveSidedAreaTriangles) {
  const Model m = read(std::string(kHead) + kPentagon + "MSHAPE,1,2D\nAMESH,1\n");
  ASSERT_GT(m.elements.size(), 20u);
  double area = 0.0;
  for (const auto& [id, e] : m.elements) {
    EXPECT_EQ(e.nodes[2], e.nodes[3]);  // triangles: I J K K
    const Vec3 a = m.nodes.at(e.nodes[0]).x, b = m.nodes.at(e.nodes[1]).x,
               c = m.nodes.at(e.nodes[2]).x;
    const double z = (b - a).cross(c - a).z();
    EXPECT_GT(z, 0.0);  // normal along +Z, the loop's
    area += 0.5 * z;
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(FreeMeshing, FiveSidedAreaQuadrilaterals) {
  const Model m = read(std::string(kHead) + kPentagon + "AMESH,1\n");
  std::size_t quads = 0;
  double area = 0.0;
  for (const auto& [id, e] : m.elements) {
    const Vec3 a = m.nodes.at(e.nodes[0]).x, b = m.nodes.at(e.nodes[1]).x,
               c = m.nodes.at(e.nodes[2]).x, d = m.nodes.at(e.nodes[3]).x;
    if (e.nodes[2] != e.nodes[3]) ++quads;
    const double z = 0.5 * ((c - a).cross(d - b)).z();
    EXPECT_GT(z, 0.0);
    area += z;
  }
  EXPECT_GT(quads, m.elements.size() * 3 / 4);  // mostly quadrilaterals
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(FreeMeshing, Refusals) {
  EXPECT_NE(message(std::string(kHead) + "ET,1,SOLID187\nBLOCK,0,1,0,1,0,1\nMSHKEY,1\nVMESH,ALL\n")
                .find("MSHKEY,1"),
            std::string::npos);
  EXPECT_NE(
      message(std::string(kHead) + "ET,1,SOLID186\nBLOCK,0,1,0,1,0,1\nMSHAPE,1,3D\nVSWEEP,1\n")
          .find("VSWEEP makes bricks"),
      std::string::npos);
  // A quadrilateral area mesh next to a tetrahedral volume.
  EXPECT_NE(message(std::string(kHead) +
                    "ET,1,SOLID186\nET,2,SOLID187\nBLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\n"
                    "NUMMRG,KP\nESIZE,0.5\nVMESH,1\nTYPE,2\nVMESH,2\n")
                .find("quadrilateral mesh"),
            std::string::npos);
}

// ---- CAD files (IGESIN) -------------------------------------------------------------------

/// Element areas of a plane mesh (triangles I J K K and quadrilaterals).
double plane_area(const Model& m) {
  double area = 0.0;
  for (const auto& [id, e] : m.elements) {
    const Vec3 a = m.nodes.at(e.nodes[0]).x, b = m.nodes.at(e.nodes[1]).x,
               c = m.nodes.at(e.nodes[2]).x, d = m.nodes.at(e.nodes[3]).x;
    area += 0.5 * std::abs((c - a).cross(d - b).z());
  }
  return area;
}

TEST(FreeMeshing, IgesAreasWithHolesMeshedToTheCadArea) {
  // The Verification Manual's VM228-1.iges: two annuli (r 0.5-1 and 4-5) written by MAPDL in
  // metres, each a planar area with a hole bounded by four 90-degree arcs per circle.
  const std::string iges =
      std::string(IMPACTFE_TEST_DECKS) + "/../../../shared/vm/verif/VM228-1.iges";
  if (!std::ifstream(iges)) GTEST_SKIP() << "no " << iges;
  const Model m = read(std::string(kHead) + "ET,1,PLANE182\n/AUX15\nIGESIN,'" +
                       iges.substr(0, iges.size() - 5) + "',iges\nFINISH\n/PREP7\n" +
                       "ESIZE,0.05\nMSHAPE,1,2D\nAMESH,ALL\n");
  EXPECT_EQ(m.solid.areas.size(), 2u);
  EXPECT_EQ(m.solid.lines.size(), 16u);
  const double cad = geometry::cad_measure(iges, 2);
  EXPECT_NEAR(cad, M_PI * (1.0 - 0.25 + 25.0 - 16.0), 1e-9 * cad);  // unit: the file's own
  // The mesh's straight edges cut the arcs (the outer circles lose area, the holes too), by
  // about (h / r)^2 / 12 of the area near each circle.
  const double meshed = plane_area(m);
  EXPECT_NEAR(meshed / cad, 1.0, 1e-3);
  // Nodes on the circles lie on them (arcs carried over exactly).
  for (const auto& [id, l] : m.solid.lines)
    for (int n : l.nodes) {
      const double r = m.nodes.at(n).x.norm();
      const double nearest =
          std::min({std::abs(r - 0.5), std::abs(r - 1.0), std::abs(r - 4.0), std::abs(r - 5.0)});
      EXPECT_LT(nearest, 1e-9) << "line " << id;
    }
}

TEST(FreeMeshing, StepVolumeMeshedToTheCadVolume) {
  // A quarter cylinder r = 1, h = 2 (planar faces and one cylindrical 4-sided face) written as
  // STEP by Gmsh's OpenCASCADE kernel, read back by IGESIN and meshed with SOLID187.
  const std::string step = ::testing::TempDir() + "quarter_cylinder.step";
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("quarter");
  gmsh::model::occ::addCylinder(0, 0, 0, 0, 0, 2, 1.0, -1, M_PI / 2);
  gmsh::model::occ::synchronize();
  gmsh::write(step);
  gmsh::finalize();
  const double cad = geometry::cad_measure(step, 3);
  EXPECT_NEAR(cad, M_PI / 2, 1e-9);
  const Model m = read(std::string(kHead) + "ET,1,SOLID187\nIGESIN,'" +
                       step.substr(0, step.size() - 5) + "',step\nESIZE,0.1\nVMESH,ALL\n");
  ASSERT_EQ(m.solid.volumes.size(), 1u);
  const Totals t = totals(m);
  EXPECT_GT(t.least_corner, 0.0);
  EXPECT_LT(t.volume, cad);  // faceted: inscribed
  EXPECT_NEAR(t.volume / cad, 1.0, 2e-3);
  // A B-spline curve is refused by name, and nothing is added.
  const std::string spline = ::testing::TempDir() + "spline.step";
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("spline");
  const int p1 = gmsh::model::occ::addPoint(0, 0, 0), p2 = gmsh::model::occ::addPoint(1, 1, 0),
            p3 = gmsh::model::occ::addPoint(2, 0, 0);
  gmsh::model::occ::addBSpline({p1, p2, p3});
  gmsh::model::occ::synchronize();
  gmsh::write(spline);
  gmsh::finalize();
  EXPECT_NE(message("/PREP7\nIGESIN,'" + spline.substr(0, spline.size() - 5) + "',step\n")
                .find("BSpline"),
            std::string::npos);
}

TEST(FreeMeshing, MeshSubcommandWritesTheCdbOfACadFile) {
  // impactfe mesh on the STEP quarter cylinder: a CDB whose NBLOCK / EBLOCK CDREAD reads back
  // into the same number of nodes and SOLID187 elements as the IGESIN deck makes.
  const std::string step = ::testing::TempDir() + "quarter_mesh.step";
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("quarter");
  gmsh::model::occ::addCylinder(0, 0, 0, 0, 0, 2, 1.0, -1, M_PI / 2);
  gmsh::model::occ::synchronize();
  gmsh::write(step);
  gmsh::finalize();
  const std::string cdb = ::testing::TempDir() + "quarter_mesh.cdb";
  std::remove(cdb.c_str());
  const std::string command = std::string(IMPACTFE_BINARY) + " mesh " + step +
                              " --type 187 --esize 0.25 -o " + cdb + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const Model direct = read(std::string(kHead) + "ET,1,SOLID187\nIGESIN,'" +
                            step.substr(0, step.size() - 5) + "',step\nESIZE,0.25\nVMESH,ALL\n");
  const Model back = read("/PREP7\nCDREAD,DB,'" + cdb.substr(0, cdb.size() - 4) + "',cdb\n");
  EXPECT_GT(back.elements.size(), 20u);
  EXPECT_EQ(back.elements.size(), direct.elements.size());
  EXPECT_EQ(back.nodes.size(), direct.nodes.size());
  EXPECT_NEAR(totals(back).volume, totals(direct).volume, 1e-9);
}

}  // namespace
}  // namespace impactfe::test_free_meshing
