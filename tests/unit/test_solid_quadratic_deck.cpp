// The quadratic solids through the deck reader and the mesher: E + EMORE, omitted midside nodes
// refused, SOLID186's tetrahedron form, its wedge refused, VMESH with midside nodes shared
// between elements and between volumes meshed apart, NSLE CORNER / MID.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <string>

#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/element.h"
#include "elements/solid_quadratic.h"

namespace impactfe::test_solid_quadratic_deck {
namespace {

const char* kHead = "/PREP7\nMP,EX,1,200E3\nMP,PRXY,1,0.3\nMP,DENS,1,7.85E-9\n";

Model read(const std::string& text) {
  return read_deck_text(text, "quadratic.inp", DeckOptions{}).model;
}

std::unique_ptr<Element> build(const Model& m, int element) {
  ElementBuildContext ctx{m, [](const ElementRecord&) { return std::string(); }};
  return create_element(ctx, m.elements.at(element));
}

/// The unit cube's corners 1..8 and its edge midpoints 9..20 (VTK / MAPDL order).
std::string cube_nodes() {
  const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                            {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::string out;
  for (int a = 0; a < 8; ++a)
    out += fmt::format("N,{},{},{},{}\n", a + 1, c[a][0], c[a][1], c[a][2]);
  for (int k = 0; k < 12; ++k) {
    const auto* p = c[edges[k][0]];
    const auto* q = c[edges[k][1]];
    out += fmt::format("N,{},{},{},{}\n", 9 + k, 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]),
                       0.5 * (p[2] + q[2]));
  }
  return out;
}

TEST(QuadraticSolidDeck, EAndEmoreGiveTheTwentyNodes) {
  const Model m = read(std::string(kHead) + "ET,1,SOLID186\n" + cube_nodes() +
                       "E,1,2,3,4,5,6,7,8\nEMORE,9,10,11,12,13,14,15,16\nEMORE,17,18,19,20\n");
  ASSERT_EQ(m.elements.at(1).nodes.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(m.elements.at(1).nodes[k], k + 1);
  const auto e = build(m, 1);
  EXPECT_EQ(e->n_dofs(), 60);
  EXPECT_NEAR(*e->volume(), 1.0, 1e-12);
}

TEST(QuadraticSolidDeck, OmittedMidsideNodeIsRefused) {
  // EMORE with a blank field: MAPDL's straight edge without a midside node.
  const Model m = read(std::string(kHead) + "ET,1,SOLID186\n" + cube_nodes() +
                       "E,1,2,3,4,5,6,7,8\nEMORE,9,,11,12,13,14,15,16\nEMORE,17,18,19,20\n");
  try {
    build(m, 1);
    FAIL() << "an omitted midside node was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("midside node 10 (of 20) is not given"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read(std::string(kHead) + "ET,1,SOLID186\n" + cube_nodes() +
                    "E,1,2,3,4,5,6,7,8\nEMORE,9,10,11,12,13,14,15,16,17\nEMORE,18,19,20,21\n"),
               InputError);  // EMORE beyond the 20 nodes
}

TEST(QuadraticSolidDeck, Solid186TetrahedronFormAndRefusedWedge) {
  // Tetrahedron I J K M = nodes 1 2 4 5 of the cube: K = L = S, M = N = O = P = U..X, A = B.
  const std::string nodes = cube_nodes();
  const Model tet = read(std::string(kHead) + "ET,1,SOLID186\n" + nodes +
                         "N,21,0.5,0.5,0\nN,22,0,0.5,0.5\nN,23,0.5,0,0.5\n"
                         "E,1,2,4,4,5,5,5,5\nEMORE,9,21,4,12,5,5,5,5\nEMORE,17,23,22,22\n");
  const auto e = build(tet, 1);
  const auto* solid = dynamic_cast<const QuadraticSolid*>(e.get());
  ASSERT_NE(solid, nullptr);
  EXPECT_EQ(solid->shape(), QuadraticShape::Tet10);
  EXPECT_EQ(e->n_dofs(), 30);
  EXPECT_NEAR(*e->volume(), 1.0 / 6.0, 1e-12);
  // The wedge (K = L, O = P) is refused with the element named.
  const Model wedge = read(std::string(kHead) + "ET,1,SOLID186\n" + nodes +
                           "E,1,2,3,3,5,6,7,7\nEMORE,9,10,3,12,13,14,7,16\nEMORE,17,18,19,19\n");
  try {
    build(wedge, 1);
    FAIL() << "the wedge form was accepted";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("wedge"), std::string::npos) << err.what();
  }
}

