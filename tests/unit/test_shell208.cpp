// SHELL208 (src/elements/shell208.cpp), the 2-node axisymmetric shell: symmetry, the rigid axial
// translation and the mass of the element; through the deck reader and the static driver the
// closed cylinder under internal pressure (membrane stresses p R / t and p R / 2t) and the
// clamped circular plate under uniform pressure (Timoshenko & Woinowsky-Krieger §62 with the
// Mindlin shear deflection), for both integrations (KEYOPT(3) = 0 and 2).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <numbers>
#include <string>

#include "../support/model_records.h"
#include "../support/run_deck.h"
#include "elements/element.h"

namespace impactfe::test_shell208 {
namespace {

constexpr double kPi = std::numbers::pi;

/// One element from (r1, y1) to (r2, y2), thickness h, steel-like material.
Model one_element(double r1, double y1, double r2, double y2, double h, int keyopt3) {
  Model m;
  m.nodes[1] = Node{1, Vec3(r1, y1, 0.0), Vec3::Zero()};
  m.nodes[2] = Node{2, Vec3(r2, y2, 0.0), Vec3::Zero()};
  ElementType et = testing::element_type(1, "SHELL208");
  et.keyopt[3] = keyopt3;
  m.element_types[1] = et;
  m.materials[1] = Material{1, {{"EX", 2e11}, {"PRXY", 0.3}, {"DENS", 7800.0}}};
  Section s;
  s.id = 1;
  s.type = "SHELL";
  s.data = {h};
  s.layers = {{h}};
  m.sections[1] = s;
  ElementRecord e = testing::element_record(1, 1, 1, 1, {1, 2}, "shell208.inp");
  e.secnum = 1;
  m.elements[1] = e;
  return m;
}

class Shell208Element : public ::testing::TestWithParam<int> {};

TEST_P(Shell208Element, SymmetricWithTheAxialTranslationItsOnlyZeroEnergyMotion) {
  const Model m = one_element(0.5, 0.0, 0.8, 0.4, 0.02, GetParam());
  const ElementBuildContext ctx{m, {}};
  const auto element = create_element(ctx, m.elements.at(1));
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  element->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  Eigen::VectorXd axial = Eigen::VectorXd::Zero(6);
  axial(1) = axial(4) = 1.0;
  EXPECT_LT((K * axial).norm(), 1e-10 * K.norm());
  // Rank 5: a radial translation stretches the hoops, a rotation bends; nothing else is free.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
  EXPECT_LT(std::abs(eig.eigenvalues()(0)), 1e-10 * eig.eigenvalues()(5));
  EXPECT_GT(eig.eigenvalues()(1), 1e-8 * eig.eigenvalues()(5));
}

TEST_P(Shell208Element, MassOfAConicalFrustum) {
  // ρ h · 2π r̄ L for the frustum (exact: the radius is linear along and across it).
  const double r1 = 0.5, y1 = 0.0, r2 = 0.8, y2 = 0.4, h = 0.02;
  const Model m = one_element(r1, y1, r2, y2, h, GetParam());
  const ElementBuildContext ctx{m, {}};
  const auto element = create_element(ctx, m.elements.at(1));
  const double L = std::hypot(r2 - r1, y2 - y1);
  const double mass = 7800.0 * h * 2.0 * kPi * 0.5 * (r1 + r2) * L;
  for (bool lumped : {false, true}) {
    ElementContext c;
    c.lumped_mass = lumped;
    Eigen::MatrixXd M;
    element->mass(c, M);
    EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
    Eigen::VectorXd axial = Eigen::VectorXd::Zero(6);
    axial(1) = axial(4) = 1.0;
    EXPECT_NEAR(axial.dot(M * axial), mass, 1e-12 * mass) << "lumped " << lumped;
    Eigen::VectorXd radial = Eigen::VectorXd::Zero(6);
    radial(0) = radial(3) = 1.0;
    EXPECT_NEAR(radial.dot(M * radial), mass, 1e-12 * mass) << "lumped " << lumped;
  }
  EXPECT_NEAR(*element->volume(), mass / 7800.0, 1e-12 * mass / 7800.0);
}

INSTANTIATE_TEST_SUITE_P(Integration, Shell208Element, ::testing::Values(0, 2));

double element_value(const testing::DeckRun& run, int element, const std::string& item) {
  const auto series = run.reader->element_series(element, item);
  EXPECT_FALSE(series.empty()) << item;
  return series.empty() ? std::nan("") : series.back().second;
}

double node_value(const testing::DeckRun& run, int node, const std::string& lab) {
  const auto series = run.reader->nodal_series(node, lab);
  EXPECT_FALSE(series.empty()) << lab;
  return series.empty() ? std::nan("") : series.back().second;
}

class Shell208Deck : public ::testing::TestWithParam<int> {};

TEST_P(Shell208Deck, ClosedCylinderUnderInternalPressureCarriesTheMembraneStresses) {
  // R = 60, t = 1, p = 500 on face 1 of elements running up the axis (face 1 presses against
  // the normal n = (−t_y, t_x) = −X: outward, on the inner surface r_i = R − t/2); the cap
  // force p π R² on the top. The hoop resultant is p r_i (equilibrium of the tube); at the
  // mid-surface it agrees with Lamé's thick-walled cylinder (29749 at r = R, vm13's target).
  const double R = 60.0, t = 1.0, p = 500.0, r_i = R - 0.5 * t;
  const std::string deck = "/PREP7\nET,1,SHELL208,,," + std::to_string(GetParam()) +
                           "\nSECTYPE,1,SHELL\nSECDATA,1\nMP,EX,1,30E6\nMP,NUXY,1,.3\n"
                           "N,1,60\nN,5,60,10\nFILL\nE,1,2\nEGEN,4,1,1\nCP,1,UX,ALL\n"
                           "D,1,UY\nD,ALL,ROTZ\nF,5,FY,5654866.8\nSFE,ALL,1,PRES,,500\n"
                           "FINISH\n/SOLU\nSOLVE\nFINISH\n";
  const testing::DeckRun run =
      testing::run_deck_text("shell208_cylinder_" + std::to_string(GetParam()), deck);
  // KEYOPT(3) = 2: the internal node carries no pressure (as incompatible modes carry no
  // load), so its bubble draws the mid-element in by O((L/R)²): 2.7e-4 here, L/R = 1/24.
  const double tolerance = GetParam() == 0 ? 1e-4 : 5e-4;
  for (int e = 1; e <= 4; ++e) {
    EXPECT_NEAR(element_value(run, e, "SZ_MID"), p * r_i / t, tolerance * p * R / t);
    EXPECT_NEAR(element_value(run, e, "SY_MID"), p * R / (2 * t), 1e-3 * p * R / t);
    EXPECT_NEAR(element_value(run, e, "SX_MID"), 0.0, 1e-9 * p * R / t);
  }
  // The radial growth of the membrane solution: u = R/E (σ_θ − ν σ_y).
  const double u = R / 30e6 * (p * r_i / t - 0.3 * p * R / (2 * t));
  EXPECT_NEAR(node_value(run, 3, "UX"), u, 2e-3 * u);
}

TEST_P(Shell208Deck, ClampedCircularPlateUnderUniformPressure) {
  // a = 40, t = 1, p = 6 (vm15's case 1) on 40 equal elements: w(0) = p a⁴ / 64D (1 + 16 D /
  // (κ G t a²)), the Mindlin plate's; the edge moment p a² / 8 gives |σ_r| = 6 M / t² at the
  // clamped edge (extrapolated to its node by the two-point element, at the last element's
  // centre otherwise).
  const double a = 40.0, t = 1.0, p = 6.0, E = 30e6, nu = 0.3;
  const std::string deck = "/PREP7\nET,1,SHELL208,,," + std::to_string(GetParam()) +
                           "\nSECTYPE,1,SHELL\nSECDATA,1\nMP,EX,1,30E6\nMP,NUXY,1,.3\n"
                           "N,1\nN,41,40\nFILL\nE,1,2\nEGEN,40,1,1\nD,1,UX,,,,,ROTZ\nD,41,ALL\n"
                           "SFE,ALL,1,PRES,,6\nFINISH\n/SOLU\nSOLVE\nFINISH\n";
  const testing::DeckRun run =
      testing::run_deck_text("shell208_plate_" + std::to_string(GetParam()), deck);
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  const double G = E / (2 * (1 + nu));
  const double w = p * std::pow(a, 4) / (64 * D) * (1 + 16 * D / (5.0 / 6.0 * G * t * a * a));
  // Face 1 presses against n = (0, 1): the plate deflects down.
  EXPECT_NEAR(node_value(run, 1, "UY"), -w, 5e-3 * w);
  const double s_edge = 6 * (p * a * a / 8) / (t * t);
  const double r_last = a - 0.5;  // the last element's centre
  const double s_centre = 6 * (p / 16 * ((3 + nu) * r_last * r_last - (1 + nu) * a * a)) / (t * t);
  const double s_top = element_value(run, 40, "SX_TOP");
  EXPECT_NEAR(std::abs(s_top), s_centre, 0.01 * s_edge);
  EXPECT_LT(s_edge - std::abs(s_top), 0.05 * s_edge);
}

INSTANTIATE_TEST_SUITE_P(Integration, Shell208Deck, ::testing::Values(0, 2));

TEST(Shell208Deck, RefusesWhatItDoesNotCarryOut) {
  const std::string base = "/PREP7\nET,1,SHELL208\nMP,EX,1,30E6\nMP,NUXY,1,.3\nN,1,1\nN,2,1,1\n";
  const std::string layered = base +
                              "SECTYPE,1,SHELL\nSECDATA,0.1,1\nSECDATA,0.1,1\nE,1,2\nD,1,ALL\n"
                              "F,2,FY,1\nFINISH\n/SOLU\nSOLVE\n";
  EXPECT_NE(testing::run_deck_error("shell208_layered", layered).find("layered SHELL208"),
            std::string::npos);
  const std::string large = base +
                            "SECTYPE,1,SHELL\nSECDATA,0.1\nE,1,2\nD,1,ALL\nF,2,FY,1\nFINISH\n"
                            "/SOLU\nNLGEOM,ON\nSOLVE\n";
  EXPECT_NE(testing::run_deck_error("shell208_nlgeom", large).find("large deflection"),
            std::string::npos);
  // The apex of a dome sits on the axis (its bottom surface at the node crosses it): read;
  // a section thicker than the element's distance from the axis is not.
  const std::string apex =
      "/PREP7\nET,1,SHELL208\nMP,EX,1,30E6\nMP,NUXY,1,.3\nSECTYPE,1,SHELL\nSECDATA,0.01\n"
      "N,1,0,0.5\nN,2,0.02,0.499\nE,1,2\nD,1,UX,,,,,ROTZ\nD,2,ALL\nF,1,FY,-1\nFINISH\n/SOLU\n"
      "SOLVE\n";
  EXPECT_EQ(testing::run_deck_error("shell208_apex", apex), "");
  const std::string thick =
      "/PREP7\nET,1,SHELL208\nMP,EX,1,30E6\nMP,NUXY,1,.3\nSECTYPE,1,SHELL\nSECDATA,0.5\n"
      "N,1,0,0\nN,2,0.1,0.2\nE,1,2\nD,1,ALL\nFINISH\n/SOLU\nSOLVE\n";
  EXPECT_NE(testing::run_deck_error("shell208_thick", thick)
                .find("its thickness reaches across the axis"),
            std::string::npos);
}

}  // namespace
}  // namespace impactfe::test_shell208
