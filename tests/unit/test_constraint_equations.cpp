// Constraint equations by master-slave elimination (CE, CERIG, MPC184; docs/constraints.md):
// closed-form checks through the deck reader and the drivers, and the resolution of chained
// equations (assembly/constraint_equations.h).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "../support/run_deck.h"
#include "assembly/constraint_equations.h"
#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/kinematic_constraint.h"

namespace impactfe::test_constraint_equations {
namespace {

using testing::last_nodal_value;
using testing::run_deck_error;

// Two UX springs to ground, k1 at node 2 and k2 at node 4, tied by u2 = 2 u4 (CE,,0,2,UX,1,4,UX,
// -2: node 2 is the slave). The reduced system has one DOF, u4, with stiffness 4 k1 + k2 and load
// F4 + 2 F2 (the force on the slave acts on its master through Tᵀ).
const char* kTwoSprings =
    "/PREP7\nET,1,COMBIN14,,1\nR,1,100\nR,2,300\nN,1\nN,2,1\nN,3,0,1\nN,4,1,1\n"
    "REAL,1\nE,1,2\nREAL,2\nE,3,4\n";

TEST(ConstraintEquations, EquationTyingTwoSpringsClosedForm) {
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0,2,UX,1,4,UX,-2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,UX\nD,3,UX\n"
                           "F,4,FX,70\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_two_springs", deck);
  const double k1 = 100, k2 = 300, F = 70;
  const double u4 = F / (4 * k1 + k2);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), u4, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 2 * u4,
              1e-12);  // the slave's value, recovered
  // Reactions: each spring's ground end. They do not sum to −F: u2 = 2 u4 is a lever, whose
  // constraint force (λ on u2, −2λ on u4) has a resultant of its own.
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "FX"), -k1 * 2 * u4, 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 3, "FX"), -k2 * u4, 1e-9);
}

TEST(ConstraintEquations, ForceOnTheSlaveActsOnItsMasters) {
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0,2,UX,1,4,UX,-2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,UX\nD,3,UX\n"
                           "F,2,FX,70\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_slave_force", deck);
  const double u4 = 2 * 70.0 / (4 * 100.0 + 300.0);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), u4, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 2 * u4, 1e-12);
}

TEST(ConstraintEquations, HeldFirstDofLeavesTheEliminationToTheNext) {
  // MAPDL eliminates the first unique DOF of an equation: node 2 UX is held (D = 0.1), so
  // u2 − 2 u4 = 0 eliminates u4 = u2/2 = 0.05. The held DOF's reaction carries both springs:
  // k1 u2 + (1/2) k2 u4 = 10 + 7.5 (Tᵀ of spring 2's force).
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0,2,UX,1,4,UX,-2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,UX\nD,3,UX\n"
                           "D,2,UX,0.1\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_held_first", deck);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), 0.05, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "FX"), 17.5, 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "FX"), -10.0, 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 3, "FX"), -15.0, 1e-9);
}

TEST(ConstraintEquations, ConstantPrescribesARelativeDisplacement) {
  // CE,1,0.5,2,UX,1,4,UX,-1: u2 − u4 = 0.5 with no load: k1 u2 + k2 u4 = 0, so
  // u2 = 0.5 k2/(k1 + k2), u4 = −0.5 k1/(k1 + k2), and the reactions are equal and opposite.
  // Given in two commands (CE,HIGH adds the second term) to check the continuation.
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0.5,2,UX,1\nCE,HIGH,,4,UX,-1\nFINISH\n/SOLU\nANTYPE,STATIC\n"
                           "D,1,UX\nD,3,UX\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_constant", deck);
  const double k1 = 100, k2 = 300;
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 0.5 * k2 / (k1 + k2), 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), -0.5 * k1 / (k1 + k2), 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "FX"), -k1 * 0.5 * k2 / (k1 + k2), 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 3, "FX"), -last_nodal_value(*run.reader, 1, "FX"),
              1e-9);
}

