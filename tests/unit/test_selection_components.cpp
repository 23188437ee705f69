// Components (CM, CMSEL, CMDELE and components as node lists) on the model's selection, and the
// model get functions (NX, NODE(x,y,z), NNEAR, DISTND, CENTRX, NELEM, NSEL, NDNEXT) seeing it,
// run on decks read by a DeckReader. The select logic itself is tested with core/selection.
#include <gtest/gtest.h>

#include "core/errors.h"
#include "core/selection.h"
#include "deck/deck_context.h"
#include "deck/post_support.h"

namespace impactfe::deck::test_selection_components {
namespace {

std::vector<int> range(int first, int last) {
  std::vector<int> out;
  for (int i = first; i <= last; ++i) out.push_back(i);
  return out;
}

// core/selection (the modelling branch's): S/R/A/U/STAT/INVE/NONE/ALL, issue 9's select logic.
TEST(Selection, SelectReselectAddUnselectInvertNone) {
  const auto defined = range(1, 10);
  Selection s;
  EXPECT_EQ(s.selected_of(defined).size(), 10u);  // everything starts selected
  s.apply(SelectType::Select, defined, [](int id) { return id <= 6; });
  EXPECT_EQ(s.selected_of(defined), range(1, 6));
  s.apply(SelectType::Reselect, defined, [](int id) { return id % 2 == 0; });  // 1..6: evens
  EXPECT_EQ(s.selected_of(defined), (std::vector<int>{2, 4, 6}));
  s.apply(SelectType::Also, defined, [](int id) { return id == 9; });
  EXPECT_EQ(s.selected_of(defined), (std::vector<int>{2, 4, 6, 9}));
  s.apply(SelectType::Unselect, defined, [](int id) { return id == 4 || id == 5; });
  EXPECT_EQ(s.selected_of(defined), (std::vector<int>{2, 6, 9}));
  s.apply(SelectType::Stat, defined, [](int) { return true; });  // changes nothing
  EXPECT_EQ(s.selected_of(defined).size(), 3u);
  s.apply(SelectType::Invert, defined, [](int) { return false; });
  EXPECT_EQ(s.selected_of(defined), (std::vector<int>{1, 3, 4, 5, 7, 8, 10}));
  s.apply(SelectType::None, defined, [](int) { return true; });
  EXPECT_EQ(s.selected_of(defined).size(), 0u);
  s.apply(SelectType::All, defined, [](int) { return false; });
  EXPECT_EQ(s.selected_of(defined).size(), 10u);
  // An entity created after a selection is selected (MAPDL selects new entities).
  s.apply(SelectType::Select, defined, [](int id) { return id == 1; });
  EXPECT_TRUE(s.selected(11));
}

TEST(Selection, TypeLabels) {
  EXPECT_EQ(parse_select_type(""), SelectType::Select);
  EXPECT_EQ(parse_select_type("INVE"), SelectType::Invert);
  EXPECT_EQ(parse_select_type("NONE"), SelectType::None);
  EXPECT_FALSE(parse_select_type("X").has_value());
}

/// A deck read (not solved) up to its end, the reader kept for inspection.
struct ReadDeck {
  DeckOptions options;
  DeckReader reader{options, Dialect::Modern, "sel"};
  explicit ReadDeck(const std::string& text) { reader.run_text(text, "sel.inp"); }
};

const char* kLine =
    "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1.0\nMP,EX,1,1E6\n"
    "N,1,0\nN,2,1\nN,3,2\nN,4,3\nN,5,4\nE,1,2\nE,2,3\nE,3,4\nE,4,5\n";

TEST(Components, FrozenListsSelectedByCmsel) {
  ReadDeck d(std::string(kLine) +
             "NSEL,S,LOC,X,0,1.5\nCM,LEFT,NODE\nESEL,S,ELEM,,4\nCM,LAST,ELEM\n"
             "NSEL,S,LOC,X,3.5,4.5\nCM,RIGHT,NODE\nALLSEL\n"
             "NSEL,NONE\nCMSEL,S,LEFT\n");
  DeckReader& r = d.reader;
  ASSERT_EQ(r.model.components.size(), 3u);
  EXPECT_EQ(r.model.components.at("LEFT").ids, (std::vector<int>{1, 2}));
  EXPECT_EQ(r.model.components.at("LAST").entity, "ELEM");
  EXPECT_EQ(selected_nodes(r), (std::vector<int>{1, 2}));
  r.run_text("CMSEL,A,RIGHT\n", "sel.inp");
  EXPECT_EQ(selected_nodes(r), (std::vector<int>{1, 2, 5}));
  r.run_text("CMSEL,U,LEFT\n", "sel.inp");
  EXPECT_EQ(selected_nodes(r), (std::vector<int>{5}));
  // ALLSEL then reselect within the component; elements keep their own selection.
  r.run_text("ALLSEL\nCMSEL,S,LAST\n", "sel.inp");
  EXPECT_EQ(selected_elements(r), (std::vector<int>{4}));
  EXPECT_EQ(selected_nodes(r).size(), 5u);
  // A component name stands for its nodes in a node field (D here).
  r.run_text("D,LEFT,UX\n", "sel.inp");
  EXPECT_EQ(r.model.current.constraints.count(DofKey{1, Dof::UX}), 1u);
  EXPECT_EQ(r.model.current.constraints.count(DofKey{2, Dof::UX}), 1u);
  EXPECT_EQ(r.model.current.constraints.count(DofKey{3, Dof::UX}), 0u);
  // CMDELE removes it; selecting it afterwards is an error naming it.
  r.run_text("CMDELE,LEFT\n", "sel.inp");
  EXPECT_EQ(r.model.components.count("LEFT"), 0u);
  try {
    r.run_text("CMSEL,S,LEFT\n", "sel.inp");
    FAIL() << "CMSEL of a deleted component must fail";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("component 'LEFT' is not defined"), std::string::npos)
        << e.what();
  }
}

TEST(Components, EmptySelectionAndBadNamesAreErrors) {
  ReadDeck d(kLine);
  DeckReader& r = d.reader;
  EXPECT_THROW(r.run_text("NSEL,NONE\nCM,EMPTY,NODE\n", "sel.inp"), InputError);
  r.run_text("ALLSEL\n", "sel.inp");
  EXPECT_THROW(r.run_text("CM,1ABC,NODE\n", "sel.inp"), InputError);
  EXPECT_THROW(r.run_text("CM,ALL,NODE\n", "sel.inp"), InputError);
  EXPECT_THROW(r.run_text("CM,GOOD,WHAT\n", "sel.inp"), InputError);
  // D,ALL with nothing selected is an error, not a silent no-op.
  try {
    r.run_text("NSEL,NONE\nD,ALL,UX\n", "sel.inp");
    FAIL() << "D,ALL on an empty selection must fail";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sel.inp:"), std::string::npos) << e.what();
  }
}

TEST(GetFunctions, ModelFunctionsSeeTheSelection) {
  ReadDeck d(std::string(kLine) + "N,10,1.2,0.1\n");
  DeckReader& r = d.reader;
  Command c;
  c.name = "X";
  c.where = {"sel.inp", 1};
  auto f = [&](const char* expression) { return r.eval(c, expression); };
  EXPECT_DOUBLE_EQ(f("NX(3)"), 2.0);
  EXPECT_DOUBLE_EQ(f("NY(10)"), 0.1);
  EXPECT_DOUBLE_EQ(f("NODE(1.1,0,0)"), 2.0);  // nearest of the selected
  EXPECT_DOUBLE_EQ(f("NNEAR(2)"), 10.0);      // nearest other node
  EXPECT_DOUBLE_EQ(f("DISTND(1,5)"), 4.0);
  EXPECT_DOUBLE_EQ(f("CENTRX(2)"), 1.5);   // element 2 = nodes 2, 3
  EXPECT_DOUBLE_EQ(f("NELEM(3,2)"), 4.0);  // second node of element 3
  EXPECT_DOUBLE_EQ(f("NELEM(3,7)"), 0.0);  // beyond the node list
  EXPECT_DOUBLE_EQ(f("ENEARN(5)"), 4.0);
  r.run_text("NSEL,U,NODE,,2\nESEL,U,ELEM,,2\n", "sel.inp");
  EXPECT_DOUBLE_EQ(f("NODE(1.1,0,0)"), 10.0);  // 2 is unselected now
  EXPECT_DOUBLE_EQ(f("NSEL(2)"), -1.0);
  EXPECT_DOUBLE_EQ(f("NSEL(3)"), 1.0);
  EXPECT_DOUBLE_EQ(f("NSEL(99)"), 0.0);
  EXPECT_DOUBLE_EQ(f("NDNEXT(1)"), 3.0);
  EXPECT_DOUBLE_EQ(f("NDNEXT(10)"), 0.0);
  EXPECT_DOUBLE_EQ(f("ESEL(2)"), -1.0);
  EXPECT_DOUBLE_EQ(f("ELNEXT(1)"), 3.0);
  // In assignments and with a space before the parenthesis (issue 9).
  r.run_text("A=2\nB=0\nN1 = NODE (A/2,-B,0 )\n*GET,NC,NODE,0,COUNT\n", "sel.inp");
  EXPECT_DOUBLE_EQ(f("N1"), 10.0);  // (1,0,0): node 2 is unselected, 10 at (1.2,0.1) nearest
  EXPECT_DOUBLE_EQ(f("NC"), 5.0);   // 6 nodes, one unselected
  EXPECT_THROW(f("NOSUCH(1)"), InputError);
  EXPECT_THROW(f("NX(1,2)"), InputError);  // wrong arity
  EXPECT_THROW(f("NX(42)"), InputError);   // undefined node
}

}  // namespace
}  // namespace impactfe::deck::test_selection_components
