// Model building by the deck reader: generation commands with their defaults (APDL_SUBSET
// §3.8-§3.12), element checks, loads, masters, and the 4x / modern solution requests.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "deck/deck_reader.h"

namespace test_deck_model {

using namespace impactfe;

namespace {

Job parse(const std::string& text, std::optional<Dialect> dialect = std::nullopt) {
  DeckOptions o;
  o.dialect = dialect;
  return read_deck_text(text, "mem.inp", o);
}

/// Runs `text` and returns the error message ("" when it parses).
std::string error_of(const std::string& text, std::optional<Dialect> dialect = std::nullopt) {
  try {
    parse(text, dialect);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::map<DofKey, double>& m, int node, Dof d) {
  return m.count(DofKey{node, d}) != 0;
}

}  // namespace

TEST(DeckModel, FillDefaultsUseLastTwoNodesDefinedByN) {
  const Job job = parse("/PREP7\nN,1,0,0,0\nN,5,4,8,-4,0,0,40\nFILL\n");
  const Model& m = job.model;
  ASSERT_EQ(m.nodes.size(), 5u);
  for (int i = 2; i <= 4; ++i) {
    const double s = (i - 1) / 4.0;
    EXPECT_NEAR((m.node(i).x - Vec3(4 * s, 8 * s, -4 * s)).norm(), 0.0, 1e-14);
    EXPECT_NEAR(m.node(i).angles_deg.z(), 40 * s, 1e-12);  // angles interpolated too
  }
}

TEST(DeckModel, FillWithSpacingRatioAndExplicitNumbers) {
  // Two interior nodes, divisions in ratio 1 : 2 : 4 (SPACE = last/first = 4): x = 1, 3 of 7.
  const Job job = parse("/PREP7\nN,1\nN,10,7\nFILL,1,10,2,20,5,,,4\n");
  EXPECT_NEAR(job.model.node(20).x.x(), 1.0, 1e-12);
  EXPECT_NEAR(job.model.node(25).x.x(), 3.0, 1e-12);
  EXPECT_EQ(job.model.nodes.size(), 4u);
}

TEST(DeckModel, NgenCopiesPattern) {
  // §3.9 decoded: NGEN,3,3,1,3,1,1 makes nodes 4-6 at x=0 and 7-9 at x=1 from nodes 1-3.
  const Job job = parse("/PREP7\nN,1,-1,-1,1.5\nN,3,-1,1,1.5\nFILL\nNGEN,3,3,1,3,1,1\n");
  ASSERT_EQ(job.model.nodes.size(), 9u);
  EXPECT_EQ(job.model.node(5).x, Vec3(0, 0, 1.5));
  EXPECT_EQ(job.model.node(9).x, Vec3(1, 1, 1.5));
}

TEST(DeckModel, NgenSpacingRatioGradesTheCopies) {
  // NGEN,4,1,1,,,3,0,0,4: three divisions, the last four times the first (ratio 2 between
  // neighbours: 1 + 2 + 4 = 7 parts of the 9 units), the last copy at 3 × DX = 9 as without SPACE.
  const Job job = parse("/PREP7\nN,1\nNGEN,4,1,1,,,3,0,0,4\n");
  ASSERT_EQ(job.model.nodes.size(), 4u);
  EXPECT_NEAR(job.model.node(2).x.x(), 9.0 / 7.0, 1e-12);
  EXPECT_NEAR(job.model.node(3).x.x(), 27.0 / 7.0, 1e-12);
  EXPECT_NEAR(job.model.node(4).x.x(), 9.0, 1e-12);
}

TEST(DeckModel, EgenKeepsPatternAttributesAndIncrements) {
  const Job job = parse(
      "/PREP7\nET,1,LINK180\nET,2,LINK180\nET,3,LINK180\nN,1\n,2,1\n,3,2\n,4,3\nTYPE,1\nMAT,"
      "1\nREAL,1\nE,1,2\n"
      "TYPE,2\nMAT,5\nEGEN,3,1,1,,,1,1,2\n");
  const Model& m = job.model;
  ASSERT_EQ(m.elements.size(), 3u);
  EXPECT_EQ(m.elements.at(2).nodes, (std::vector<int>{2, 3}));
  EXPECT_EQ(m.elements.at(2).mat, 2);
  EXPECT_EQ(m.elements.at(2).type, 2);  // pattern type 1 + TINC, not the current TYPE
  EXPECT_EQ(m.elements.at(3).type, 3);
  EXPECT_EQ(m.elements.at(2).real, 3);
  EXPECT_EQ(m.elements.at(3).nodes, (std::vector<int>{3, 4}));
  EXPECT_EQ(m.elements.at(3).mat, 3);
  EXPECT_EQ(m.elements.at(3).real, 5);
  // the first copy asks for type 2, which does not exist
  EXPECT_NE(error_of("/PREP7\nET,1,LINK180\nN,1\n,2,1\n,3,2\nE,1,2\nEGEN,3,1,1,,,,1\n")
                .find("element type 2 of generated element 2 is not defined"),
            std::string::npos);
}

TEST(DeckModel, EngenNumbersByIncrementAndNegativePattern) {
  const Job job = parse(
      "/PREP7\nET,1,LINK8\nN,1\nNGEN,10,1,1,,,1\nE,1,2\nE,2,3\nENGEN,10,2,3,1,2\nEGEN,2,1,-1\n");
  const Model& m = job.model;
  EXPECT_EQ(m.elements.at(11).nodes, (std::vector<int>{4, 5}));
  EXPECT_EQ(m.elements.at(12).nodes, (std::vector<int>{5, 6}));
  EXPECT_EQ(m.elements.at(13).nodes, (std::vector<int>{6, 7}));  // copy of the last element (12)
  EXPECT_EQ(m.elements.size(), 5u);
  EXPECT_NE(error_of("/PREP7\nET,1,LINK8\nN,1\nN,2,1\nE,1,2\nENGEN,5,2,7,1\n")
                .find("node 8 of generated element 6 (copy of 1) is not defined"),
            std::string::npos);
}

TEST(DeckModel, EgenGeneratesMissingNodesFromDxDyDz) {
  // EGEN's DX, DY, DZ define the nodes a copy needs and that do not exist yet, as NGEN with
  // the same increments would; existing nodes are kept (EGEN notes). VM25 builds its strip so.
  const Job job =
      parse("/PREP7\nET,1,LINK180\nN,1\nN,2,1\nN,4,7,7\nE,1,2\nEGEN,3,2,1,,,,,,,,0.5,0.25\n");
  const Model& m = job.model;
  ASSERT_EQ(m.elements.size(), 3u);
  EXPECT_EQ(m.elements.at(2).nodes, (std::vector<int>{3, 4}));
  EXPECT_TRUE(m.nodes.at(3).x.isApprox(Vec3(0.5, 0.25, 0.0)));
  EXPECT_TRUE(m.nodes.at(4).x.isApprox(Vec3(7, 7, 0.0)));  // existing: not moved
  EXPECT_TRUE(m.nodes.at(5).x.isApprox(Vec3(1.0, 0.5, 0.0)));
  EXPECT_TRUE(m.nodes.at(6).x.isApprox(Vec3(2.0, 0.5, 0.0)));
  // Without DX, DY, DZ a missing node stays an error.
  EXPECT_NE(error_of("/PREP7\nET,1,LINK180\nN,1\nN,2,1\nE,1,2\nEGEN,2,2,1\n")
                .find("node 3 of generated element 2 (copy of 1) is not defined"),
            std::string::npos);
}

TEST(DeckModel, EsizeWithBlankSizeAndNdivResetsTheDefaults) {
  // ESIZ,,,2 (VMP09): SIZE and NDIV blank: no default size, as ESIZE alone; an explicit zero
  // size without NDIV is refused.
  const Job job = parse("/PREP7\nESIZE,0.5\nESIZ,,,2\n");
  EXPECT_EQ(job.model.solid.mesh.esize, 0.0);
  EXPECT_EQ(job.model.solid.mesh.esize_ndiv, 0);
  EXPECT_NE(error_of("/PREP7\nESIZE,0\n").find("element size must be positive"), std::string::npos);
}

TEST(DeckModel, EmidAddsSharedMidsideNodes) {
  // 4-node quadrilaterals retyped as PLANE183 (VM5): EMID puts one node at the middle of each
  // edge, a shared edge's node once; the collapsed edge K = L of a triangle takes K.
  const Job job = parse(
      "/PREP7\nET,1,PLANE182\nN,1\nN,2,2\nN,3,4\nN,4,0,2\nN,5,2,2\nN,6,4,2\nN,7,3,4\n"
      "E,1,2,5,4\nE,2,3,6,5\nE,5,6,7,7\nET,1,PLANE183\nEMID\n");
  const Model& m = job.model;
  ASSERT_EQ(m.elements.at(1).nodes.size(), 8u);
  const auto& a = m.elements.at(1).nodes;
  const auto& b = m.elements.at(2).nodes;
  const auto& t = m.elements.at(3).nodes;
  EXPECT_TRUE(m.nodes.at(a[4]).x.isApprox(Vec3(1, 0, 0)));
  EXPECT_TRUE(m.nodes.at(a[5]).x.isApprox(Vec3(2, 1, 0)));
  EXPECT_EQ(a[5], b[7]);  // the shared edge 2-5 (J-K of 1, L-I of 2): one node
  EXPECT_EQ(b[6], t[4]);  // the shared edge 6-5
  EXPECT_EQ(t[6], 7);     // the collapsed edge K-L
  EXPECT_EQ(m.nodes.size(), 7u + 4u + 3u + 2u);
  EXPECT_NE(error_of("/PREP7\nET,1,PLANE183\nN,1\nEMID,REMOVE\n").find("Key 'REMOVE'"),
            std::string::npos);
}

TEST(DeckModel, ElementNodeCountsAndDegenerateShapes) {
  const Job job = parse(
      "/PREP7\nET,1,SHELL63\nET,2,SOLID45\nET,3,MASS21\nN,1\nN,2,1\nN,3,1,1\nN,4,0,1\n"
      "NGEN,2,4,1,4,1,,,1\nE,1,2,3\nTYPE,2\nE,1,2,3,3,5,6,7,7\nTYPE,3\nE,4\n");
  EXPECT_EQ(job.model.elements.at(1).nodes, (std::vector<int>{1, 2, 3, 3}));
  EXPECT_EQ(job.model.elements.at(2).nodes, (std::vector<int>{1, 2, 3, 3, 5, 6, 7, 7}));
  EXPECT_EQ(job.model.elements.at(3).nodes, (std::vector<int>{4}));
  EXPECT_EQ(job.model.elements.at(3).where.line, 14);
  EXPECT_NE(error_of("/PREP7\nET,1,SOLID45\nN,1\nN,2,1\nE,1,2,1,2\n")
                .find("SOLID45 needs 8 nodes, 4 given"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nET,1,LINK8\nN,1\nE,,1\n").find("node 1 of element 1 is blank"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nN,1\nN,2\nE,1,2\n").find("element type 1 is not defined"),
            std::string::npos);
}

TEST(DeckModel, RealConstantsRmoreRmodif) {
  const Job job = parse("/PREP7\nR,2,1650,,,.1\nRMORE,7,,9\nRMODIF,2,2,5\nR,3,1.0,,,\n");
  const RealSet& r2 = job.model.real_sets.at(2);
  EXPECT_EQ(r2.values, (std::vector<double>{1650, 5, 0, 0.1, 0, 0, 7, 0, 9}));
  EXPECT_DOUBLE_EQ(r2.get(4), 0.1);
  EXPECT_EQ(job.model.real_sets.at(3).values.size(), 1u);  // trailing blanks are not constants
}

TEST(DeckModel, MaterialsBothForms) {
  const Job job = parse("/PREP7\nEX,1,30E6\nNUXY,1,.33\nMP,PRXY,2,0.25\nMP,DENS,2,7.3E-4\n",
                        Dialect::Classic4x);
  EXPECT_DOUBLE_EQ(job.model.materials.at(1).get("EX", 0), 30e6);
  EXPECT_DOUBLE_EQ(job.model.materials.at(1).get("PRXY", 0), 0.33);
  EXPECT_DOUBLE_EQ(job.model.materials.at(2).get("NUXY", 0), 0.25);
  EXPECT_DOUBLE_EQ(job.model.materials.at(2).get("DENS", 0), 7.3e-4);
}

TEST(DeckModel, MaterialAndRealMayFollowE) {
  // ANSYS allows R and MP after E; they are checked when the analysis is frozen.
  const Job job = parse(
      "/PREP7\nET,1,LINK180\nN,1\nN,2,10\nE,1,2\nR,1,0.5\nMP,EX,1,2E11\nFINISH\n/SOLU\n"
      "D,1,ALL\nF,2,FX,1\nSOLVE\n");
  ASSERT_EQ(job.steps.size(), 1u);
  EXPECT_EQ(job.steps[0].model_snapshot->materials.size(), 1u);
}

TEST(DeckModel, SectionsForLink180AndShell181) {
  const Job job = parse(
      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,0.25\nMP,EX,1,1\nN,1\nN,2,1\nE,1,2\n"
      "FINISH\n/SOLU\nD,1,ALL\nSOLVE\n");
  EXPECT_EQ(job.model.elements.at(1).secnum, 1);
  EXPECT_DOUBLE_EQ(job.model.sections.at(1).data.at(0), 0.25);
  EXPECT_EQ(job.steps.size(), 1u);
  // Without a section the modern default SECNUM 1 is dropped when the analysis is frozen.
  const Job no_section =
      parse("/PREP7\nET,1,LINK180\nR,1,0.25\nMP,EX,1,1\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nSOLVE\n");
  EXPECT_EQ(no_section.steps.at(0).model_snapshot->elements.at(1).secnum, 0);
}

TEST(DeckModel, ConstraintsRangesLabelsAndDeletion) {
  const Job job = parse(
      "/PREP7\nN,1\nNGEN,6,1,1,,,1\nD,1,UX,,,5,2,UY,ROTZ\nD,6,ALL,0.5\nDDELE,6,ROTX\n"
      "F,2,FY,-10,,4\nF,3,FY\nFDELE,4,ALL\nACEL,,,386.4\nIC,2,UX,0.1,3\nIC,2,VELY,7\n");
  const LoadStep& s = job.model.current;
  for (int n : {1, 3, 5}) {
    EXPECT_TRUE(has(s.constraints, n, Dof::UX));
    EXPECT_TRUE(has(s.constraints, n, Dof::UY));
    EXPECT_TRUE(has(s.constraints, n, Dof::ROTZ));
    EXPECT_FALSE(has(s.constraints, n, Dof::UZ));
  }
  EXPECT_FALSE(has(s.constraints, 2, Dof::UX));
  EXPECT_EQ(s.constraints.at(DofKey{6, Dof::UZ}), 0.5);
  EXPECT_FALSE(has(s.constraints, 6, Dof::ROTX));
  EXPECT_EQ(s.constraints.size(), 9u + 5u);
  EXPECT_EQ(s.forces.at(DofKey{2, Dof::UY}), -10.0);
  EXPECT_EQ(s.forces.at(DofKey{3, Dof::UY}), 0.0);  // blank VALUE = 0, entry kept
  EXPECT_FALSE(has(s.forces, 4, Dof::UY));
  EXPECT_EQ(s.acel, Vec3(0, 0, 386.4));
  const auto& ic = job.model.initial_conditions.at(DofKey{2, Dof::UX});
  EXPECT_DOUBLE_EQ(ic.displacement, 0.1);
  EXPECT_DOUBLE_EQ(ic.velocity, 3.0);  // legacy VALUE2
  EXPECT_DOUBLE_EQ(job.model.initial_conditions.at(DofKey{2, Dof::UY}).velocity, 7.0);
}

TEST(DeckModel, TolerantDofLabelIn4xOnly) {
  // OCR line of the thesis pendulum: "D,1,UX,,,,UY" (UY in the NINC field) = fix UX and UY.
  const Job job = parse("/PREP7\nKAN,4\nN,1\nD,1,UX,,,,UY\n");
  EXPECT_TRUE(has(job.model.current.constraints, 1, Dof::UX));
  EXPECT_TRUE(has(job.model.current.constraints, 1, Dof::UY));
  EXPECT_EQ(job.model.current.constraints.size(), 2u);
  EXPECT_NE(error_of("/PREP7\nN,1\nD,1,UX,,,,UY\n").find("mem.inp:3: D: field 6"),
            std::string::npos);
}

TEST(DeckModel, MastersDeduplicatedInInputOrder) {
  const Job job = parse("/PREP7\nN,1\nNGEN,5,1,1,,,1\nM,3,UZ,5\nM,1,UX,3,2,UZ\nM,ALL,UZ\n");
  const std::vector<DofKey> expected = {{3, Dof::UZ}, {4, Dof::UZ}, {5, Dof::UZ}, {1, Dof::UX},
                                        {1, Dof::UZ}, {3, Dof::UX}, {2, Dof::UZ}};
  EXPECT_EQ(job.model.masters, expected);
}

TEST(DeckModel, KayBeforeKanIsReinterpreted) {
  const Job job = parse("/PREP7\nKAY,6,2\nKAN,7\n");
  EXPECT_EQ(job.model.options.superelement_matrices, 2);
  EXPECT_FALSE(job.model.options.large_deflection);
  EXPECT_EQ(job.model.options.type, AnalysisType::Substructure);
  EXPECT_NE(error_of("/PREP7\nKAN,3\n").find("KAN=3 (harmonic) is not supported"),
            std::string::npos);
}

TEST(DeckModel, FourXLoadStepsAreCumulativeSnapshots) {
  const Job job = parse(
      "/PREP7\nKAN,4\nET,1,21\nR,1,2\nN,1\nE,1\nKAY,5,0\nTIME,1\nITER,4\nF,1,FX,5\nLWRITE\n"
      "KAY,5,1\nTIME,2\nDTIME,0.1\nF,1,FY,3\nKBC,1\nLWRITE\nAFWRITE\nFINISH\n/EXEC\n/INPUT,27\n");
  ASSERT_EQ(job.steps.size(), 1u);
  const auto& steps = job.steps[0].analysis->load_steps;
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_FALSE(steps[0].time_integration);  // KAY(5)=0: static step
  EXPECT_EQ(*steps[0].n_substeps, 4);
  EXPECT_EQ(steps[0].forces.size(), 1u);
  EXPECT_TRUE(steps[1].time_integration);
  EXPECT_FALSE(steps[1].n_substeps.has_value());  // DTIME replaces ITER's NITTER under KAN=4
  EXPECT_DOUBLE_EQ(*steps[1].dt, 0.1);
  EXPECT_EQ(steps[1].forces.size(), 2u);  // FX carried over
  EXPECT_TRUE(steps[1].stepped);
  EXPECT_EQ(steps[1].number, 2);
  EXPECT_EQ(steps[1].where.line, 17);
  EXPECT_EQ(job.steps[0].analysis->where.line, 21);
}

TEST(DeckModel, ModernTransientWithHoubolt) {
  const Job job = parse(
      "/PREP7\nET,1,MASS21\nR,1,1\nN,1\nE,1\nFINISH\n/SOLU\nANTYPE,TRANS\n"
      "TRNOPT,FULL,,,,,HOUB\nNLGEOM,ON\nTIME,1\nNSUBST,10\nOUTRES,ALL,ALL\nF,1,FX,1\nSOLVE\n"
      "TIME,2\nDELTIM,0.05\nFDELE,1,FX\nSOLVE\nFINISH\n");
  ASSERT_EQ(job.steps.size(), 1u);
  const AnalysisRequest& a = *job.steps[0].analysis;
  EXPECT_EQ(a.options.integrator, IntegratorKind::Houbolt);
  EXPECT_TRUE(a.options.large_deflection);
  EXPECT_TRUE(a.options.stress_stiffening);
  ASSERT_EQ(a.load_steps.size(), 2u);
  EXPECT_EQ(*a.load_steps[0].n_substeps, 10);
  EXPECT_EQ(a.load_steps[0].output.every, 1);
  EXPECT_FALSE(a.load_steps[1].n_substeps.has_value());
  EXPECT_DOUBLE_EQ(*a.load_steps[1].dt, 0.05);
  EXPECT_TRUE(a.load_steps[1].forces.empty());
  EXPECT_EQ(a.where.command, "SOLVE");
}

TEST(DeckModel, ModernDefaultsNewmarkHhtAndNewStepPerAntype) {
  const Job job = parse(
      "/PREP7\nET,1,MASS21\nR,1,1\nN,1\nE,1\nFINISH\n/SOLU\nANTYPE,MODAL\nMODOPT,LANB,4\n"
      "SOLVE\nFINISH\n/SOLU\nANTYPE,TRANS\nTRNOPT,MSUP,3\nDMPRAT,0.02\nMDAMP,,0.01,0.03\nTIME,1\n"
      "DELTIM,0.01\nSOLVE\nFINISH\n/SOLU\nEXPASS,ON\nNUMEXP,4,0,1\nEXPSOL,,,0.5\nSOLVE\n"
      "FINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\n");
  ASSERT_EQ(job.steps.size(), 4u);
  EXPECT_EQ(job.steps[0].analysis->options.type, AnalysisType::Modal);
  EXPECT_EQ(job.steps[0].analysis->options.modal.n_modes, 4);
  const AnalysisOptions& t = job.steps[1].analysis->options;
  EXPECT_EQ(t.type, AnalysisType::Transient);
  EXPECT_EQ(t.method, TransientMethod::ModeSuperposition);
  EXPECT_EQ(t.integrator, IntegratorKind::Newmark);
  EXPECT_EQ(t.msup_modes, 3);
  EXPECT_DOUBLE_EQ(t.modal_damping.at(1), 0.01);
  EXPECT_DOUBLE_EQ(t.modal_damping.at(2), 0.03);
  ASSERT_TRUE(job.steps[2].expansion.has_value());
  const auto& q = job.steps[2].expansion->requests;
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].count, 4);
  EXPECT_DOUBLE_EQ(q[0].t_end, 1.0);
  EXPECT_EQ(q[1].count, 1);
  EXPECT_DOUBLE_EQ(q[1].t_end, 0.5);
  ASSERT_TRUE(job.steps[3].analysis.has_value()) << job.steps[3].expansion.has_value();
  EXPECT_EQ(job.steps[3].analysis->options.type, AnalysisType::Static);
  const Job hht = parse("/SOLU\nANTYPE,TRANS\nTRNOPT,FULL,,,,,HHT\nTINTP,,,,,,,,,,0.1,0.05\n");
  EXPECT_EQ(hht.model.options.integrator, IntegratorKind::HHT);
  EXPECT_DOUBLE_EQ(*hht.model.options.tintp.alpha_f, 0.1);
  EXPECT_DOUBLE_EQ(*hht.model.options.tintp.alpha_m, 0.05);
}

