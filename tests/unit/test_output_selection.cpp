// OUTRES per item, frequency and component: which substeps and which nodes / elements an item
// is written for (later specifications win where they overlap), the element-item categories,
// the masking of a time point, and the settings a load step carries by value.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/model.h"
#include "core/output_control.h"
#include "results/output_selection.h"

namespace impactfe::test_output_selection {
namespace {

OutputControl control(int every) {
  OutputControl c;
  c.every = every;
  return c;
}

TEST(OutputSelection, UniformFrequencyWritesEveryNthAndTheLastSubstep) {
  const OutputControl c = control(3);
  for (int k = 0; k <= 10; ++k) {
    const bool expected = k == 0 || k % 3 == 0 || k == 10;
    EXPECT_EQ(output_selection(c, k, 10).any(), expected) << k;
    EXPECT_EQ(output_selection(c, k, 10)[OutputItem::NSOL].all(), expected) << k;
  }
  EXPECT_FALSE(output_selection(control(-1), 10, 10).any());  // NONE: not even the last
  EXPECT_TRUE(output_selection(control(0), 10, 10).any());    // LAST
  EXPECT_FALSE(output_selection(control(0), 9, 10).any());
}

TEST(OutputSelection, ItemsAndComponentsAccumulateLaterWinning) {
  OutputControl c = control(-1);  // OUTRES,ALL,NONE
  auto& nsol = c.items[static_cast<int>(OutputItem::NSOL)];
  nsol.push_back({5, "", {}});             // OUTRES,NSOL,5
  nsol.push_back({1, "TIP", {7, 8, 9}});   // OUTRES,NSOL,ALL,TIP
  nsol.push_back({-1, "MID", {5, 6, 7}});  // OUTRES,NSOL,NONE,MID (7 overlaps TIP: NONE)
  const OutputSelection at5 = output_selection(c, 5, 20);
  const IdSelection& s5 = at5[OutputItem::NSOL];
  for (int id : {1, 2, 4, 8, 9}) EXPECT_TRUE(s5.contains(id)) << id;
  for (int id : {5, 6, 7}) EXPECT_FALSE(s5.contains(id)) << id;
  EXPECT_TRUE(at5[OutputItem::STRS].none());
  const OutputSelection at3 = output_selection(c, 3, 20);
  const IdSelection& s3 = at3[OutputItem::NSOL];
  for (int id : {8, 9}) EXPECT_TRUE(s3.contains(id)) << id;
  for (int id : {1, 5, 7}) EXPECT_FALSE(s3.contains(id)) << id;
  EXPECT_FALSE(output_selection(c, 3, 20)[OutputItem::VSOL].contains(8));
}

// The bound the results file sizes its time blocks with (block_rows_for): never below the
// substeps output_selection stores, and equal to them for one frequency.
TEST(OutputSelection, StoredSubstepsAtMostCountsTheSubstepsThatStore) {
  OutputControl mixed = control(-1);  // OUTRES,ALL,NONE; NSOL every 4th; STRS every 6th of TIP
  mixed.items[static_cast<int>(OutputItem::NSOL)].push_back({4, "", {}});
  mixed.items[static_cast<int>(OutputItem::STRS)].push_back({6, "TIP", {3}});
  OutputControl none = control(-1);
  none.items[static_cast<int>(OutputItem::RSOL)].push_back({-1, "", {}});
  struct Case {
    OutputControl control;
    bool exact;  // one frequency: the bound is the count
  };
  const std::vector<Case> cases{{control(-1), true}, {control(0), true}, {control(1), true},
                                {control(3), true},  {control(7), true}, {control(20), true},
                                {control(50), true}, {mixed, false},     {none, true}};
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (int n : {1, 2, 7, 20, 24, 200}) {
      long long stored = 0;
      for (int k = 1; k <= n; ++k) stored += output_selection(cases[i].control, k, n).any();
      const long long bound = stored_substeps_at_most(cases[i].control, n);
      EXPECT_GE(bound, stored) << "case " << i << ", " << n << " substeps";
      if (cases[i].exact) EXPECT_EQ(bound, stored) << "case " << i << ", " << n << " substeps";
    }
  EXPECT_EQ(stored_substeps_at_most(control(10), 200), 20);
  EXPECT_EQ(stored_substeps_at_most(mixed, 24), 6 + 4 - 1);  // 4, 8, .., 24 and 6, 12, 18
}

TEST(OutputSelection, ElementItemCategories) {
  for (const char* s : {"SAXL", "SX", "SXY_TOP", "SEQV", "SEQV_BOT", "S1", "SINT", "SZ"})
    EXPECT_EQ(element_item_category(s), OutputItem::STRS) << s;
  EXPECT_EQ(element_item_category("EPEL"), OutputItem::EPEL);
  for (const char* s : {"FORC", "F1", "STAT", "SLIDE", "STRETCH", "TX", "MXY", "LENGTH", "DELTA"})
    EXPECT_EQ(element_item_category(s), OutputItem::MISC) << s;
}

TEST(OutputSelection, MaskingSetsWhatIsNotWrittenToNaN) {
  OutputControl c = control(1);
  c.items[static_cast<int>(OutputItem::VSOL)] = {{-1, "", {}}};
  c.items[static_cast<int>(OutputItem::NSOL)] = {{1, "", {}}, {-1, "A", {20}}};
  c.items[static_cast<int>(OutputItem::STRS)] = {{-1, "", {}}, {1, "E", {3}}};
  TimePoint p;
  p.displacement = Eigen::MatrixXd::Ones(3, 6);
  p.velocity = Eigen::MatrixXd::Ones(3, 6);
  ElementResultTable t;
  t.element_ids = {3, 4};
  t.item_names = {"FORC", "SAXL", "EPEL"};
  t.values = Eigen::MatrixXd::Ones(2, 3);
  p.element_results["Spar"] = t;
  apply_output_selection(output_selection(c, 1, 2), {10, 20, 30}, p);
  EXPECT_EQ(p.velocity.size(), 0);  // not written at all: absent
  EXPECT_TRUE(std::isnan(p.displacement(1, 0)));
  EXPECT_EQ(p.displacement(0, 0), 1.0);
  EXPECT_EQ(p.displacement(2, 5), 1.0);
  const auto& v = p.element_results.at("Spar").values;
  EXPECT_EQ(v(0, 1), 1.0);           // element 3 SAXL
  EXPECT_TRUE(std::isnan(v(1, 1)));  // element 4 SAXL
  EXPECT_EQ(v(1, 0), 1.0);           // FORC, EPEL: every element
  EXPECT_EQ(v(1, 2), 1.0);
}

TEST(OutputControl, ALoadStepCarriesItsPerItemSettings) {
  EXPECT_TRUE(control(4).uniform());
  LoadStep first;
  first.output = control(-1);
  first.output.items[static_cast<int>(OutputItem::RSOL)] = {{2, "", {}}};
  EXPECT_FALSE(first.output.uniform());
  LoadStep second = first;  // a copy keeps the settings, independent of the original
  first.output.items[static_cast<int>(OutputItem::RSOL)].clear();
  EXPECT_TRUE(first.output.uniform());
  EXPECT_EQ(second.output.every, -1);
  ASSERT_EQ(second.output.items[static_cast<int>(OutputItem::RSOL)].size(), 1u);
  EXPECT_EQ(second.output.items[static_cast<int>(OutputItem::RSOL)][0].every, 2);
  EXPECT_FALSE(output_selection(second.output, 1, 4)[OutputItem::NSOL].all());
  EXPECT_FALSE(output_selection(second.output, 1, 4)[OutputItem::RSOL].all());
  EXPECT_TRUE(output_selection(second.output, 2, 4)[OutputItem::RSOL].all());
}

}  // namespace
}  // namespace impactfe::test_output_selection
