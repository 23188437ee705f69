// The single-point response spectrum analysis through a deck (ANTYPE,SPECTR after ANTYPE,MODAL):
// a two-DOF spring-mass chain on a moving base, worked out by hand from its modes — the mode
// coefficient, the SRSS of the modes used with the missing mass response of the mode left out,
// what *GET,MODE,n,MCOEF reads, and the refusals of the spectra not supported.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "results/result_sets.h"

namespace test_spectrum_deck {

using namespace impactfe;
using impactfe::testing::run_deck_text;

namespace {

// Base node 1 − k1 − node 2 (m1) − k2 − node 3 (m2), along X (COMBIN40 with its mass at node I).
constexpr double k1 = 42832.0, k2 = 32416.0, m1 = 0.5, m2 = 1.0;
constexpr double sa = 150.0, zpa = 40.0;

std::string deck(const std::string& spectrum) {
  return R"(/PREP7
ET,1,COMBIN40
R,1,42832.,,0.50
R,2,32416.,,1.0
N,1
N,2,1
N,3,2
E,2,1
REAL,2
E,3,2
D,1,UX
FINISH
/SOLU
ANTYPE,MODAL
MODOPT,LANB,2
MXPAND,2,,,YES
SOLVE
FINISH
/SOLU
ANTYPE,SPECTR
)" + spectrum +
         R"(
SOLVE
*GET,MC1,MODE,1,MCOEF
*GET,PF1,MODE,1,PFACT
FINISH
)";
}

}  // namespace

TEST(SpectrumDeck, SrssWithMissingMassAgreesWithTheHandSolution) {
  const auto run = run_deck_text("spectrum_two_dof", deck(R"(SPOPT,SPRS,1
SED,1
SVTYP,2
FREQ,1,1000
SV,0.02,150,150
DMPRAT,0.02
SRSS,0.001,DISP
MMASS,ON,40)"));
  // The hand solution: mass-normalised modes of K φ = ω² M φ; mode 1 alone is used (NMODE 1).
  Eigen::Matrix2d k, m;
  k << k1 + k2, -k2, -k2, k2;
  m << m1, 0.0, 0.0, m2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(k, m);
  const Eigen::Vector2d phi1 = eig.eigenvectors().col(0);
  const double w1 = std::sqrt(eig.eigenvalues()(0));
  const double gamma1 = phi1.dot(m * Eigen::Vector2d::Ones());
  const double a1 = sa * gamma1 / (w1 * w1);
  // Missing mass: K u = S0 M (D − γ1 φ1).
  const Eigen::Vector2d um = k.ldlt().solve(zpa * m * (Eigen::Vector2d::Ones() - gamma1 * phi1));

  const auto analyses = run.reader->analyses();
  const auto& spectrum = analyses.back();
  ASSERT_EQ(spectrum.kind, ResultsKind::Spectrum);
  EXPECT_NEAR(std::abs(spectrum.numeric_attributes.at("mode_coefficient_1")), std::abs(a1),
              1e-8 * std::abs(a1));
  EXPECT_NEAR(std::abs(spectrum.numeric_attributes.at("participation_factor_1")), std::abs(gamma1),
              1e-8 * std::abs(gamma1));
  EXPECT_EQ(spectrum.numeric_attributes.count("mode_coefficient_2"), 0u);  // NMODE 1
  // Point 0: the combined response; point 1 (load step 2): the missing mass response.
  const TimePoint combined = run.reader->time_point(spectrum.index, 0);
  const TimePoint missing = run.reader->time_point(spectrum.index, 1);
  EXPECT_EQ(missing.load_step, 2);
  for (int node = 2; node <= 3; ++node) {
    const int row = node - 1;  // rows in ascending node id: 1, 2, 3
    const double modal = a1 * phi1(node - 2);
    EXPECT_NEAR(missing.displacement(row, 0), um(node - 2), 1e-8 * std::abs(um(node - 2)));
    const double expected = std::hypot(modal, um(node - 2));
    EXPECT_NEAR(combined.displacement(row, 0), expected, 1e-8 * expected) << "node " << node;
  }
  EXPECT_NEAR(combined.displacement(0, 0), 0.0, 1e-14);  // the base: relative displacement 0
}

TEST(SpectrumDeck, ModalElementResultsAreReadWithTheModesSet) {
  // MXPAND Elcalc YES: POST1's set of mode 1 holds the spring forces of the mode shape, e.g. the
  // base spring's k1 φ1(node 2) (as stored: mass-normalised).
  const auto run = run_deck_text("spectrum_mode_elements", deck(R"(SPOPT,SPRS
SED,1
SVTYP,3
FREQ,1,1000
SV,,0.1,0.1)"));
  Eigen::Matrix2d k, m;
  k << k1 + k2, -k2, -k2, k2;
  m << m1, 0.0, 0.0, m2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(k, m);
  const double force = k1 * std::abs(eig.eigenvectors()(0, 0));
  const auto sets = result_sets(*run.reader);
  ASSERT_GE(sets.size(), 2u);
  ASSERT_EQ(sets[0].mode, 1);
  const SetData data = read_set(*run.reader, sets[0]);
  ASSERT_FALSE(data.point.element_results.empty());
  bool found = false;
  for (const auto& [family, table] : data.point.element_results)
    for (Eigen::Index row = 0; row < table.values.rows(); ++row)
      if (table.element_ids[static_cast<std::size_t>(row)] == 1)
        for (Eigen::Index col = 0; col < table.values.cols(); ++col)
          found |= std::abs(std::abs(table.values(row, col)) - force) < 1e-8 * force;
  EXPECT_TRUE(found) << "no item of element 1 is k1 |phi1(2)| = " << force;
  // Without a combination command the spectrum analysis stores no response (SVTYP 3:
  // Ai = Su γi).
  const auto spectrum = run.reader->analyses().back();  // a copy: analyses() is a temporary
  EXPECT_EQ(spectrum.n_time_points, 0);
  const double gamma1 = eig.eigenvectors().col(0).dot(m * Eigen::Vector2d::Ones());
  EXPECT_NEAR(std::abs(spectrum.numeric_attributes.at("mode_coefficient_1")),
              0.1 * std::abs(gamma1), 1e-9);
}

TEST(SpectrumDeck, RefusesTheSpectraItDoesNotCompute) {
  for (const char* text : {"SPOPT,PSD,2", "SPOPT,SPRS\nSVTYP,1", "SPOPT,SPRS\nSED,,,,BASE"}) {
    try {
      run_deck_text("spectrum_refused", deck(text));
      ADD_FAILURE() << text << " was accepted";
    } catch (const LocatedError& e) {
      EXPECT_GT(e.where().line, 0) << text << ": " << e.what();
    }
  }
}

}  // namespace test_spectrum_deck