TEST(DeckModel, LswriteLssolve) {
  const Job job = parse(
      "/PREP7\nET,1,MASS21\nR,1,1\nN,1\nE,1\nFINISH\n/SOLU\nANTYPE,STATIC\nTIME,1\nF,1,FX,1\n"
      "LSWRITE\nTIME,2\nF,1,FX,2\nLSWRITE\nLSSOLVE,1,2\n");
  ASSERT_EQ(job.steps.size(), 1u);
  const auto& s = job.steps[0].analysis->load_steps;
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].forces.at(DofKey{1, Dof::UX}), 1.0);
  EXPECT_EQ(s[1].forces.at(DofKey{1, Dof::UX}), 2.0);
  EXPECT_DOUBLE_EQ(*s[1].time_end, 2.0);
}

TEST(DeckModel, SuperelementRecords) {
  const Job modern = parse("/PREP7\nET,1,MATRIX50\nSE,helmet\n");
  EXPECT_EQ(modern.model.elements.at(1).superelement_file, "helmet");
  EXPECT_NE(error_of("/PREP7\nET,1,MASS21\nSE,x\n").find("MATRIX50"), std::string::npos);
  EXPECT_NE(error_of("/PREP7\nET,1,MATRIX50\nN,1\nE,1\n").find("SE,File"), std::string::npos);
}

