// Contact-pair generation (issue 16, APDL_MODELING §4.5 ESURF, §8.4 TSHAP): ESURF counts and
// facet orientation on a VMESH block, no duplicate contact nodes, TSHAP shapes and errors, and a
// block dropped on a rigid plane built with ESURF + TSHAP,PILO equal to the same deck written with
// E commands.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/element.h"
#include "elements/element_registry.h"

namespace impactfe::test_contact_generation {
namespace {

Model read(const std::string& text) {
  return read_deck_text(text, "esurf_test.inp", DeckOptions{}).model;
}

int count_type(const Model& m, int type) {
  return static_cast<int>(std::count_if(m.elements.begin(), m.elements.end(),
                                        [&](const auto& e) { return e.second.type == type; }));
}

/// A 2 x 2 x 1 block meshed 4 x 4 x 2 (75 nodes, 9 of them interior), a contact and a target type.
const char* kBlock = R"(/PREP7
ET,1,SOLID185
ET,2,TARGE170
ET,3,CONTA175
MP,EX,1,1.0E5
R,3,,,1.0,0.1
BLOCK,0,2,0,2,0,1
ESIZE,0.5
VMESH,ALL
)";

TEST(Esurf, TargetFacetsOnTheBottomFacePointOutOfTheBlock) {
  const Model m = read(std::string(kBlock) + R"(TYPE,2
REAL,3
NSEL,S,LOC,Z,0
ESLN,S,0
ESURF
ALLSEL
)");
  ASSERT_EQ(count_type(m, 1), 32);
  EXPECT_EQ(count_type(m, 2), 16);  // one facet per bottom face
  double area = 0.0;
  for (const auto& [id, e] : m.elements) {
    if (e.type != 2) continue;
    EXPECT_EQ(e.real, 3);
    ASSERT_EQ(e.nodes.size(), 4u);
    const Vec3 a = m.nodes.at(e.nodes[0]).x, b = m.nodes.at(e.nodes[1]).x,
               c = m.nodes.at(e.nodes[2]).x, d = m.nodes.at(e.nodes[3]).x;
    for (const Vec3& x : {a, b, c, d}) EXPECT_NEAR(x(2), 0.0, 1e-12);
    const Vec3 n = 0.5 * ((c - a).cross(d - b));  // quadrilateral area vector
    EXPECT_NEAR(n(2), -0.25, 1e-12) << "element " << id << ": normal out of the block (-Z)";
    area += n.norm();
  }
  EXPECT_NEAR(area, 4.0, 1e-12);
}

TEST(Esurf, ContactNodesOncePerNodeAndNotTwice) {
  const Model bottom = read(std::string(kBlock) + R"(TYPE,3
REAL,3
NSEL,S,LOC,Z,0
ESLN,S,0
ESURF
ESURF
ALLSEL
)");
  EXPECT_EQ(count_type(bottom, 3), 25);  // 5 x 5 bottom nodes, the repeated ESURF adds none
  std::set<int> nodes;
  for (const auto& [id, e] : bottom.elements)
    if (e.type == 3) {
      ASSERT_EQ(e.nodes.size(), 1u);
      EXPECT_NEAR(bottom.nodes.at(e.nodes[0]).x(2), 0.0, 1e-12);
      nodes.insert(e.nodes[0]);
    }
  EXPECT_EQ(nodes.size(), 25u);

  // Everything selected: the exterior faces only (64), every surface node once (75 - 9).
  const Model all = read(std::string(kBlock) + "TYPE,3\nREAL,3\nESURF\nTYPE,2\nESURF\n");
  EXPECT_EQ(count_type(all, 3), 66);
  EXPECT_EQ(count_type(all, 2), 64);
}

TEST(Conta174, FacesCarryTheStiffnessOfTheNodeContactsOnTheSameNodes) {
  // The block on a rigid plane at its bottom (pilot 1000): ESURF with CONTA174 (type 4) and with
  // CONTA175 (type 3) on the bottom face. Shared nodes split their stiffness by tributary area,
  // so the 16 faces carry in total what the 25 node contacts carry, and an interior node's
  // four faces carry 1/4 each.
  const Model m = read(std::string(kBlock) + R"(ET,4,CONTA174
N,1001,-1,-1,0
N,1002,3,-1,0
N,1003,3,3,0
N,1004,-1,3,0
N,1000,1,1,-1
TYPE,2
REAL,3
TSHAP,PILO
E,1000
TSHAP,QUAD
E,1001,1002,1003,1004
NSEL,S,LOC,Z,0
NSEL,U,NODE,,1000,1004
ESLN,S,0
TYPE,3
ESURF
TYPE,4
ESURF
ALLSEL
)");
  ASSERT_EQ(count_type(m, 3), 25);
  ASSERT_EQ(count_type(m, 4), 16);
  const ElementBuildContext ctx{m, {}};
  double k174 = 0.0, k175 = 0.0;
  for (const auto& [id, e] : m.elements) {
    if (e.type != 3 && e.type != 4) continue;
    const auto element = create_element(ctx, e);
    EXPECT_EQ(element->n_dofs(), e.type == 3 ? 6 : 15);
    const ElementTypeDescriptor& d = element_type_descriptor(m.element_types.at(e.type));
    EXPECT_EQ(element->result_names(), d.result_names);
    EXPECT_EQ(element->family(), d.family);
    EXPECT_EQ(element->has_status(), d.has_status);
    (e.type == 3 ? k175 : k174) += element->contact_stiffness();
  }
  EXPECT_GT(k175, 0.0);
  EXPECT_NEAR(k174, k175, 1e-12 * k175);
}

TEST(Esurf, RejectsOtherTypesOptionsAndEmptySelections) {
  const auto fails = [](const std::string& tail, const std::string& message) {
    try {
      read(std::string(kBlock) + tail);
      ADD_FAILURE() << "accepted: " << tail;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  fails("TYPE,1\nESURF\n", "TARGE170 target facets, CONTA174 contact faces, TARGE169 target");
  fails("TYPE,2\nESURF,5\n", "XNODE");
  fails("TYPE,2\nESURF,,SIDE\n", "Tlab");
  fails("TYPE,2\nNSEL,S,LOC,Z,0.5\nESLN,S,0\nESURF\n", "no exterior face");
}

TEST(Tshap, ShapesCheckTheNodeCountAndUnsupportedShapesAreErrors) {
  const std::string head = R"(/PREP7
ET,2,TARGE170
R,3
N,1,0,0,0
N,2,1,0,0
N,3,1,1,0
N,4,0,1,0
N,5,0,0,-1
TYPE,2
REAL,3
)";
  const Model ok = read(head + "TSHAP,PILO\nE,5\nTSHAP,QUAD\nE,1,2,3,4\nTSHAP,TRIA\nE,1,2,3\n");
  EXPECT_EQ(ok.elements.size(), 3u);
  const auto fails = [&](const std::string& tail, const std::string& message) {
    try {
      read(head + tail);
      ADD_FAILURE() << "accepted: " << tail;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  fails("TSHAP,PILO\nE,1,2,3,4\n", "TSHAP,PILO makes a TARGE170 of 1 node, 4 given");
  fails("TSHAP,QUAD\nE,1,2,3\n", "TSHAP,QUAD makes a TARGE170 of 4 nodes, 3 given");
  fails("TSHAP,SPHE\n", "analytic rigid primitives");
  fails("TSHAP,LINE\nE,1,2\n", "TSHAP,LINE is a 2-D (TARGE169) target shape");
  fails("TSHAP,PARA\n", "curved 2-D (TARGE169) target segments");
  fails("TSHAP,QUA8\n", "higher-order");
  fails("TSHAP,BLOB\n", "unknown target shape");
}

/// A 1 x 1 x 0.2 brick (nodes 1-8) falling from 0.05 above the top face of a fixed ground brick
/// (nodes 11-18, top at z = 0) under gravity; the rigid target moves with pilot node 100 (fixed).
/// `pair` defines the target facet and the contact nodes.
std::string drop_deck(const std::string& pair) {
  return R"(/PREP7
ET,1,SOLID185
ET,2,TARGE170
ET,3,CONTA175
MP,EX,1,1.0E6
MP,PRXY,1,0.3
MP,DENS,1,1000
MP,MU,2,0.2
R,3,,,1.0,0.1
N,1,0,0,0.05
N,2,1,0,0.05
N,3,1,1,0.05
N,4,0,1,0.05
N,5,0,0,0.25
N,6,1,0,0.25
N,7,1,1,0.25
N,8,0,1,0.25
N,11,-1,-1,-0.5
N,12,2,-1,-0.5
N,13,2,2,-0.5
N,14,-1,2,-0.5
N,15,-1,-1,0
N,16,2,-1,0
N,17,2,2,0
N,18,-1,2,0
N,100,0.5,0.5,-1
TYPE,1
MAT,1
E,1,2,3,4,5,6,7,8
E,11,12,13,14,15,16,17,18
TYPE,2
REAL,3
TSHAP,PILO
E,100
)" + pair +
         R"(ALLSEL
FINISH
/SOLU
ANTYPE,TRANS
TRNOPT,FULL
NSEL,S,NODE,,11,18
NSEL,A,NODE,,100
D,ALL,ALL,0
ALLSEL
KBC,1
ACEL,0,0,9.81
TIME,0.15
DELTIM,1.0E-3
OUTRES,ALL,ALL
SOLVE
FINISH
)";
}

TEST(Esurf, DropOnARigidPlaneEqualsTheHandMadeDeck) {
  // ESURF: the target facet on the ground's top face, contact nodes on the block's bottom face.
  const auto generated = testing::run_deck_text("esurf_drop", drop_deck(R"(NSEL,S,LOC,Z,0
ESLN,S,0
ESURF
TYPE,3
MAT,2
NSEL,S,LOC,Z,0.05
ESLN,S,0
ESURF
)"));
  const auto by_hand = testing::run_deck_text("esurf_drop_e", drop_deck(R"(TSHAP,QUAD
E,15,16,17,18
TYPE,3
MAT,2
E,1
E,2
E,3
E,4
)"));
  // CONTA174 on the block's bottom face with nodal detection (KEYOPT(4) = 1; the default 0 is
  // segment-to-segment, test_contact_segment.cpp): one face, so each corner carries all of its
  // node's stiffness: the same law as the four CONTA175.
  const auto faces = testing::run_deck_text("esurf_drop_174", drop_deck(R"(NSEL,S,LOC,Z,0
ESLN,S,0
ESURF
ET,4,CONTA174,,,,1
TYPE,4
MAT,2
NSEL,S,LOC,Z,0.05
ESLN,S,0
ESURF
)"));
  for (int node : {1, 3, 5, 7}) {
    const auto a = generated.reader->nodal_series(node, "UZ");
    const auto b = by_hand.reader->nodal_series(node, "UZ");
    const auto f = faces.reader->nodal_series(node, "UZ");
    ASSERT_EQ(a.size(), f.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_NEAR(a[k].second, f[k].second, 1e-9) << "CONTA174, node " << node;
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 100u);
    double lowest = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_NEAR(a[k].second, b[k].second, 1e-12) << "node " << node << " t " << a[k].first;
      lowest = std::min(lowest, a[k].second);
    }
    // Free fall before the contact at t = sqrt(2 0.05 / 9.81) = 0.101 s (Newmark's average
    // acceleration is exact for constant acceleration), then the block lands on the plane.
    EXPECT_NEAR(testing::value_stored_at(a, 0.05), -0.5 * 9.81 * 0.05 * 0.05, 1e-9);
    // The block lands (measured: bottom nodes down to -0.0582, i.e. a penetration of 0.0082
    // within the augmented-Lagrange tolerance FTOLN depth = 0.1 0.2^(1/3) = 0.058).
    EXPECT_LT(lowest, -0.05);
    if (node <= 4) EXPECT_GT(lowest, -0.05 - 0.1 * std::cbrt(0.2));
  }
}

}  // namespace
}  // namespace impactfe::test_contact_generation