// CP couples two DOFs of one element into one equation: the nonlinear elements' tangent takes
// both K_ab and K_ba on that diagonal entry. A large-deflection SHELL181 cantilever whose tip
// nodes share UZ (CP) gives the deflection of the same tie as a constraint equation and of no
// tie at all (a symmetric load); only K_ab, before, left Newton stalled at the full load.
TEST(ConstraintEquations, CoupledDofsOfOneNonlinearElement) {
  const auto deflection = [](const std::string& tag, const std::string& tie) {
    const auto run = testing::run_deck_text(
        tag,
        "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA,0.1\nMP,EX,1,1E7\nMP,NUXY,1,0.3\n"
        "N,1\nN,2,0,1\nN,3,10\nN,4,10,1\nE,1,3,4,2\nD,1,ALL\nD,2,ALL\n" +
            tie +
            "\nF,3,FZ,10\nF,4,FZ,10\nFINISH\n/SOLU\nANTYPE,STATIC\nNLGEOM,ON\nNSUBST,5\n"
            "SOLVE\nFINISH\n");
    const auto w = run.reader->nodal_series(3, "UZ");
    return std::make_pair(w.back().second, run.statistics.analyses.back().n_iterations);
  };
  const auto [free_w, free_iterations] = deflection("cp_shell_free", "");
  const auto [cp_w, cp_iterations] = deflection("cp_shell_cp", "CP,1,UZ,3,4");
  const auto [ce_w, ce_iterations] = deflection("cp_shell_ce", "CE,1,0,3,UZ,1,4,UZ,-1");
  EXPECT_GT(free_w, 4.0);  // large deflection: below the linear 5.86 of this mesh
  EXPECT_NEAR(cp_w, free_w, 1e-6 * free_w);
  EXPECT_NEAR(ce_w, free_w, 1e-6 * free_w);
  EXPECT_LE(cp_iterations, free_iterations);
}

TEST(ConstraintEquations, CoupledSetsAreGeneratedFromSets) {
  // CPSGEN copies sets with their nodes incremented (numbered after the highest set), CPLGEN
  // makes sets of the same nodes for other labels, CPNGEN adds or removes a node range.
  DeckOptions o;
  o.dialect = Dialect::Modern;
  std::string nodes = "/PREP7\n";
  for (int n = 1; n <= 40; ++n) nodes += "N," + std::to_string(n) + "," + std::to_string(n) + "\n";
  const Job job = read_deck_text(nodes +
                                     "CP,1,UZ,2,12\nCP,2,ROTY,2,12\nCPSGEN,3,2,1,2\n"
                                     "CPLGEN,1,UX,ROTZ\nCPNGEN,20,UY,30,34,2\nCPNGEN,20,,-32\n",
                                 "mem.inp", o);
  const auto& sets = job.model.coupled_sets;
  ASSERT_EQ(sets.size(), 9u);
  const auto expect = [&](int id, Dof dof, std::vector<int> n) {
    ASSERT_EQ(sets.count(id), 1u) << id;
    EXPECT_EQ(sets.at(id).dof, dof) << id;
    EXPECT_EQ(sets.at(id).nodes, n) << id;
  };
  expect(3, Dof::UZ, {4, 14});
  expect(4, Dof::ROTY, {4, 14});
  expect(5, Dof::UZ, {6, 16});
  expect(6, Dof::ROTY, {6, 16});
  expect(7, Dof::UX, {2, 12});
  expect(8, Dof::ROTZ, {2, 12});
  expect(20, Dof::UY, {30, 34});
  // A generated set may not take a DOF already coupled, nor a node that does not exist.
  EXPECT_THROW(read_deck_text(nodes + "CP,1,UZ,2,12\nCP,2,UZ,4,14\nCPSGEN,2,2,1\n", "mem.inp", o),
               InputError);
  EXPECT_THROW(read_deck_text(nodes + "CP,1,UZ,2,12\nCPSGEN,2,30,1\n", "mem.inp", o), InputError);
}