TEST(DeckModel, DoLoopsIfBlocksAndMacros) {
  const Job job = parse(
      "/PREP7\n*DO,I,1,5\nN,I,I*2\n*IF,I,GE,4,THEN\nN,I+10\n*ELSEIF,I,EQ,1,THEN\nN,100\n*ELSE\n"
      "*ENDIF\n*ENDDO\n*CREATE,MK\nN,ARG1,ARG2\n*END\n*USE,MK,50,7.5\n");
  const Model& m = job.model;
  EXPECT_EQ(m.nodes.size(), 5u + 2u + 1u + 1u);
  EXPECT_DOUBLE_EQ(m.node(5).x.x(), 10.0);
  EXPECT_TRUE(m.nodes.count(14) && m.nodes.count(15) && m.nodes.count(100));
  EXPECT_FALSE(m.nodes.count(13));
  EXPECT_DOUBLE_EQ(m.node(50).x.x(), 7.5);
  EXPECT_NE(error_of("/PREP7\n*DO,I,1,3\nN,I\n").find("no matching *ENDDO"), std::string::npos);
}

TEST(DeckModel, InputFilesRelativeToTheIncludingDeck) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "impactfe_deck_input_test";
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "main.inp") << "/PREP7\n/INPUT,sub/nodes,inp\nN,3,3\n";
  std::ofstream(dir / "sub" / "nodes.inp") << "N,1\n/INPUT,more\nN,9,9\n";
  std::ofstream(dir / "sub" / "more.inp") << "N,2,2\n/EOF\nN,4,4\n";
  std::ofstream(dir / "loop.inp") << "/PREP7\n/INPUT,loop.inp\n";
  const Job job = read_deck((dir / "main.inp").string());
  EXPECT_EQ(job.model.nodes.size(), 4u);  // 1, 2, 9, 3 (N,4 after /EOF not read)
  EXPECT_FALSE(job.model.nodes.count(4));
  EXPECT_EQ(job.model.jobname, "main");
  try {
    read_deck((dir / "loop.inp").string());
    FAIL() << "endless /INPUT accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recursive call refused"), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(DeckModel, FilnameSetsJobnameUnlessGivenOnTheCommandLine) {
  EXPECT_EQ(parse("/FILNAME,crash\n").model.jobname, "crash");
  // The Verification Manual's spelling (vm149: /filename,case1).
  EXPECT_EQ(parse("/filename,case1\n").model.jobname, "case1");
  DeckOptions o;
  o.jobname = "cli";
  EXPECT_EQ(read_deck_text("/FILNAME,crash\n", "x.inp", o).model.jobname, "cli");
}

