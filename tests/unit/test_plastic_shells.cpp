// Elastic-plastic SHELL181 (layered plane-stress J2): a plate cycled in uniaxial membrane
// tension-compression follows the closed-form BKIN loop, and a plate strip bent by end
// rotations yields first at M_y = σy t²/6 and flattens at the collapse moment of its section.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../support/bilinear_closed_form.h"
#include "../support/run_deck.h"

namespace impactfe {
namespace {

constexpr double kE = 200e3, kSy = 250.0, kEt = 20e3;

testing::DeckRun run_text(const std::string& tag, const std::string& text) {
  const auto dir = testing::fresh_directory(tag);
  const std::string deck = (dir / (tag + ".inp")).string();
  {
    std::ofstream out(deck);
    out << text;
  }
  return testing::run_deck_in(deck, dir);
}

double at(const std::vector<std::pair<double, double>>& series, double t) {
  for (const auto& [time, v] : series)
    if (std::abs(time - t) < 1e-9) return v;
  ADD_FAILURE() << "no value at t = " << t;
  return NAN;
}

TEST(PlasticShells, MembraneCycleFollowsTheBkinLoop) {
  // One SHELL181 quad 1 × 1, t = 0.1, pulled along X by D,UX on the edge x = 1; free to
  // contract in Y, rotations fixed: uniaxial plane stress, σx = ΣFX / t.
  const double t = 0.1, ey = kSy / kE;
  const auto path = testing::cyclic_strain_path(4.0 * ey, 0.45 * ey);
  std::ostringstream deck;
  deck << "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA," << t << "\nMP,EX,1," << kE
       << "\nMP,PRXY,1,0.3\nTB,PLAS,1,,,BKIN\nTBDATA,1," << kSy << "," << kEt
       << "\nN,1,0,0\nN,2,1,0\nN,3,1,1\nN,4,0,1\nE,1,2,3,4\nFINISH\n/SOLU\nANTYPE,STATIC\n"
          "CNVTOL,F,,1E-10\nD,ALL,UZ\nD,ALL,ROTX\nD,ALL,ROTY\nD,ALL,ROTZ\nD,1,UX\nD,4,UX\n"
          "D,1,UY\n";
  for (std::size_t k = 0; k < path.size(); ++k)
    deck << "TIME," << k + 1 << "\nD,2,UX," << path[k] << "\nD,3,UX," << path[k] << "\nSOLVE\n";
  deck << "FINISH\n";
  const auto run = run_text("shell_membrane_cycle", deck.str());
  const auto expected = testing::bilinear_closed_form(path, kE, kSy, kEt, true);
  const auto f2 = run.reader->nodal_series(2, "FX"), f3 = run.reader->nodal_series(3, "FX");
  double max_error = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const double sx = (at(f2, k + 1.0) + at(f3, k + 1.0)) / t;
    max_error = std::max(max_error, std::abs(sx - expected[k]));
  }
  // The reaction at a prescribed DOF is the internal force there: +σx t at the pulled edge.
  EXPECT_LT(max_error, 1e-6 * kSy);
  EXPECT_GT(at(run.reader->element_series(1, "EPEQ"), 1.0 * path.size()), 5.0 * ey);
}

TEST(PlasticShells, StripInBendingYieldsAtMyAndCollapsesAtTheSectionLimit) {
  // Strip L = 4, b = 1, t = 0.1 (4 SHELL181), elastic-perfectly plastic; end rotation θ = κL
  // imposed at x = L, x = 0 held against rigid motion only, so the curvature is uniform and the
  // strip bends anticlastically (free edges). Moment per width from the reactions MY at x = 0.
  // Elastic: m = E t³ κ / 12; first yield of the surface layer at m_y = σy t²/6
  // (θ_y = 2σy L/(E t)). The 5-point Gauss–Lobatto layers include the surfaces, so first yield is
  // exact; the fully plastic moment of the continuum is m_p = σy t²/4, and of the 5-layer rule
  // 2σy (t/2)² (0.1 + 49/90 √(3/7)) = 0.9128 m_p, which the strip must approach.
  const double t = 0.1, length = 4.0;
  const double theta_y = 2.0 * kSy * length / (kE * t);
  const std::vector<double> rotations = {0.9 * theta_y, 1.1 * theta_y, 10.0 * theta_y,
                                         40.0 * theta_y};
  std::ostringstream deck;
  deck << "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA," << t << "\nMP,EX,1," << kE
       << "\nMP,PRXY,1,0.3\nTB,BISO,1\nTBDATA,1," << kSy << ",0\n";
  for (int i = 0; i <= 4; ++i)
    deck << "N," << i + 1 << "," << i << ",0\nN," << i + 6 << "," << i << ",1\n";
  for (int i = 1; i <= 4; ++i)
    deck << "E," << i << "," << i + 1 << "," << i + 6 << "," << i + 5 << "\n";
  deck << "FINISH\n/SOLU\nANTYPE,STATIC\nCNVTOL,F,,1E-8\nNSUBST,4\nNEQIT,50\n"
          "D,1,UX\nD,1,UY\nD,1,UZ\nD,1,ROTY\nD,6,UX\nD,6,UZ\nD,6,ROTY\n";
  for (std::size_t k = 0; k < rotations.size(); ++k)
    deck << "TIME," << k + 1 << "\nD,5,ROTY," << -rotations[k] << "\nD,10,ROTY," << -rotations[k]
         << "\nSOLVE\n";
  deck << "FINISH\n";
  const auto run = run_text("shell_strip_bending", deck.str());
  const auto m1 = run.reader->nodal_series(1, "MY"), m6 = run.reader->nodal_series(6, "MY");
  auto moment = [&](double time) { return std::abs(at(m1, time) + at(m6, time)); };
  const double m_y = kSy * t * t / 6.0, m_p = kSy * t * t / 4.0;
  EXPECT_NEAR(moment(1.0), 0.9 * m_y, 1e-6 * m_y);  // elastic, exact for uniform curvature
  EXPECT_EQ(at(run.reader->element_series(2, "EPEQ"), 1.0), 0.0);
  EXPECT_GT(at(run.reader->element_series(2, "EPEQ"), 2.0), 0.0);
  const double rule_limit = 2.0 * kSy * 0.25 * t * t * (0.1 + 49.0 / 90.0 * std::sqrt(3.0 / 7.0));
  EXPECT_NEAR(rule_limit / m_p, 0.9128, 1e-4);
  // Beyond 10 θ_y the moment is within 2 % of the section's limit and never above it.
  EXPECT_GT(moment(3.0), 0.97 * rule_limit);
  EXPECT_NEAR(moment(4.0), rule_limit, 0.02 * rule_limit);
  EXPECT_LT(moment(4.0), m_p);
  RecordProperty("moment_ratio_40_theta_y", std::to_string(moment(4.0) / m_p));
}

}  // namespace
}  // namespace impactfe