TEST(ConstraintEquations, DistributingCouplingFollowsRigidMotionsOfItsSlaves) {
  // RBE3's master follows a rigid translation and a rigid small rotation of its slaves exactly
  // (weighted, irregular slaves, master off the centroid); slaves on a line cannot carry the
  // master's rotations and are refused.
  const std::vector<int> slaves = {1, 2, 3, 4, 5};
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(2, 0.1, 0), Vec3(2.2, 1.5, 0.3),
                               Vec3(-0.1, 1.2, 0.2), Vec3(1, 0.6, -0.4)};
  const std::vector<double> w = {1.0, 2.0, 0.5, 1.5, 3.0};
  const Vec3 xm(0.7, 0.4, 2.5);
  const auto eqs = distributing_coupling_equations(
      100, xm, slaves, x, w, {Dof::UX, Dof::UY, Dof::UZ, Dof::ROTX, Dof::ROTY, Dof::ROTZ}, {});
  ASSERT_EQ(eqs.size(), 6u);
  const Vec3 t(0.3, -0.2, 0.5), theta(1e-3, -2e-3, 0.5e-3);
  // The master's DOF d from the equation: −u_m + Σ c u_i = 0.
  const auto master_value = [&](std::size_t k, const std::function<Vec3(const Vec3&)>& u) {
    double sum = 0.0;
    for (const ConstraintTerm& term : eqs[k].terms) {
      if (term.dof.node == 100) continue;
      sum += term.coefficient *
             u(x[static_cast<std::size_t>(term.dof.node - 1)])(static_cast<int>(term.dof.dof));
    }
    return sum;
  };
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(eqs[k].terms.front().dof.node, 100);  // the master is the dependent DOF
    EXPECT_DOUBLE_EQ(eqs[k].terms.front().coefficient, -1.0);
    const double moved = master_value(k, [&](const Vec3&) { return t; });
    EXPECT_NEAR(moved, k < 3 ? t(static_cast<int>(k)) : 0.0, 1e-14) << k;
    const double turned = master_value(k, [&](const Vec3& p) { return Vec3(theta.cross(p)); });
    const double expected =
        k < 3 ? theta.cross(xm)(static_cast<int>(k)) : theta(static_cast<int>(k) - 3);
    EXPECT_NEAR(turned, expected, 1e-14) << k;
  }
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_THROW(distributing_coupling_equations(100, Vec3(1, 0, 1), {1, 2, 3}, line, {1, 1, 1},
                                               {Dof::ROTX}, {}),
               InputError);
  // Translations of a master at the centroid of slaves on a line are their mean.
  const auto mean = distributing_coupling_equations(100, Vec3(1, 0, 0), {1, 2, 3}, line, {1, 1, 1},
                                                    {Dof::UY}, {});
  ASSERT_EQ(mean.front().terms.size(), 4u);
  for (std::size_t i = 1; i < 4; ++i)
    EXPECT_NEAR(mean.front().terms[i].coefficient, 1.0 / 3, 1e-15);
}

TEST(ConstraintEquations, EquationsSurviveSaveAndResume) {
  // SAVE, CEDELE,ALL, RESUME: the equation comes back with the database (u2 = 2 u4 as above).
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0,2,UX,1,4,UX,-2\nSAVE\nCEDELE,ALL\nRESUME\nFINISH\n/SOLU\n"
                           "ANTYPE,STATIC\nD,1,UX\nD,3,UX\nF,4,FX,70\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_resume", deck);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 0.2, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), 0.1, 1e-12);
}

TEST(ConstraintEquations, ConstantAppliesToTheTotalInANonlinearRun) {
  // The same under two substeps (the element with a constant is evaluated at every iterate):
  // the end state is the same, the constant acts on the total displacement, not per increment.
  const std::string deck = std::string(kTwoSprings) +
                           "CE,1,0.5,2,UX,1,4,UX,-1\nFINISH\n/SOLU\nANTYPE,STATIC\nNSUBST,2\n"
                           "OUTRES,ALL,ALL\nD,1,UX\nD,3,UX\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("ce_constant_substeps", deck);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 0.5 * 300 / 400.0, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "UX"), -0.5 * 100 / 400.0, 1e-12);
}