/// NMODIF moves existing nodes in the active system, a blank field keeping the node's value;
/// *REPEAT steps the node number; ALL takes the selected nodes; an undefined node is refused.
TEST(DeckModel, NmodifMovesNodesKeepingBlankFields) {
  const Model m = parse(
                      "/PREP7\nN,1,1,2,3\nN,2,4,5,6\nN,3,7,8,9\nNMODIF,1,10\n"
                      "NMODIF,2,,,0.5,30\n*REPEAT,2,1\nCSYS,1\nNMODIF,1,2,90\n")
                      .model;
  EXPECT_NEAR(m.nodes.at(1).x.x(), 0.0, 1e-12);
  EXPECT_NEAR(m.nodes.at(1).x.y(), 2.0, 1e-12);  // r = 2 at 90 degrees
  EXPECT_NEAR(m.nodes.at(1).x.z(), 3.0, 1e-12);  // Z kept
  for (int n : {2, 3}) {
    EXPECT_NEAR(m.nodes.at(n).x.z(), 0.5, 1e-12);
    EXPECT_NEAR(m.nodes.at(n).angles_deg.x(), 30.0, 1e-12);
  }
  EXPECT_NEAR(m.nodes.at(3).x.x(), 7.0, 1e-12);
  const Model all = parse("/PREP7\nN,1,1\nN,2,2\nN,3,3\nNSEL,S,NODE,,2,3\nNMODIF,ALL,,4\n").model;
  EXPECT_NEAR(all.nodes.at(1).x.y(), 0.0, 1e-12);
  EXPECT_NEAR(all.nodes.at(2).x.y(), 4.0, 1e-12);
  EXPECT_NEAR(all.nodes.at(3).x.y(), 4.0, 1e-12);
  EXPECT_NE(error_of("/PREP7\nN,1\nNMODIF,5,1\n").find("node 5"), std::string::npos);
}

