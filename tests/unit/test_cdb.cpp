// CDB archives: the Fortran formats of the blocks, the lexer handing a block's records to its
// command, NBLOCK/EBLOCK/CMBLOCK/RLBLOCK read by column, the record forms of CE, LOCAL and SFE,
// and CDWRITE,DB read back by CDREAD to the same model, the same file and the same solution.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "deck/cdb_format.h"
#include "deck/cdb_writer.h"
#include "deck/deck_reader.h"
#include "deck/lexer.h"

namespace impactfe::deck::test_cdb {
namespace {

TEST(CdbFormat, ColumnsOfTheBlockFormats) {
  EXPECT_EQ(field_widths(parse_fortran_format("(3i9,6e21.13e3)")),
            (std::vector<int>{9, 9, 9, 21, 21, 21, 21, 21, 21}));
  EXPECT_EQ(field_widths(parse_fortran_format("(1i7,2i9,6e21.13)")),
            (std::vector<int>{7, 9, 9, 21, 21, 21, 21, 21, 21}));
  EXPECT_EQ(field_widths(parse_fortran_format("(19i10)")).size(), 19u);
  EXPECT_EQ(field_widths(parse_fortran_format("(2i8,6g16.9)")),
            (std::vector<int>{8, 8, 16, 16, 16, 16, 16, 16}));
  EXPECT_THROW(parse_fortran_format("(3q9)"), std::invalid_argument);
  EXPECT_THROW(parse_fortran_format("3i9"), std::invalid_argument);
  EXPECT_THROW(parse_fortran_format("(i)"), std::invalid_argument);
}

TEST(CdbLexer, BlockRecordsBelongToTheirCommand) {
  const std::string text =
      "/PREP7\n"
      "NBLOCK,6,SOLID,2,2\n"
      "(3i9,6e21.13e3)\n"
      "        1        0        0 1.0000000000000E+000\n"
      "        2        0        0-2.0000000000000E+000-3.0000000000000E+000\n"
      "N,R5.3,LOC,       -1,\n"
      "FINISH\n";
  const auto cmds = lex_text(text, "a.cdb", Dialect::Modern);
  ASSERT_EQ(cmds.size(), 3u);  // /PREP7, NBLOCK with its records, FINISH
  EXPECT_EQ(cmds[1].name, "NBLOCK");
  ASSERT_TRUE(cmds[1].block);
  EXPECT_EQ(cmds[1].block_line, 3);
  EXPECT_NE(cmds[1].block->find("-2.0000000000000E+000-3.0"), std::string::npos);
  EXPECT_EQ(cmds[2].name, "FINISH");
  EXPECT_EQ(cmds[2].line, 7);
}

/// Two SOLID185 bricks along X, nodes 1-12; components and a real set of 9 values.
const char* kArchive =
    "/PREP7\n"
    "ET,1,185\n"
    "ET,2,14\n"
    "RLBLOCK,       1,       7,       9,       7\n"
    "(2i8,6g16.9)\n"
    "(7g16.9)\n"
    "       7       9     1000.0           0.5             0.0             0.0             0.0 "
    "            0.0\n"
    "             0.0             0.0         3.25\n"
    "NBLOCK,6,SOLID,12,12\n"
    "(3i9,6e21.13e3)\n"
    "        1        0        0\n"
    "        2        0        0 1.0000000000000E+000\n"
    "        3        0        0 1.0000000000000E+000 1.0000000000000E+000\n"
    "        4        0        0 0.0000000000000E+000 1.0000000000000E+000\n"
    "        5        0        0 0.0000000000000E+000 0.0000000000000E+000 1.0000000000000E+000\n"
    "        6        0        0 1.0000000000000E+000 0.0000000000000E+000 1.0000000000000E+000\n"
    "        7        0        0 1.0000000000000E+000 1.0000000000000E+000 1.0000000000000E+000\n"
    "        8        0        0 0.0000000000000E+000 1.0000000000000E+000 1.0000000000000E+000\n"
    "        9        0        0 2.0000000000000E+000\n"
    "       10        0        0 2.0000000000000E+000 1.0000000000000E+000\n"
    "       11        0        0 2.0000000000000E+000 0.0000000000000E+000 1.0000000000000E+000\n"
    "       12        0        0 2.0000000000000E+000 1.0000000000000E+000 1.0000000000000E+000"
    " 0.0000000000000E+000 0.0000000000000E+000 3.0000000000000E+001\n"
    "N,R5.3,LOC,       -1,\n"
    "EBLOCK,19,SOLID,2,2\n"
    "(19i10)\n"
    "         3         1         1         1         0         0         0         0         8"
    "         0        10         1         2         3         4         5         6         7"
    "         8\n"
    "         3         1         1         1         0         0         0         0         8"
    "         0        11         2         9        10         3         6        11        12"
    "         7\n"
    "        -1\n"
    "CMBLOCK,LEFT    ,NODE,       2  ! users node component definition\n"
    "(8i10)\n"
    "         1        -4\n"
    "CMBLOCK,BOTH,ELEM,       2\n"
    "(8i10)\n"
    "        10       -11\n"
    "MPTEMP,R5.0, 1, 1,  0.00000000    ,\n"
    "MPDATA,R5.0, 1,EX  ,       3, 1, 2.100000000E+11,\n"
    "MPTEMP,R5.0, 1, 1,  0.00000000    ,\n"
    "MPDATA,R5.0, 1,NUXY,       3, 1, 0.300000000    ,\n"
    "FINISH\n";

// The element block without SOLID (as MAPDL and Workbench write contact and target elements):
// element number, TYPE, REAL, MAT, ESYS and the nodes, more than ten continuing on the next
// record.
const char* const kNonSolidArchive =
    "/PREP7\n"
    "ET,1,186\nET,2,170\nET,3,174\n"
    "*DO,I,1,20\n"
    "N,I,I,MOD(I,3),MOD(I,5)\n"
    "*ENDDO\n"
    "EBLOCK,10,,22,3\n"
    "(15i9)\n"
    "       20        2        3        4        0        1        2        3        4\n"
    "       21        3        3        4        0        5        6        7        8\n"
    "       22        1        1        1        0        1        2        3        4        5"
    "        6        7        8        9       10\n"
    "       11       12       13       14       15       16       17       18       19       20\n"
    "       -1\n"
    "FINISH\n";

TEST(CdbRead, BlocksByColumn) {
  const Job job = read_deck_text(kArchive, "archive.cdb");
  const Model& m = job.model;
  ASSERT_EQ(m.nodes.size(), 12u);
  EXPECT_EQ(m.node(1).x, Vec3(0, 0, 0));  // no reals: the origin
  EXPECT_EQ(m.node(3).x, Vec3(1, 1, 0));  // Z blank: 0
  EXPECT_EQ(m.node(12).x, Vec3(2, 1, 1));
  EXPECT_EQ(m.node(12).angles_deg, Vec3(0, 0, 30));
  ASSERT_EQ(m.elements.size(), 2u);
  const ElementRecord& e = m.elements.at(11);
  EXPECT_EQ(e.mat, 3);
  EXPECT_EQ(e.type, 1);
  EXPECT_EQ(e.nodes, (std::vector<int>{2, 9, 10, 3, 6, 11, 12, 7}));
  EXPECT_EQ(m.components.at("LEFT").ids, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(m.components.at("BOTH").entity, "ELEM");
  EXPECT_EQ(m.components.at("BOTH").ids, (std::vector<int>{10, 11}));
  ASSERT_EQ(m.real_sets.at(7).values.size(), 9u);
  EXPECT_EQ(m.real_sets.at(7).values[0], 1000.0);
  EXPECT_EQ(m.real_sets.at(7).values[8], 3.25);
  EXPECT_EQ(m.materials.at(3).get("EX", 0), 2.1e11);
  EXPECT_EQ(m.materials.at(3).get("PRXY", m.materials.at(3).get("NUXY", 0)), 0.3);
}

TEST(CdbRead, BadRecordsNameTheirLine) {
  std::string bad = kArchive;
  bad.replace(bad.find("        9        0        0 2.0"), 9, "      9x ");
  try {
    read_deck_text(bad, "bad.cdb");
    FAIL() << "a record with a letter was read";
  } catch (const InputError& e) {
    // The lexer ends the block at the line that is not a record: the NBLOCK misses node 9 and
    // the line itself is no command.
    EXPECT_NE(std::string(e.what()).find("bad.cdb:"), std::string::npos) << e.what();
  }
  std::string solkey = kArchive;
  solkey.replace(solkey.find("EBLOCK,19,SOLID"), 15, "EBLOCK,19,SOLIX");
  try {
    read_deck_text(solkey, "solkey.cdb");
    FAIL() << "Solkey SOLIX was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":24: EBLOCK: Solkey 'SOLIX'"), std::string::npos)
        << e.what();
  }
  std::string nonsolid_esys = kNonSolidArchive;
  nonsolid_esys.replace(nonsolid_esys.find("       20        2        3        4        0"), 45,
                        "       20        2        3        4        5");
  try {
    read_deck_text(nonsolid_esys, "esys.cdb");
    FAIL() << "ESYS 5 (a system below 11) was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("esys.cdb:10: EBLOCK: ESYS 5"), std::string::npos)
        << e.what();
  }
}

TEST(CdbRead, NonSolidElementBlock) {
  const Job job = read_deck_text(kNonSolidArchive, "nonsolid.cdb");
  const Model& m = job.model;
  ASSERT_EQ(m.elements.size(), 3u);
  const ElementRecord& target = m.elements.at(20);
  EXPECT_EQ(target.type, 2);
  EXPECT_EQ(target.real, 3);
  EXPECT_EQ(target.mat, 4);
  EXPECT_EQ(target.nodes, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(m.elements.at(21).type, 3);
  // Four of CONTA174's eight nodes: completed as E,5,6,7,8 completes them.
  const Job by_e = read_deck_text(
      "/PREP7\nET,3,174\n*DO,I,5,8\nN,I,I\n*ENDDO\nTYPE,3\n"
      "E,5,6,7,8\nFINISH\n",
      "e.inp");
  EXPECT_EQ(m.elements.at(21).nodes, by_e.model.elements.at(1).nodes);
  // Twenty nodes: ten on the record, ten on its continuation.
  const ElementRecord& brick = m.elements.at(22);
  EXPECT_EQ(brick.type, 1);
  std::vector<int> all(20);
  for (int k = 0; k < 20; ++k) all[static_cast<std::size_t>(k)] = k + 1;
  EXPECT_EQ(brick.nodes, all);
}

TEST(CdbWrite, ReadBackGivesTheSameModelAndFile) {
  const std::string deck =
      "/PREP7\nET,1,SOLID185\nET,2,COMBIN14\nKEYOPT,1,2,3\nR,2,1.5E3,0.25\nMP,EX,1,2.1E11\n"
      "MP,PRXY,1,0.3\nMP,DENS,1,7850\nTB,BISO,1\nTBDATA,1,2.5E8,1.0E9\n"
      "BLOCK,0,1,0,0.5,0,0.3\nESIZE,0.1\nTYPE,1\nMAT,1\nVMESH,ALL\n"
      "N,1000,0.1,0.2,0.3,10,20,30\nN,1001,1.5,0.5,0.3\nTYPE,2\nREAL,2\nE,1000,1001\n"
      "NSEL,S,LOC,X,0\nCM,FIXED,NODE\nALLSEL\nD,FIXED,ALL,0\nF,1001,FX,1.0/3\n"
      "IC,1001,UX,0,2.5\nFINISH\n";
  const Model built = read_deck_text(deck, "built.inp").model;
  std::ostringstream first;
  write_cdb(built, first);
  const Model read = read_deck_text(first.str(), "written.cdb").model;
  std::ostringstream second;
  write_cdb(read, second);
  EXPECT_EQ(first.str(), second.str());
  ASSERT_EQ(read.nodes.size(), built.nodes.size());
  for (const auto& [id, n] : built.nodes) {
    EXPECT_EQ(read.node(id).x, n.x) << "node " << id;  // bitwise: 17 significant digits
    EXPECT_EQ(read.node(id).angles_deg, n.angles_deg) << "node " << id;
  }
  ASSERT_EQ(read.elements.size(), built.elements.size());
  for (const auto& [id, e] : built.elements) {
    EXPECT_EQ(read.elements.at(id).nodes, e.nodes);
    EXPECT_EQ(read.elements.at(id).type, e.type);
    EXPECT_EQ(read.elements.at(id).real, e.real);
  }
  EXPECT_EQ(read.element_types.at(1).key(2), 3);
  EXPECT_EQ(read.real_sets.at(2).values, built.real_sets.at(2).values);
  EXPECT_EQ(read.components.at("FIXED").ids, built.components.at("FIXED").ids);
  EXPECT_EQ(read.current.constraints, built.current.constraints);
  EXPECT_EQ(read.current.forces, built.current.forces);
  EXPECT_EQ(read.material_tables.size(), 1u);
  EXPECT_EQ(read.initial_conditions.at(DofKey{1001, Dof::UX}).velocity, 2.5);
}

// A shell plate whose elements take their axes from a local system (ESYS 11), held at X = 0,
// its end X = 1 made rigid (CERIG) with the master on a beam that carries the load, two nodes
// coupled in UZ (CP), two tied by an equation (CE), and a uniform and a tapered pressure (SFE).
const char* kCoupledModel =
    "/PREP7\nET,1,SHELL181\nMP,EX,1,2E11\nMP,PRXY,1,0.3\nSECTYPE,1,SHELL\nSECDATA,0.01\n"
    "LOCAL,11,0,0,0,0,30\nCSYS,0\nESYS,11\nRECTNG,0,1,0,0.5\nESIZE,0.25\nAMESH,ALL\nESYS,0\n"
    "ET,2,BEAM188\nMP,EX,2,2E11\nMP,PRXY,2,0.3\nSECTYPE,2,BEAM,RECT\nSECDATA,0.05,0.05\n"
    "N,1000,1.25,0.25,0\nN,1001,1.75,0.25,0\nTYPE,2\nMAT,2\nSECNUM,2\nE,1000,1001\n"
    "NSEL,S,LOC,X,1\nCERIG,1000,ALL,ALL\nALLSEL\n"
    "CP,1,UZ,NODE(0.5,0.5,0),NODE(0.75,0.5,0)\n"
    "CE,1,0,NODE(0.25,0,0),UZ,1,NODE(0.25,0.5,0),UZ,-0.5\n"
    "NSEL,S,LOC,X,0\nD,ALL,ALL\nALLSEL\n"
    "ESEL,S,CENT,X,0,0.5\nSFE,ALL,1,PRES,,1000\nALLSEL\n"
    "SFE,8,1,PRES,,100,200,300,400\nF,1001,FZ,100\nF,1001,MX,5\n";

TEST(CdbWrite, CouplingsEquationsLocalSystemsAndPressuresReadBack) {
  const Model built = read_deck_text(std::string(kCoupledModel) + "FINISH\n", "built.inp").model;
  ASSERT_FALSE(built.coupled_sets.empty());
  ASSERT_FALSE(built.constraint_equations.empty());
  ASSERT_FALSE(built.rigid_regions.empty());
  ASSERT_FALSE(built.current.pressures.empty());
  std::ostringstream first;
  write_cdb(built, first);
  EXPECT_NE(first.str().find("CE,R5.0,DEFI,2,1,"), std::string::npos) << first.str();
  EXPECT_NE(first.str().find("LOCAL,R5.0,ANG,11,0,"), std::string::npos);
  EXPECT_NE(first.str().find("SFE,8,1,PRES,1,R5.0\n"), std::string::npos);
  const Model read = read_deck_text(first.str(), "written.cdb").model;
  std::ostringstream second;
  write_cdb(read, second);
  EXPECT_EQ(first.str(), second.str());
  ASSERT_EQ(read.coupled_sets.size(), built.coupled_sets.size());
  for (const auto& [id, set] : built.coupled_sets) {
    EXPECT_EQ(read.coupled_sets.at(id).dof, set.dof);
    EXPECT_EQ(read.coupled_sets.at(id).nodes, set.nodes);
  }
  ASSERT_EQ(read.constraint_equations.size(), built.constraint_equations.size());
  for (const auto& [id, eq] : built.constraint_equations) {
    const ConstraintEquation& back = read.constraint_equations.at(id);
    EXPECT_EQ(back.constant, eq.constant);
    ASSERT_EQ(back.terms.size(), eq.terms.size());
    for (std::size_t k = 0; k < eq.terms.size(); ++k) {
      EXPECT_EQ(back.terms[k].dof, eq.terms[k].dof);
      EXPECT_EQ(back.terms[k].coefficient, eq.terms[k].coefficient);
    }
  }
  std::vector<int> slaves;
  for (const RigidRegion& region : read.rigid_regions) {
    EXPECT_EQ(region.master, 1000);
    EXPECT_TRUE(region.translations && region.rotations);
    slaves.insert(slaves.end(), region.slaves.begin(), region.slaves.end());
  }
  EXPECT_EQ(slaves, built.rigid_regions.front().slaves);
  ASSERT_TRUE(read.coordinate_systems.has(11));
  EXPECT_EQ(read.coordinate_systems.get(11).axes, built.coordinate_systems.get(11).axes);
  EXPECT_EQ(read.coordinate_systems.active, 0);
  EXPECT_EQ(read.elements.at(1).esys, 11);
  ASSERT_EQ(read.current.pressures.size(), built.current.pressures.size());
  for (const auto& [face, load] : built.current.pressures)
    EXPECT_EQ(read.current.pressures.at(face).values, load.values) << "element " << face.element;
}

TEST(CdbWrite, ReadBackSolvesBitwiseAsTheOriginal) {
  const auto original = testing::run_deck_text(
      "cdb_original", std::string(kCoupledModel) +
                          "CDWRITE,DB,'model',cdb\nFINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n");
  const std::filesystem::path archive = original.directory / "model.cdb";
  ASSERT_TRUE(std::filesystem::exists(archive));
  const auto again = testing::run_deck_text(
      "cdb_read_back", "/PREP7\nCDREAD,DB,'" + (original.directory / "model").string() +
                           "',cdb\nCDWRITE,DB,'again',cdb\nFINISH\n/SOLU\nANTYPE,STATIC\n"
                           "SOLVE\nFINISH\n");
  const auto text = [](const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(text(archive), text(again.directory / "again.cdb"));
  ASSERT_EQ(again.reader->node_ids(), original.reader->node_ids());
  double largest = 0.0;
  for (int id : original.reader->node_ids())
    for (const char* dof : {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"}) {
      const double v = original.reader->nodal_series(id, dof).back().second;
      EXPECT_EQ(again.reader->nodal_series(id, dof).back().second, v) << "node " << id << dof;
      largest = std::max(largest, std::abs(v));
    }
  EXPECT_GT(largest, 0.0);  // the loads act: the comparison is not of zeros
}

TEST(CdbRead, SurfaceLoadRecordForm) {
  const std::string deck =
      "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA,0.01\nN,1\nN,2,1\nN,3,1,1\nN,4,0,1\n"
      "E,1,2,3,4\nSFE,1,1,PRES,1,R5.0\n 1.00000000E+00 2.00000000E+00 3.00000000E+00 "
      "4.00000000E+00\nSFE,       1,     2,PRES, 0,R5.0\n  7.50000000    \nFINISH\n";
  const Model m = read_deck_text(deck, "sfe.cdb").model;
  EXPECT_EQ(m.current.pressures.at(FaceKey{1, 1}).values, (std::array<double, 4>{1, 2, 3, 4}));
  EXPECT_EQ(m.current.pressures.at(FaceKey{1, 2}).values,
            (std::array<double, 4>{7.5, 7.5, 7.5, 7.5}));
  std::string bad = deck;
  bad.replace(bad.find(" 1.00000000E+00"), 15, " 1.0x");
  try {
    read_deck_text(bad, "sfe_bad.cdb");
    FAIL() << "a values line with a letter was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sfe_bad.cdb:"), std::string::npos) << e.what();
  }
}

TEST(CdbRead, ConstraintEquationRecordsAreChecked) {
  const std::string nodes = "/PREP7\nN,1\nN,2,1\nN,3,2\n";
  const Model m = read_deck_text(nodes +
                                     "CE,R5.0,DEFI,       3,       4,  0.25    \n"
                                     "CE,R5.0,NODE,       1,UX  ,  1.0    ,       2,UY  , -2.0\n"
                                     "CE,R5.0,NODE,       3,ROTZ,  0.5\nFINISH\n",
                                 "ce.cdb")
                      .model;
  const ConstraintEquation& eq = m.constraint_equations.at(4);
  EXPECT_EQ(eq.constant, 0.25);
  ASSERT_EQ(eq.terms.size(), 3u);
  EXPECT_EQ(eq.terms[0].dof, (DofKey{1, Dof::UX}));
  EXPECT_EQ(eq.terms[1].coefficient, -2.0);
  EXPECT_EQ(eq.terms[2].dof, (DofKey{3, Dof::ROTZ}));
  const auto stop = [](const std::string& text) {
    try {
      read_deck_text(text, "ce.cdb");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(stop(nodes + "CE,R5.0,NODE,1,UX,1.0\n").find("ce.cdb:5: CE: CE,R5.0,NODE without"),
            std::string::npos);
  EXPECT_NE(stop(nodes + "CE,R5.0,DEFI,2,1,0\nCE,R5.0,NODE,1,UX,1\nCE,R5.0,DEFI,1,2,0\n")
                .find("ce.cdb:7: CE: CE,R5.0,DEFI before the last 1 term(s) of equation 1"),
            std::string::npos);
  EXPECT_NE(stop(nodes + "CP,R5.0,1,UX\n").find("ce.cdb:5: CP: the CDB record form"),
            std::string::npos);
  // An archive that ends before the terms its last DEFI announced stops at the CDREAD.
  const std::filesystem::path dir = testing::fresh_directory("cdb_short_equation");
  {
    std::ofstream out(dir / "short.cdb");
    out << "CE,R5.0,DEFI,3,1,0\nCE,R5.0,NODE,1,UX,1,2,UX,-1\n";
  }
  const std::string short_archive =
      stop(nodes + "CDREAD,DB,'" + (dir / "short").string() + "',cdb\n");
  EXPECT_NE(short_archive.find("ce.cdb:5: CDREAD: the archive"), std::string::npos)
      << short_archive;
  EXPECT_NE(short_archive.find("ends 1 term(s) short of constraint equation 1"), std::string::npos)
      << short_archive;
}

TEST(CdbWrite, RefusesWhatTheArchiveCannotHold) {
  const std::string base = "/PREP7\nET,1,LINK180\nN,1\nN,2,1\nE,1,2\n";
  const auto stop = [](const std::string& text) {
    try {
      testing::run_deck_text("cdb_refused", text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string table = stop(base +
                                 "*DIM,LOAD,TABLE,2,1,1,TIME\nLOAD(1,0)=0,1\nLOAD(1,1)=0,5\n"
                                 "F,2,FX,%LOAD%\nCDWRITE,DB,'t',cdb\n");
  EXPECT_NE(table.find("cdb_refused.inp:10: CDWRITE: table (%TABLE%) constraints and forces"),
            std::string::npos)
      << table;
  const std::string gap = stop(base + "M,1,UX\nM,2,UX\nGP,1,2,UX,1E3,0.1\nCDWRITE,DB,'t',cdb\n");
  EXPECT_NE(gap.find(":9: CDWRITE: gap conditions (GP, the first at "), std::string::npos) << gap;
}

TEST(CdbWrite, TemperaturesReadBack) {
  const Model built = read_deck_text(
                          "/PREP7\nET,1,LINK180\nN,1\nN,2,1\nE,1,2\nTREF,20\nTUNIF,50\n"
                          "BF,2,TEMP,100.5\nFINISH\n",
                          "temperatures.inp")
                          .model;
  std::ostringstream first;
  write_cdb(built, first);
  const Model read = read_deck_text(first.str(), "temperatures.cdb").model;
  EXPECT_EQ(read.current.reference_temperature, 20.0);
  EXPECT_EQ(read.current.uniform_temperature, std::optional<double>(50.0));
  EXPECT_EQ(read.current.node_temperatures, built.current.node_temperatures);
}

}  // namespace
}  // namespace impactfe::deck::test_cdb
