// Parameters named like labels (issue 46): MAPDL accepts a parameter named UZ or MZ (its
// Programmer's Reference only advises against such names) and substitutes a numeric parameter
// where a number is expected, never in a label field. Each row defines the parameter and uses its
// name both ways in one command where it can; the check reads what the command did.
#include <gtest/gtest.h>

#include <functional>
#include <sstream>

#include "deck/deck_context.h"
#include "deck/expression.h"

namespace test_label_parameters {

using namespace impactfe;
using namespace impactfe::deck;

namespace {

struct Session {
  std::ostringstream out;
  DeckOptions options;
  DeckReader reader;
  Session() : options(make_options(out)), reader(options, Dialect::Modern, "mem") {}
  static DeckOptions make_options(std::ostringstream& o) {
    DeckOptions d;
    d.output = &o;
    return d;
  }
  double num(const std::string& expr) { return evaluate(expr, reader.params); }
};

// Node 1 at z = 3, node 2 at x = 7: a coordinate read through a label differs from the
// parameter's value in every row.
constexpr const char* kPrelude = "/PREP7\nET,1,BEAM188\nN,1,0,0,3\nN,2,7,0,0\n";

struct Row {
  const char* what;
  const char* deck;
  std::function<void(Session&)> check;
};

}  // namespace

TEST(LabelParameters, LabelFieldsKeepTheirLabelsNumericFieldsUseTheParameter) {
  const std::vector<Row> rows = {
      {"D: Lab is the label UZ, VALUE the parameter", "UZ = 0.25\nD,1,UZ,UZ\n",
       [](Session& s) {
         const auto& d = s.reader.model.current.constraints;
         ASSERT_EQ(d.size(), 1u);
         EXPECT_DOUBLE_EQ(d.at(DofKey{1, Dof::UZ}), 0.25);
       }},
      {"D: extra labels Lab2.. are labels too", "ROTX = 2\nD,2,ROTX,ROTX,,,,UY\n",
       [](Session& s) {
         const auto& d = s.reader.model.current.constraints;
         ASSERT_EQ(d.size(), 2u);
         EXPECT_DOUBLE_EQ(d.at(DofKey{2, Dof::ROTX}), 2.0);
         EXPECT_DOUBLE_EQ(d.at(DofKey{2, Dof::UY}), 2.0);
       }},
      {"F: Lab is the moment label MZ, VALUE the parameter", "MZ = 40\nF,2,MZ,MZ\n",
       [](Session& s) {
         const auto& f = s.reader.model.current.forces;
         ASSERT_EQ(f.size(), 1u);
         EXPECT_DOUBLE_EQ(f.at(DofKey{2, Dof::ROTZ}), 40.0);
       }},
      {"*GET: the item component Z is a label", "Z = 99\n*GET,P,NODE,1,LOC,Z\n",
       [](Session& s) { EXPECT_DOUBLE_EQ(s.num("P"), 3.0); }},
      {"*GET into a parameter named like a force label (vm70)", "*GET,MZ,NODE,2,LOC,X\nQ = 2*MZ\n",
       [](Session& s) { EXPECT_DOUBLE_EQ(s.num("Q"), 14.0); }},
      {"NSEL: Comp X is a label, VMIN the parameter",
       "X = 7\nNSEL,S,LOC,X,X\n*GET,N,NODE,0,COUNT\n*GET,P,NODE,0,NUM,MIN\n",
       [](Session& s) {
         EXPECT_DOUBLE_EQ(s.num("N"), 1.0);
         EXPECT_DOUBLE_EQ(s.num("P"), 2.0);
       }},
      {"ET: the element name is a label", "BEAM188 = 3\nET,2,BEAM188\n",
       [](Session& s) { EXPECT_EQ(s.reader.model.element_types.at(2).ansys_name, "BEAM188"); }},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.what);
    Session s;
    s.reader.run_text(std::string(kPrelude) + row.deck, "mem.inp");
    row.check(s);
  }
}

TEST(LabelParameters, ScalarParameterAndGetFunctionOfTheSameName) {
  // NX = 5 stored, then NX(2) is still the get function (x of node 2 = 7).
  Session s;
  s.reader.run_text(std::string(kPrelude) + "NX = 5\nP = NX(2) + NX\n", "mem.inp");
  EXPECT_DOUBLE_EQ(s.num("P"), 12.0);
}

TEST(LabelParameters, ConvenienceLabelsAndFunctionsStayRefused) {
  for (const char* deck : {"ALL = 1\n", "ON = 1\n", "SIN = 1\n", "*GET,OFF,NODE,1,LOC,X\n"}) {
    SCOPED_TRACE(deck);
    Session s;
    try {
      s.reader.run_text(std::string(kPrelude) + deck, "mem.inp");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cannot be a parameter"), std::string::npos);
    }
  }
}

}  // namespace test_label_parameters