TEST(DeckModel, NdeleDeletesFreeNodesAndKeepsUsedOnes) {
  const Model m = parse(
                      "/PREP7\nET,1,LINK180\nN,1\nN,2,1\nN,3,2\nN,4,3\nE,1,2\n"
                      "NDELE,1,4\n")
                      .model;
  EXPECT_EQ(m.nodes.count(1), 1u);  // used by element 1
  EXPECT_EQ(m.nodes.count(2), 1u);
  EXPECT_EQ(m.nodes.count(3), 0u);
  EXPECT_EQ(m.nodes.count(4), 0u);
  // A node with a constraint is refused rather than leaving the constraint behind.
  EXPECT_NE(error_of("/PREP7\nN,1\nD,1,UX\nNDELE,1\n").find("node 1 carries"), std::string::npos);
}

TEST(DeckModel, EdeleDeletesElementsAndTheirPressures) {
  const Model m = parse(
                      "/PREP7\nET,1,PLANE182\nN,1\nN,2,1\nN,3,1,1\nN,4,0,1\nN,5,2\n"
                      "N,6,2,1\nE,1,2,3,4\nE,2,5,6,3\nSFE,1,1,PRES,,5\nSFE,2,1,PRES,,5\n"
                      "ESEL,S,ELEM,,2\nEDELE,ALL\nESEL,ALL\nNDELE,ALL\n")
                      .model;
  EXPECT_EQ(m.elements.count(1), 1u);
  EXPECT_EQ(m.elements.count(2), 0u);
  EXPECT_EQ(m.current.pressures.count(FaceKey{2, 1}), 0u);
  EXPECT_EQ(m.current.pressures.count(FaceKey{1, 1}), 1u);
  EXPECT_EQ(m.nodes.count(5), 0u);  // freed by EDELE, deleted by NDELE
  EXPECT_EQ(m.nodes.count(3), 1u);
}