TEST(ConstraintEquations, RigidRegionCarriesAMomentAsAForceCouple2D) {
  // CERIG 2-D: master node 1 (MASS21 KEYOPT(3) = 3 gives it UX UY ROTZ) at the origin, slaves
  // 2 and 3 at y = ±h, each on a UX spring k to ground. UX_s = UX_m − ROTZ_m y_s, so a moment M
  // turns the master by θ = M/(2 k h²) and the springs carry the couple ±M/(2h).
  const double k = 1000, h = 0.5, M = 40;
  const std::string deck =
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21,,,3\nR,1,1000\nR,2,1,1\nN,1\nN,2,0,0.5\n"
      "N,3,0,-0.5\nN,4,1,0.5\nN,5,1,-0.5\nTYPE,1\nREAL,1\nE,2,4\nE,3,5\nTYPE,2\nREAL,2\nE,1\n"
      "CERIG,1,2,ALL\nCERIG,1,3,ALL\nFINISH\n/SOLU\nANTYPE,STATIC\nD,4,UX\nD,5,UX\nD,1,UY\n"
      "F,1,MZ,40\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("cerig_couple_2d", deck);
  const double theta = M / (2 * k * h * h);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "ROTZ"), theta, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "UX"), 0.0, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), -theta * h, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 3, "UX"), theta * h, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "FX"), M / (2 * h), 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 5, "FX"), -M / (2 * h), 1e-9);
}

TEST(ConstraintEquations, RigidRegionCarriesAMomentAsAForceCouple3D) {
  // CERIG 3-D (master with ROTX ROTY ROTZ from MASS21 KEYOPT(3) = 0), slaves at z = ±h on UX
  // springs: UX_s = UX_m + ROTY_m z_s, a moment MY gives θy = M/(2 k h²), couple ±M/(2h).
  const double k = 1000, h = 0.25, M = 10;
  const std::string deck =
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21\nR,1,1000\nR,2,1,1,1,1,1,1\nN,1\nN,2,0,0,0.25\n"
      "N,3,0,0,-0.25\nN,4,1,0,0.25\nN,5,1,0,-0.25\nTYPE,1\nREAL,1\nE,2,4\nE,3,5\nTYPE,2\nREAL,2\n"
      "E,1\nNSEL,S,NODE,,2,3\nCERIG,1,ALL,UXYZ\nNSEL,ALL\nFINISH\n/SOLU\nANTYPE,STATIC\n"
      "D,4,UX\nD,5,UX\nD,1,UY,,,,,UZ,ROTX,ROTZ\nF,1,MY,10\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("cerig_couple_3d", deck);
  const double theta = M / (2 * k * h * h);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "ROTY"), theta, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), theta * h, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "FX"), -M / (2 * h), 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 5, "FX"), M / (2 * h), 1e-9);
}

TEST(ConstraintEquations, RigidBeamWithTipMassModalClosedForm) {
  // MPC184 rigid beam (KEYOPT(1) = 1) of length L from node 1 to node 2, point mass m at node 2,
  // node 1 on a torsional ROTZ spring k_t (COMBIN14 KEYOPT(2) = 6) and otherwise held: a rigid
  // bar with a mass, f = sqrt(k_t / (m L²)) / (2π).
  const double kt = 5000, m = 2, L = 1.5;
  const std::string deck =
      "/PREP7\nET,1,MPC184,1\nET,2,MASS21,,,2\nET,3,COMBIN14,,6\nR,2,2\nR,3,5000\nN,1\n"
      "N,2,1.5\nN,3\nTYPE,1\nE,1,2\nTYPE,2\nREAL,2\nE,2\nTYPE,3\nREAL,3\nE,3,1\nFINISH\n"
      "/SOLU\nANTYPE,MODAL\nMODOPT,LANB,1\nD,1,UX,,,,,UY,UZ,ROTX,ROTY\nD,3,ROTZ\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("mpc184_modal", deck);
  const auto f = run.reader->frequencies();
  ASSERT_FALSE(f.empty());
  EXPECT_NEAR(f[0], std::sqrt(kt / (m * L * L)) / (2 * std::numbers::pi), 1e-9);
}

