// Thesis example 3, helmet case (2) (chapter V.C, Figs. 5-3-x): superelement generation of the 72
// SHELL63 helmet to 9 UZ masters (helmet_segen.inp), use pass with the head bricks and the gaps
// (helmet_use.inp, 4x E,1,8 -> the only *.sub.h5 in the directory), compared with case (1)
// (helmet_full.inp) and with the rigid-helmet reference values of REFERENCE.md §3.
#include <gtest/gtest.h>

#include "../support/run_deck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "analysis/job_session.h"
#include "core/log.h"
#include "deck/deck_reader.h"
#include "io/superelement_file.h"
#include "results/results_file.h"

namespace impactfe::test_helmet_superelement {
namespace {

namespace fs = std::filesystem;
using Series = std::vector<std::pair<double, double>>;

const fs::path kDecks = fs::path(IMPACTFE_TEST_DECKS) / "thesis";
const int kMasterNodes[9] = {27, 29, 31, 41, 43, 45, 55, 57, 59};
constexpr int kGroundGap = 86;  // E,68,43 (TYPE 3, REAL 3): the last element of both decks

/// Runs a thesis deck in `dir` (shared by the generation and use passes) and prints its notes.
void run_deck(const std::string& deck, const fs::path& dir, const std::string& jobname) {
  const auto run = testing::run_deck_in((kDecks / deck).string(), dir, RunSettings{}, jobname);
  for (const auto& a : run.statistics.analyses)
    for (const auto& note : a.notes) std::printf("  [%s] %s\n", jobname.c_str(), note.c_str());
}

/// Value of a series at time t (exact grid match expected; NaN if absent).
double at(const Series& s, double t) {
  for (const auto& [time, value] : s)
    if (std::abs(time - t) <= 1e-9) return value;
  return std::nan("");
}

std::pair<double, double> minimum(const Series& s) {
  std::pair<double, double> best{0.0, 1e300};
  for (const auto& [t, v] : s)
    if (v < best.second) best = {t, v};
  return best;
}

/// First time at which a gap element reports status closed (STAT = 1 or 2).
double first_closure(const ResultsReader& r, int element) {
  for (const auto& [t, v] : r.element_series(element, "STAT"))
    if (v >= 0.5) return t;
  return std::nan("");
}

class HelmetSuperelement : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing::fresh_directory("helmet_superelement");
    run_deck("helmet_segen.inp", dir_, "helmet_segen");
    run_deck("helmet_use.inp", dir_, "helmet_use");
    run_deck("helmet_full.inp", dir_, "helmet_full");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path HelmetSuperelement::dir_;

TEST_F(HelmetSuperelement, GenerationWritesNineUzMastersWithTheHelmetMass) {
  const SuperelementData se = read_superelement((dir_ / "helmet_segen.sub.h5").string());
  ASSERT_EQ(se.n_masters(), 9);
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(se.masters[k].key.node, kMasterNodes[k]);
    EXPECT_EQ(se.masters[k].key.dof, Dof::UZ);
  }
  ASSERT_TRUE(se.mass.has_value());  // KAY(6) = 2 under KAN 7: K + M
  // The UZ masters carry a rigid Z translation: Σ g_Z = helmet mass 1.2355e-4 (REFERENCE §3).
  EXPECT_NEAR(se.unit_acceleration.col(2).sum(), 1.2355e-4, 0.001 * 1.2355e-4);
  EXPECT_NEAR(se.mass->sum(), se.unit_acceleration.col(2).sum(), 1e-10);
  ResultsReader r((dir_ / "helmet_segen.h5").string());
  ASSERT_EQ(r.analyses().size(), 1u);
  EXPECT_EQ(r.analyses()[0].kind, ResultsKind::Substructure);
  EXPECT_EQ(r.analyses()[0].numeric_attributes.at("n_masters"), 9.0);
}

TEST_F(HelmetSuperelement, CrownAndGapTimesMatchTheReference) {
  // REFERENCE.md §3 table (rigid-helmet idealisation, exact values) for both cases.
  const double h = 6.667e-5;  // Δt of the last load step
  for (const char* job : {"helmet_use", "helmet_full"}) {
    SCOPED_TRACE(job);
    ResultsReader r((dir_ / (std::string(job) + ".h5")).string());
    const double closes = first_closure(r, kGroundGap);
    double reopens = std::nan("");
    for (const auto& [t, v] : r.element_series(kGroundGap, "STAT"))
      if (t > closes && v < 0.5) {
        reopens = t;
        break;
      }
    // First impact: the crown minimum while the ground gap is closed the first time.
    Series first_impact;
    for (const auto& p : r.nodal_series(43, "UZ"))
      if (p.first >= closes && p.first <= reopens) first_impact.push_back(p);
    ASSERT_FALSE(first_impact.empty());
    const auto [t_min, u_min] = minimum(first_impact);
    double head = 1e300;
    for (int e = 77; e <= 85; ++e) head = std::min(head, first_closure(r, e));
    std::printf(
        "%s: ground gap closes %.6f (ref 0.071944), reopens %.6f (ref 0.073052); crown 43 min UZ "
        "first impact %.6f at %.6f (ref -1.00982 at 0.07250); head-helmet closes %.6f "
        "(ref 0.074283)\n",
        job, closes, reopens, u_min, t_min, head);
    EXPECT_NEAR(closes, 0.071944, h);
    EXPECT_NEAR(reopens, 0.073052, 2 * h);
    EXPECT_NEAR(u_min, -1.00982, 0.001);  // 0.1 % of the 1.0 in travel
    EXPECT_NEAR(t_min, 0.07250, h);
    EXPECT_NEAR(head, 0.074283, 2 * h);
  }
}

TEST_F(HelmetSuperelement, MasterHistoriesAgreeWithTheFullModel) {
  // REFERENCE.md §3: every master-DOF history of case (2) within 1 % of the peak response of
  // case (1); the difference is the dynamic condensation error and is printed.
  ResultsReader full((dir_ / "helmet_full.h5").string());
  ResultsReader use((dir_ / "helmet_use.h5").string());
  double worst_ratio = 0.0;
  for (int node : kMasterNodes) {
    const Series s1 = full.nodal_series(node, "UZ");
    const Series s2 = use.nodal_series(node, "UZ");
    ASSERT_FALSE(s1.empty());
    ASSERT_FALSE(s2.empty());
    double peak = 0.0, diff = 0.0, t_diff = 0.0;
    int compared = 0;
    for (const auto& [t, v1] : s1) {
      peak = std::max(peak, std::abs(v1));
      const double v2 = at(s2, t);
      if (std::isnan(v2)) continue;
      ++compared;
      if (std::abs(v2 - v1) > diff) {
        diff = std::abs(v2 - v1);
        t_diff = t;
      }
    }
    EXPECT_GT(compared, 150) << "node " << node;
    const double ratio = diff / peak;
    worst_ratio = std::max(worst_ratio, ratio);
    std::printf(
        "node %d UZ: peak |u| case 1 %.5f, max |case2 - case1| %.3e at t = %.6f (%.3f %%)\n", node,
        peak, diff, t_diff, 100.0 * ratio);
    EXPECT_LE(ratio, 0.01) << "node " << node << ": condensation error " << 100.0 * ratio << " %";
  }
  std::printf("worst master-DOF difference: %.3f %% of the case (1) peak\n", 100.0 * worst_ratio);
}

TEST_F(HelmetSuperelement, ExpansionPassGivesTheHelmetShellsOfTheFullModel) {
  // The modern expansion pass (EXPASS + SEEXP, spec §10.6) through the job runner: every helmet
  // node's displacement history inside the superelement equals the full model's (case (1))
  // within 1 % of that node's peak; masters are copied, slaves follow T_sm u_m plus the static
  // correction for the recorded ACEL.
  const fs::path deck = fs::path(IMPACTFE_TEST_DECKS) / "modern" / "helmet_seexp.inp";
  const auto run = testing::run_deck_in(deck.string(), dir_, RunSettings{}, "helmet_expanded");
  const ResultsReader& expanded = *run.reader;
  ResultsReader use((dir_ / "helmet_use.h5").string());
  ResultsReader full((dir_ / "helmet_full.h5").string());
  ASSERT_EQ(expanded.analyses().size(), 1u);
  EXPECT_EQ(expanded.analyses()[0].kind, ResultsKind::Expansion);
  const Series m_use = use.nodal_series(43, "UZ");
  const Series m_exp = expanded.nodal_series(43, "UZ");
  ASSERT_EQ(m_use.size(), m_exp.size());  // NUMEXP,ALL: every use-pass solution
  for (std::size_t k = 0; k < m_use.size(); ++k)
    EXPECT_NEAR(m_use[k].second, m_exp[k].second, 1e-12);

  double worst = 0.0;
  int worst_node = 0;
  for (int node = 19; node <= 67; ++node) {
    for (const char* lab : {"UX", "UY", "UZ"}) {
      const Series f = full.nodal_series(node, lab);
      const Series e = expanded.nodal_series(node, lab);
      ASSERT_FALSE(e.empty()) << "node " << node;
      double peak = 0.0;
      for (const auto& [t, v] : full.nodal_series(node, "UZ")) peak = std::max(peak, std::abs(v));
      double diff = 0.0;
      int compared = 0;
      for (const auto& [t, v] : e) {
        const double vf = at(f, t);
        if (std::isnan(vf)) continue;
        ++compared;
        diff = std::max(diff, std::abs(v - vf));
      }
      EXPECT_GT(compared, 150) << "node " << node << " " << lab;
      const double ratio = diff / peak;
      if (ratio > worst) {
        worst = ratio;
        worst_node = node;
      }
      EXPECT_LE(ratio, 0.01) << "node " << node << " " << lab << ": " << 100.0 * ratio << " %";
    }
  }
  std::printf(
      "expanded helmet vs full model: worst difference %.3f %% of the node's peak |UZ| "
      "(node %d)\n",
      100.0 * worst, worst_node);
  // Shell stresses exist at every expanded time and are non-zero once the helmet bends.
  const Series seqv = expanded.element_series(37, "SEQV_TOP");
  ASSERT_EQ(seqv.size(), m_use.size());
  double peak = 0.0;
  for (const auto& [t, v] : seqv) peak = std::max(peak, std::abs(v));
  std::printf("expanded shell element 37 peak SEQV_TOP %.4g\n", peak);
  EXPECT_GT(peak, 0.0);
}

TEST_F(HelmetSuperelement, ExpansionPassMustBeAJobOfItsOwn) {
  const std::string text =
      "/PREP7\nET,1,LINK8\nR,1,1\nMP,EX,1,1\nN,1\nN,2,1\nE,1,2\nD,1,ALL\nFINISH\n"
      "/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n/SOLU\nEXPASS,ON\nSEEXP,helmet_segen,helmet_use\n"
      "SOLVE\nFINISH\n";
  const fs::path mixed = dir_ / "mixed.inp";
  std::ofstream(mixed) << text;
  EXPECT_THROW(testing::run_deck_in(mixed.string(), dir_, RunSettings{}, "mixed"), InputError);
  const Job missing =
      read_deck_text("/SOLU\nEXPASS,ON\nSEEXP,nosuch,helmet_use\nSOLVE\n", "missing.inp");
  try {
    results_model(missing);
    FAIL() << "a missing superelement file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.inp:3: SEEXP"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace impactfe::test_helmet_superelement
