// CDB archives: the Fortran formats of the blocks, the lexer handing a block's records to its
// command, NBLOCK/EBLOCK/CMBLOCK/RLBLOCK read by column, and CDWRITE,DB read back by CDREAD to
// the same model and the same file.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

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

}  // namespace
}  // namespace impactfe::deck::test_cdb
