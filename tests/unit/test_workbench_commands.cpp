// The commands a Workbench input file (ds.dat) writes around its SOLVE (docs/deck_reader.md):
// hidden components (a leading underscore), DMPOPTION, CNTR and NLDIAG (carried out without
// contact elements, refused with them), OUTRES,EANGL, *GET ACTIVE INT and the distributed
// statistics COMB and DLBR, CEWRITE's CE lines and /XML's parameter file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "deck/deck_reader.h"

namespace impactfe::test_workbench_commands {
namespace {

/// A cube of one SOLID185 fixed at x = 0 (through a hidden component) and pulled at x = 1.
const char* kCube = R"(/PREP7
ET,1,185
MP,EX,1,200
MP,NUXY,1,0.3
BLOCK,0,1,0,1,0,1
ESIZE,1
VMESH,1
NSEL,S,LOC,X,0
CM,_FIXEDSU,NODE
NSEL,ALL
CMSEL,S,_FIXEDSU
D,ALL,ALL
NSEL,ALL
FINISH
)";

/// The message a deck stops with ("" when it reads to the end).
std::string stop_of(const std::string& text) {
  try {
    DeckOptions o;
    std::ostringstream sink;
    o.output = &sink;
    read_deck_text(text, "wb.inp", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(WorkbenchCommands, HiddenComponentsStartWithAnUnderscore) {
  const Job job = read_deck_text(kCube, "wb.inp");
  ASSERT_TRUE(job.model.components.count("_FIXEDSU"));
  EXPECT_EQ(job.model.components.at("_FIXEDSU").ids.size(), 4u);
  EXPECT_NE(stop_of("/PREP7\nCM,1ABC,NODE\n").find("not a valid component name"),
            std::string::npos);
}

TEST(WorkbenchCommands, DistributedFileOptionsAreCheckedAndNeedNoCombining) {
  const std::string solu = std::string(kCube) + "/SOLU\n";
  EXPECT_EQ(stop_of(solu + "DMPOPTION,EMAT,NO\nDMPOPTION,ESAV,NO\nDMPOPTION,RST,YES\n"), "");
  EXPECT_NE(stop_of(solu + "DMPOPTION,XYZ,NO\n").find("FileType 'XYZ'"), std::string::npos);
  EXPECT_NE(stop_of(solu + "DMPOPTION,RST,MAYBE\n").find("Combine 'MAYBE'"), std::string::npos);
}

TEST(WorkbenchCommands, ContactDiagnosticsWithoutContactElementsAndRefusedWithThem) {
  const std::string solu = std::string(kCube) + "/SOLU\n";
  EXPECT_EQ(stop_of(solu + "CNTR,PRINT,1\nNLDIAG,CONT,ITER\nNLDIAG,NRRE,OFF\n"), "");
  EXPECT_NE(stop_of(solu + "NLDIAG,NRRE,ON\n").find("not written"), std::string::npos);
  EXPECT_NE(stop_of(solu + "CNTR,FOO,1\n").find("Option 'FOO'"), std::string::npos);
  // The same commands with a contact pair are refused: its report would be missing.
  const std::string contact = std::string(kCube) + "/PREP7\nET,2,174\nET,3,170\n/SOLU\n";
  EXPECT_NE(stop_of(contact + "CNTR,PRINT,1\n").find("contact pair reports are not written"),
            std::string::npos);
  EXPECT_NE(stop_of(contact + "NLDIAG,CONT,ITER\n").find("Jobname.cnd"), std::string::npos);
  EXPECT_EQ(stop_of(contact + "CNTR,OUT,NO\nNLDIAG,CONT,OFF\n"), "");
}

TEST(WorkbenchCommands, OutresElementAnglesAndTheInteractiveKey) {
  const Job job = read_deck_text(std::string(kCube) +
                                     "/SOLU\nOUTRES,EANGL,ALL\n"
                                     "*GET,ANSINTER_,ACTIVE,,INT\n",
                                 "wb.inp");
  ASSERT_TRUE(job.model.components.count("_FIXEDSU"));
  EXPECT_NE(stop_of(std::string(kCube) + "/SOLU\nOUTRES,EANGLE,ALL\n").find("unknown Item"),
            std::string::npos);
}

TEST(WorkbenchCommands, StatisticsAfterSolveCewriteAndXml) {
  const auto dir = testing::fresh_directory("workbench_commands");
  const auto deck = dir / "wb.inp";
  // CEWRITE writes the equations of the moment (CEDELE then removes them before the SOLVE).
  std::ofstream(deck) << kCube << R"(/PREP7
CE,7,0.5,1,UX,1.0,2,UY,-2.0,3,UZ,0.25
CE,7,0.5,4,UX,3.0
CEWRITE,file,ce
CEWRITE,mpc,ce,,INTE
CEDELE,ALL
FINISH
/SOLU
ANTYPE,0
NSEL,S,LOC,X,1
CM,_DISPNONZEROUX,NODE
F,ALL,FX,10
NSEL,ALL
*GET,ANSINTER_,ACTIVE,,INT
SOLVE
FINISH
/POST1
*GET,_dlbratio,ACTIVE,0,SOLU,DLBR
*GET,_combtime,ACTIVE,0,SOLU,COMB
XMLO,ENCODING,UTF-8
XMLO,PARM
/XML,parm,xml
FINISH
)";
  const auto run = testing::run_deck_in(deck.string(), dir);
  const std::string ce = read_file(dir / "file.ce");
  EXPECT_NE(ce.find("CE,7,0.5,1,UX,1,2,UY,-2,3,UZ,0.25\nCE,7,0.5,4,UX,3\n"), std::string::npos)
      << ce;
  const std::string mpc = read_file(dir / "mpc.ce");
  EXPECT_EQ(mpc.find("CE,"), std::string::npos) << mpc;
  const std::string xml = read_file(dir / "parm.xml");
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<parameters>\n", 0), 0u) << xml;
  EXPECT_NE(xml.find("<parameter name=\"ANSINTER_\" type=\"number\">0</parameter>"),
            std::string::npos);
  EXPECT_NE(xml.find("<parameter name=\"_DLBRATIO\" type=\"number\">1</parameter>"),
            std::string::npos);
  EXPECT_NE(xml.find("<parameter name=\"_COMBTIME\" type=\"number\">0</parameter>"),
            std::string::npos);
  EXPECT_TRUE(xml.ends_with("</parameters>\n"));
}

}  // namespace
}  // namespace impactfe::test_workbench_commands