TEST(ConstraintEquations, RigidLinkKeepsItsLengthBetweenSprings) {
  // MPC184 rigid link (KEYOPT(1) = 0) along X between nodes 2 and 3, each on an axial spring to
  // ground (k1, k2), F on node 3 (the link's slave UX): u2 = u3 = F/(k1 + k2).
  const std::string deck =
      "/PREP7\nET,1,MPC184\nET,2,COMBIN14\nR,2,100\nR,3,300\nN,1\nN,2,1\nN,3,2\nN,4,3\n"
      "TYPE,1\nE,2,3\nTYPE,2\nREAL,2\nE,1,2\nREAL,3\nE,3,4\nFINISH\n/SOLU\nANTYPE,STATIC\n"
      "D,1,ALL\nD,4,ALL\nF,3,FX,80\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("mpc184_link", deck);
  EXPECT_NEAR(last_nodal_value(*run.reader, 2, "UX"), 0.2, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 3, "UX"), 0.2, 1e-12);
  EXPECT_NEAR(last_nodal_value(*run.reader, 1, "FX"), -20.0, 1e-9);
  EXPECT_NEAR(last_nodal_value(*run.reader, 4, "FX"), -60.0, 1e-9);
}

TEST(ConstraintEquations, RefusesJointsNlgeomAndMastersWithoutRotations) {
  const std::string joint = run_deck_error(
      "mpc184_joint",
      "/PREP7\nET,1,MPC184,6\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\n"
      "SOLVE\nFINISH\n");
  EXPECT_NE(joint.find("KEYOPT(1) = 6"), std::string::npos) << joint;
  EXPECT_NE(joint.find("joints"), std::string::npos) << joint;
  const std::string nlgeom = run_deck_error(
      "mpc184_nlgeom",
      "/PREP7\nET,1,MPC184,1\nET,2,MASS21\nR,2,1,1,1,1,1,1\nN,1\nN,2,1\nTYPE,1\nE,1,2\nTYPE,2\n"
      "REAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,STATIC\nNLGEOM,ON\nD,1,ALL\nF,2,FY,1\nSOLVE\nFINISH\n");
  EXPECT_NE(nlgeom.find("NLGEOM"), std::string::npos) << nlgeom;
  const std::string no_rotation = run_deck_error(
      "cerig_no_rotation", std::string(kTwoSprings) +
                               "CERIG,2,4\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,UX\nSOLVE\nFINISH\n");
  EXPECT_NE(no_rotation.find("no rotations"), std::string::npos) << no_rotation;
}

TEST(ConstraintEquations, ChainedEquationsDependOnRetainedDofsOnly) {
  // u1 = u2 (equation 1), then u2 = 2 u3 + 1 (equation 2): u1 becomes 2 u3 + 1.
  const auto key = [](int node) { return DofKey{node, Dof::UX}; };
  DependentDofs d;
  d.add({1, 0.0, {{key(1), 1.0}, {key(2), -1.0}}, {}});
  d.add({2, 1.0, {{key(2), 1.0}, {key(3), -2.0}}, {}});
  ASSERT_NE(d.find(key(1)), nullptr);
  const DofDependence& u1 = *d.find(key(1));
  ASSERT_EQ(u1.masters.size(), 1u);
  EXPECT_EQ(u1.masters[0].first, key(3));
  EXPECT_DOUBLE_EQ(u1.masters[0].second, 2.0);
  EXPECT_DOUBLE_EQ(u1.constant, 1.0);
  // An equation whose first DOF is already a slave eliminates its next one (u4 = u1 = 2 u3 + 1);
  // one that brings a slave back onto itself is redundant and refused.
  d.add({3, 0.0, {{key(1), 1.0}, {key(4), -1.0}}, {}});
  ASSERT_NE(d.find(key(4)), nullptr);
  EXPECT_DOUBLE_EQ(d.find(key(4))->masters[0].second, 2.0);
  EXPECT_DOUBLE_EQ(d.find(key(4))->constant, 1.0);
  EXPECT_THROW(d.add({4, 0.0, {{key(3), 1.0}, {key(1), -0.5}}, {}}), InputError);
}

}  // namespace
}  // namespace impactfe::test_constraint_equations
