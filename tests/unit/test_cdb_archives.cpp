// Meshes written by other programs (docs/meshes.md): the public CDB archives and the Workbench
// input file of ../shared/cdb read by CDREAD (counts of nodes, elements and components, where an
// archive stops and why), the hexahedral beam against Timoshenko's cantilever, MESH200 cells,
// the legacy SOLID95, EQSLV and STEF, and the STRING arrays of Workbench input files.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/element.h"

namespace impactfe::test_cdb_archives {
namespace {

/// The shared archives beside the repository (never copied into it); the tests that need them
/// are skipped where they are absent.
std::filesystem::path shared_cdb() {
  return std::filesystem::path(IMPACTFE_TEST_DECKS).parent_path().parent_path().parent_path() /
         "shared" / "cdb";
}

#define REQUIRE_SHARED_CDB()                                  \
  if (!std::filesystem::exists(shared_cdb() / "HexBeam.cdb")) \
  GTEST_SKIP() << "the public archives are not in " << shared_cdb().string()

std::string cdread(const std::string& archive) {
  const std::string stem = (shared_cdb() / archive).replace_extension().string();
  return "/PREP7\nCDREAD,DB,'" + stem + "',cdb\n";
}

Model read_archive(const std::string& archive) {
  return read_deck_text(cdread(archive) + "FINISH\n", "archive.inp").model;
}

/// The message a deck stops with ("" when it reads to the end).
std::string stop_of(const std::string& text, const std::string& path = "deck.inp") {
  try {
    DeckOptions o;
    std::ostringstream sink;
    o.output = &sink;
    read_deck_text(text, path, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string run_output(const std::string& text) {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = Dialect::Modern;
  o.output = &sink;
  read_deck_text(text, "mem.inp", o);
  return sink.str();
}

std::size_t component_size(const Model& m, const std::string& name) {
  const auto it = m.components.find(name);
  return it == m.components.end() ? 0 : it->second.ids.size();
}

// ---- STRING arrays -------------------------------------------------------------------------

TEST(StringArrays, HoldOneTextPerColumnAddressedByCharacter) {
  const std::string out = run_output(
      "*DIM,DIR,STRING,20,2\n"
      "DIR(1) = 'C:\\Work\\ANSYS\\'\n"
      "DIR(1,2) = 'abcdef'\n"
      "DIR(4,2) = 'XY'\n"  // written from character 4 on: abcXY
      "*GET,KIND,PARM,DIR,TYPE\n"
      "*GET,LENGTH,PARM,DIR,DIM,X\n"
      "*VWRITE,DIR(1)\n%C\n"
      "*VWRITE,DIR(1,2)\n%C\n"
      "*VWRITE,DIR(3,1)\n%C\n"
      "*VWRITE,KIND,LENGTH\n(F3.0,F4.0)\n");
  EXPECT_EQ(out, "C:\\Work\\ANSYS\\\nabcXY\n\\Work\\ANSYS\\\n 4. 24.\n") << out;
}

TEST(StringArrays, RefuseNumbersAndOverlongDimensions) {
  EXPECT_NE(stop_of("*DIM,S,STRING,300\n")
                .find("deck.inp:1: *DIM: field 3: a STRING array holds "
                      "at most 248 characters, not 300"),
            std::string::npos);
  EXPECT_NE(stop_of("*DIM,S,STRING,8\nS(1) = 5\n")
                .find("deck.inp:2: *SET: S is a STRING array: give a quoted text, not 5"),
            std::string::npos);
  EXPECT_NE(stop_of("*DIM,S,STRING,8\n*DIM,V,,3\n*VFILL,S(1),RAMP,1,1\n").find("STRING"),
            std::string::npos);
}

// ---- the Workbench input file --------------------------------------------------------------

TEST(CdbArchives, WorkbenchInputFileSolvesItsLayeredPlate) {
  REQUIRE_SHARED_CDB();
  // The whole file runs: STRING arrays, /WB blocks, SHPP, ETCON, *GET of the wall time, the
  // SHELL281 element, its orthotropic material, the three-layer ACP section [0/45/-45] with its
  // reference at the bottom (SECOFFSET,BOTTOM), the element coordinate system (EMODIF ESYS 13),
  // the solve, CDWRITE and CEWRITE. One 0.1 m square element is stretched by UX = 1 mm on
  // x = 0.1 with UX = 0 on x = 0, free to contract, shear and bend: N_x = 0 on the free edges
  // and no moment, so the edge force is b * eps / a11 with a11 the first entry of the inverse
  // ABD matrix of classical laminate theory about the bottom surface (Jones, Mechanics of
  // Composite Materials, eq. 4.28): E1 40 GPa, E2 10 GPa, nu12 0.3, G12 5 GPa, 1 mm plies,
  // computed independently: 24993.14 N. The quadratic element holds this uniform membrane and
  // curvature state exactly.
  const testing::DeckRun run =
      testing::run_deck((shared_cdb() / "workbench_shell281_ds.dat").string(), "workbench_ds");
  const TimePoint point = run.reader->time_point(1, 0);
  const std::vector<int>& ids = run.reader->node_ids();
  double pull = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == 3 || ids[i] == 4 || ids[i] == 8) pull += point.reaction(i, 0);
  EXPECT_NEAR(pull, 24993.14, 24993.14 * 1e-4);
  EXPECT_TRUE(std::filesystem::exists(run.directory / "file.cdb"));  // the snippet's CDWRITE
}

// ---- the archives ---------------------------------------------------------------------------

TEST(CdbArchives, HexBeamReadsWithItsComponents) {
  REQUIRE_SHARED_CDB();
  const Model m = read_archive("HexBeam.cdb");
  EXPECT_EQ(m.nodes.size(), 321u);
  EXPECT_EQ(m.elements.size(), 40u);
  EXPECT_EQ(component_size(m, "ECOMP1"), 22u);  // 17-18, 21-40
  EXPECT_EQ(component_size(m, "ECOMP2"), 22u);  // 1-20, 23-24
  EXPECT_EQ(component_size(m, "NCOMP2"), 98u);
  EXPECT_EQ(component_size(m, "NODE_SELECTION"), 164u);
  EXPECT_EQ(m.materials.at(1).get("EX", 0), 70e9);
}

TEST(CdbArchives, TheOtherArchivesReadOrStopNamingTheirLine) {
  REQUIRE_SHARED_CDB();
  const Model cells = read_archive("all_solid_cells.cdb");  // one SOLID186 of each shape
  EXPECT_EQ(cells.nodes.size(), 52u);
  EXPECT_EQ(cells.elements.size(), 4u);
  const Model hm = read_archive("hypermesh.cdb");  // SHELL181, HyperMesh's own lines
  EXPECT_EQ(hm.nodes.size(), 105u);
  EXPECT_EQ(hm.elements.size(), 80u);
  EXPECT_EQ(component_size(hm, "PSHELL_1"), 80u);
  const Model wb = read_archive("workbench_193.cdb");
  EXPECT_EQ(wb.nodes.size(), 3u);
  EXPECT_EQ(wb.elements.size(), 0u);
  // A MESH200 type beside the solids (ET,1,200 with KEYOPT(1) = 6 and 7).
  const Model tets = read_archive("TetBeam.cdb");
  EXPECT_EQ(tets.nodes.size(), 1041u);
  EXPECT_EQ(tets.elements.size(), 3913u);
  EXPECT_EQ(tets.element_types.at(1).ansys_name, "MESH200");
  const Model sector = read_archive("sector.cdb");
  EXPECT_EQ(sector.nodes.size(), 655u);
  EXPECT_EQ(sector.elements.size(), 105u);
  EXPECT_EQ(component_size(sector, "REFINE"), 25u);
  // Element types impactfe does not have: the archive stops at its ET line, naming the type.
  EXPECT_NE(stop_of(cdread("mixed_missing_midside.cdb"))
                .find("mixed_missing_midside.cdb:16: ET: unknown element type '154'"),
            std::string::npos);
  EXPECT_NE(stop_of(cdread("ErnoRadiation.cdb")).find("ErnoRadiation.cdb:9: THOPT"),
            std::string::npos);
}

TEST(CdbArchives, HexBeamBendsAsTimoshenkosCantilever) {
  REQUIRE_SHARED_CDB();
  // The 1 x 1 x 5 beam along Z (E 70e9, nu 0.35; 40 SOLID186 of 2 x 2 x 10) held at Z = 0 and
  // loaded by P in X spread over the nodes of the end Z = 5. Timoshenko's cantilever:
  // d = P L^3 / (3 E I) + P L / (k G A), k = 10 (1 + nu) / (12 + 11 nu) for a rectangle
  // (Cowper 1966), compared with the mean UX of the loaded end.
  const Model m = read_archive("HexBeam.cdb");
  double z_end = 0.0;
  for (const auto& [id, n] : m.nodes) z_end = std::max(z_end, n.x.z());
  std::vector<int> end;
  for (const auto& [id, n] : m.nodes)
    if (std::abs(n.x.z() - z_end) < 1e-9) end.push_back(id);
  ASSERT_FALSE(end.empty());
  const double P = 1000.0;
  const std::string deck = cdread("HexBeam.cdb") + "FINISH\n/SOLU\nANTYPE,STATIC\n" +
                           "NSEL,S,LOC,Z,0\nD,ALL,ALL,0\n" +
                           fmt::format("NSEL,S,LOC,Z,{}\nF,ALL,FX,{}\n", z_end, P / end.size()) +
                           "ALLSEL\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("hexbeam_cantilever", deck);
  double mean = 0.0;
  for (int id : end) mean += run.reader->nodal_series(id, "UX").back().second / end.size();
  const double E = 70e9, nu = 0.35, G = E / (2 * (1 + nu)), L = z_end, b = 1.0, h = 1.0;
  const double I = b * h * h * h / 12, A = b * h, k = 10 * (1 + nu) / (12 + 11 * nu);
  const double timoshenko = P * L * L * L / (3 * E * I) + P * L / (k * G * A);
  // Measured 0.973: the root is held whole (no Poisson contraction, no warping of the section
  // there), which is stiffer than the beam theory's cantilever by a few per cent at L/h = 5.
  EXPECT_NEAR(mean / timoshenko, 1.0, 0.035) << mean << " vs " << timoshenko;
  EXPECT_GT(mean, P * L * L * L / (3 * E * I));  // softer than Euler-Bernoulli: shear counts
}

// ---- elements the archives define ------------------------------------------------------------

TEST(CdbArchives, Mesh200CellsAreCheckedByKeyopt) {
  const std::string nodes =
      "N,1\nN,2,1\nN,3,1,1\nN,4,0,1\nN,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\n";
  const auto build = [&](const std::string& keyopt, const std::string& element) {
    const Model m =
        read_deck_text("/PREP7\nET,1,MESH200\n" + keyopt + nodes + element + "\nFINISH\n",
                       "mesh200.inp")
            .model;
    return create_element(ElementBuildContext{m, {}}, m.elements.begin()->second);
  };
  // KEYOPT(1) = 6: a quadrilateral of 4 nodes; no degrees of freedom, stiffness or mass.
  const auto quad = build("KEYOPT,1,1,6\n", "E,1,2,3,4");
  EXPECT_EQ(quad->n_dofs(), 0);
  // KEYOPT(1) = 10: the brick takes 8 nodes, not 4.
  EXPECT_NO_THROW(build("KEYOPT,1,1,10\n", "E,1,2,3,4,5,6,7,8"));
  try {
    build("KEYOPT,1,1,10\n", "E,1,2,3,4");
    FAIL() << "a 4-node brick was built";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(MESH200, KEYOPT(1) = 10: brick) needs 8 nodes, 4 given"),
              std::string::npos)
        << e.what();
  }
}

TEST(CdbArchives, Solid95IsSolid186) {
  const std::string nodes =
      "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1.2,0\nN,4,0,1,0\nN,5,0,0,1\nN,6,1,0,1.1\nN,7,1,1,1\n"
      "N,8,0,1,1\nN,9,0.5,0,0\nN,10,1,0.6,0\nN,11,0.5,1.1,0\nN,12,0,0.5,0\nN,13,0.5,0,1.05\n"
      "N,14,1,0.5,1.05\nN,15,0.5,1,1\nN,16,0,0.5,1\nN,17,0,0,0.5\nN,18,1,0,0.55\n"
      "N,19,1,1.1,0.5\nN,20,0,1,0.5\n";
  const auto build = [&](const std::string& type, const std::string& keyopt) {
    const Model m = read_deck_text("/PREP7\nET,1," + type + "\n" + keyopt +
                                       "MP,EX,1,2E5\nMP,NUXY,1,0.3\n" + nodes +
                                       "E,1,2,3,4,5,6,7,8\nEMORE,9,10,11,12,13,14,15,16\n"
                                       "EMORE,17,18,19,20\nFINISH\n",
                                   "solid95.inp")
                        .model;
    return create_element(ElementBuildContext{m, {}}, m.elements.begin()->second);
  };
  const auto stiffness = [&](const std::string& type) {
    const auto e = build(type, "");
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ElementContext{}, Eigen::VectorXd::Zero(e->n_dofs()), K, f);
    return K;
  };
  const Eigen::MatrixXd k95 = stiffness("95"), k186 = stiffness("SOLID186");
  ASSERT_EQ(k95.rows(), 60);
  EXPECT_EQ(k95, k186);  // the same element, bit for bit
  try {
    build("95", "KEYOPT,1,11,1\n");
    FAIL() << "SOLID95's 14-point rule was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("SOLID95 KEYOPT(11) = 1 is not carried out"),
              std::string::npos)
        << e.what();
  }
}

// ---- commands the archives carry -------------------------------------------------------------

TEST(CdbArchives, EqslvAndStef) {
  EXPECT_EQ(stop_of("/SOLU\nEQSLV,SPARSE\nEQSLV,PCG,1E-8\neqsl,sparse,,,,,1\nSTEF,5.669E-8\n"), "");
  EXPECT_NE(
      stop_of("/SOLU\nEQSLV,FOO\n").find("deck.inp:2: EQSLV: Lab 'FOO' is not an equation solver"),
      std::string::npos);
  EXPECT_NE(stop_of("/SOLU\nEQSLV,SPARSE,,,,,2\n").find("field 6 '2' is not an EQSLV field"),
            std::string::npos);
  EXPECT_NE(stop_of("/PREP7\nSTEF,-1\n").find("deck.inp:2: STEF: VALUE -1 must be positive"),
            std::string::npos);
}

TEST(CdbArchives, ArchiveDefaultsAreAcceptedAndOtherValuesRefused) {
  EXPECT_EQ(stop_of("/PREP7\nIRLF,0\nKUSE,0\nPSTRES,OFF\nCRPLIM,0.1,0\nCRPLIM,0,1\n"
                    "NCNV,1,0,0,0,0\nNEQIT,0\n"),
            "");
  EXPECT_NE(stop_of("/PREP7\nIRLF,1\n").find("deck.inp:2: IRLF: KEY 1: inertia relief"),
            std::string::npos);
  EXPECT_NE(stop_of("/PREP7\nKUSE,1\n").find("deck.inp:2: KUSE: KEY 1"), std::string::npos);
  EXPECT_NE(stop_of("/PREP7\nPSTRES,ON\n").find("deck.inp:2: PSTRES: ON"), std::string::npos);
  EXPECT_NE(stop_of("/PREP7\nCRPLIM,0.5,1\n").find("creep-ratio time-step control"),
            std::string::npos);
  EXPECT_NE(stop_of("/PREP7\nNCNV,2\n").find("deck.inp:2: NCNV: KSTOP 2"), std::string::npos);
}

TEST(CdbArchives, EmodifAndTheBoundingBoxOfTheNodes) {
  const std::string deck =
      "/PREP7\nET,1,SOLID185\nET,2,SOLID185\nMP,EX,1,1\nN,1,-1\nN,2,1\nN,3,1,1\nN,4,0,1\n"
      "N,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,2\nE,1,2,3,4,5,6,7,8\nE,1,2,3,4,5,6,7,8\n"
      "ESEL,S,ELEM,,2\nCM,SECOND,ELEM\nALLSEL\n";
  const Model m = read_deck_text(deck +
                                     "EMODIF,SECOND,MAT,3\nEMODIF,1,TYPE,2\n"
                                     "EMODIF,ALL,REAL,4\nEMODIF,1,ESYS,0\nFINISH\n",
                                 "emodif.inp")
                      .model;
  EXPECT_EQ(m.elements.at(1).mat, 1);
  EXPECT_EQ(m.elements.at(2).mat, 3);  // the component's element
  EXPECT_EQ(m.elements.at(1).type, 2);
  EXPECT_EQ(m.elements.at(2).real, 4);
  // STLOC blank (or 0): every attribute from the current pointers (vm141: TYPE,3 then
  // EMODIF,ALL); an attribute's I1 blank or 0 is its default 1.
  const Model all = read_deck_text(deck +
                                       "ET,5,SOLID185\nTYPE,5\nMAT,7\nREAL,2\nEMODIF,1\n"
                                       "EMODIF,2,MAT,4\nEMODIF,2,MAT\nFINISH\n",
                                   "emodif_all.inp")
                        .model;
  EXPECT_EQ(all.elements.at(1).type, 5);
  EXPECT_EQ(all.elements.at(1).mat, 7);
  EXPECT_EQ(all.elements.at(1).real, 2);
  EXPECT_EQ(all.elements.at(2).type, 1);
  EXPECT_EQ(all.elements.at(2).mat, 1);
  // ESYS may name a system defined later (a Workbench file writes LOCAL before or after): it
  // is checked when the element is solved (test_element_esys.cpp).
  EXPECT_EQ(
      read_deck_text(deck + "EMODIF,1,ESYS,13\nFINISH\n", "esys.inp").model.elements.at(1).esys,
      13);
  EXPECT_NE(stop_of(deck + "EMODIF,1,TYPE,9\n").find("element type 9 is not defined"),
            std::string::npos);
  // *GET NODE MNLOC / MXLOC: the least and greatest coordinate of the selected nodes.
  const std::string out = run_output(deck +
                                     "*GET,XMIN,NODE,,MNLOC,X\n*GET,ZMAX,NODE,0,MXLOC,Z\n"
                                     "NSEL,S,NODE,,2,3\n*GET,XMIN2,NODE,,MNLOC,X\n"
                                     "*VWRITE,XMIN,ZMAX,XMIN2\n(3F5.1)\n");
  EXPECT_EQ(out, " -1.0  2.0  1.0\n") << out;
  // REAL for RCON, as Workbench writes it.
  EXPECT_EQ(run_output("/PREP7\nR,3,1.0\n*get,NR,real,0,NUM,MAX\n*VWRITE,NR\n(F3.0)\n"), " 3.\n");
}

TEST(CdbArchives, CdreadFindsTheArchiveWhateverItsCaseAndAtTheBeginLevel) {
  namespace fs = std::filesystem;
  const fs::path dir = testing::fresh_directory("cdread_case");
  {
    std::ofstream out(dir / "BLOCK.CDB");
    out << "/PREP7\nET,1,SOLID185\nN,1\nN,2,1\nN,3,1,1\nN,4,0,1\nN,5,0,0,1\nN,6,1,0,1\n"
           "N,7,1,1,1\nN,8,0,1,1\nE,1,2,3,4,5,6,7,8\n";
  }
  const fs::path deck = dir / "reads.inp";
  {
    std::ofstream out(deck);
    out << "CDREAD,db,block,cdb\nFINISH\n";  // at the Begin level, in lower case
  }
  const Job job = read_deck(deck.string());
  EXPECT_EQ(job.model.nodes.size(), 8u);
  EXPECT_EQ(job.model.elements.size(), 1u);
  const std::string missing = stop_of("CDREAD,DB,VM999,CDB\n");
  EXPECT_NE(missing.find("deck.inp:1: CDREAD: the archive 'VM999.CDB' does not exist"),
            std::string::npos)
      << missing;
}

}  // namespace
}  // namespace impactfe::test_cdb_archives