TEST(DeckModel, EgenKeepsMissingMidsideNodesMissing) {
  // PLANE183 given its corners only: the copies' midside nodes stay 0 (EMID fills them), not
  // the pattern's 0 plus the node increment.
  const Model m = parse(
                      "/PREP7\nET,1,PLANE183\nN,1\nN,2,1\nN,3,2\nN,11,0,1\nN,12,1,1\n"
                      "N,13,2,1\nE,1,2,12,11\nEGEN,2,1,1\nEMID\n")
                      .model;
  ASSERT_EQ(m.elements.count(2), 1u);
  const auto& n = m.elements.at(2).nodes;
  EXPECT_EQ(n[0], 2);
  EXPECT_EQ(n[2], 13);
  // EMID placed the shared midside node of edge 2-12 once, for both elements.
  EXPECT_EQ(m.elements.at(1).nodes[5], n[7]);
  EXPECT_NEAR(m.nodes.at(n[7]).x.x(), 1.0, 1e-12);
  EXPECT_NEAR(m.nodes.at(n[7]).x.y(), 0.5, 1e-12);
}

TEST(DeckModel, TriangleFormTakesItsCornersForEmid) {
  const Model m = parse("/PREP7\nET,1,PLANE183,1\nN,1\nN,2,1\nN,3,0,1\nE,1,2,3\nEMID\n").model;
  const auto& n = m.elements.at(1).nodes;
  ASSERT_EQ(n.size(), 8u);
  EXPECT_EQ(n[3], 3);  // the triangle K = L = O
  EXPECT_EQ(n[6], 3);
  EXPECT_NEAR(m.nodes.at(n[4]).x.x(), 0.5, 1e-12);  // midside of I-J
  EXPECT_NEAR(m.nodes.at(n[7]).x.y(), 0.5, 1e-12);  // midside of K-I
}

TEST(DeckModel, SelectionTypesReadAsMapdlAbbreviates) {
  const Model m = parse("/PREP7\nN,1\nN,2,1\nNSEL,S,NODE,,1\nNSEL,INVERT\n").model;
  EXPECT_FALSE(m.selection.nodes.selected(1));
  EXPECT_TRUE(m.selection.nodes.selected(2));
}

}  // namespace test_deck_model