std::array<long long, 3> key(const Vec3& x) {
  return {std::llround(x(0) * 1e6), std::llround(x(1) * 1e6), std::llround(x(2) * 1e6)};
}

TEST(QuadraticSolidDeck, VmeshMakesSharedMidsideNodes) {
  const Model m =
      read(std::string(kHead) + "ET,1,SOLID186\nBLOCK,0,100,0,20,0,10\nESIZE,5\nVMESH,ALL\n");
  ASSERT_EQ(m.elements.size(), 20u * 4u * 2u);
  // Corners 21 x 5 x 3 and one node per lattice edge: 20·5·3 + 21·4·3 + 21·5·2.
  EXPECT_EQ(m.nodes.size(), 315u + 300u + 252u + 210u);
  std::set<std::array<long long, 3>> positions;
  for (const auto& [id, n] : m.nodes) positions.insert(key(n.x));
  EXPECT_EQ(positions.size(), m.nodes.size());
  for (const auto& [id, e] : m.elements) {
    ASSERT_EQ(e.nodes.size(), 20u);
    // Each midside node at the middle of its edge.
    const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (int k = 0; k < 12; ++k) {
      const Vec3 mid =
          0.5 * (m.nodes.at(e.nodes[edges[k][0]]).x + m.nodes.at(e.nodes[edges[k][1]]).x);
      EXPECT_LT((m.nodes.at(e.nodes[8 + k]).x - mid).norm(), 1e-12);
    }
    EXPECT_NEAR(*build(m, id)->volume(), 125.0, 1e-9);
  }
  // Every node is owned by an entity (a volume clear removes its midside nodes).
  std::size_t owned = 0;
  for (const auto& [id, k] : m.solid.keypoints) owned += k.node != 0 ? 1 : 0;
  for (const auto& [id, l] : m.solid.lines) owned += l.nodes.size() - 2;
  for (const auto& [id, a] : m.solid.areas) owned += a.interior_nodes.size();
  for (const auto& [id, v] : m.solid.volumes) owned += v.interior_nodes.size();
  EXPECT_EQ(owned, m.nodes.size());
}

TEST(QuadraticSolidDeck, VolumesMeshedApartShareTheirMidsideNodes) {
  const Model m = read(std::string(kHead) +
                       "ET,1,SOLID186\nBLOCK,0,1,0,1,0,1\nBLOCK,1,2,0,1,0,1\nNUMMRG,KP\n"
                       "ESIZE,0.5\nVMESH,1\nVMESH,2\n");
  std::set<std::array<long long, 3>> positions;
  for (const auto& [id, n] : m.nodes) positions.insert(key(n.x));
  EXPECT_EQ(positions.size(), m.nodes.size());  // no duplicate node on the shared face
  // Corners 5 x 3 x 3, edges 4·3·3 + 5·2·3 + 5·3·2.
  EXPECT_EQ(m.nodes.size(), 45u + 36u + 30u + 30u);
}

TEST(QuadraticSolidDeck, VmeshWithTetrahedraAndNsleMid) {
  EXPECT_THROW(read(std::string(kHead) + "ET,1,SOLID187\nBLOCK,0,1,0,1,0,1\nMSHKEY,1\nVMESH,ALL\n"),
               InputError);
  const std::string one = std::string(kHead) + "ET,1,SOLID186\n" + cube_nodes() +
                          "E,1,2,3,4,5,6,7,8\nEMORE,9,10,11,12,13,14,15,16\nEMORE,17,18,19,20\n";
  const Model mid = read(one + "NSEL,NONE\nESEL,ALL\nNSLE,S,MID\n");
  const Model corner = read(one + "NSEL,NONE\nESEL,ALL\nNSLE,S,CORNER\n");
  int n_mid = 0, n_corner = 0;
  for (int n = 1; n <= 20; ++n) {
    n_mid += mid.selection.nodes.selected(n) ? 1 : 0;
    n_corner += corner.selection.nodes.selected(n) ? 1 : 0;
    EXPECT_EQ(mid.selection.nodes.selected(n), n > 8) << n;
  }
  EXPECT_EQ(n_mid, 12);
  EXPECT_EQ(n_corner, 8);
}

}  // namespace
}  // namespace impactfe::test_solid_quadratic_deck
