// J2 plasticity material point (src/materials/j2_plasticity): uniaxial hysteresis loops against
// the closed form, the MISO curve, the consistent tangents of the three variants against finite
// differences, and the 3-D / plane-stress returns under uniaxial stress against the 1-D law.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/bilinear_closed_form.h"
#include "materials/j2_plasticity.h"

namespace impactfe::test_j2_plasticity {
namespace {

constexpr double kE = 200e3, kNu = 0.3, kSy = 250.0, kEt = 20e3;

std::vector<double> cyclic_path(double a, double h) {
  return testing::cyclic_strain_path(a, h);
}

void check_loop(const J2Plasticity& law, bool kinematic, double step) {
  const double ey = kSy / kE;
  const auto path = cyclic_path(4.0 * ey, step);
  const auto expected = testing::bilinear_closed_form(path, kE, kSy, kEt, kinematic);
  UniaxialPlasticState state;
  double max_error = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    UniaxialPlasticState next;
    const UniaxialResponse r = law.uniaxial(state, path[i], &next);
    max_error = std::max(max_error, std::abs(r.stress - expected[i]));
    state = next;
  }
  // Radial return is exact for linear hardening in 1-D at any step size.
  EXPECT_LT(max_error, 1e-9 * kSy) << "step " << step;
  EXPECT_GT(state.alpha, 10.0 * ey);  // the loops did yield repeatedly
}

TEST(J2Plasticity, BisoHysteresisLoopEqualsClosedForm) {
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, false);
  for (double step : {1e-5, 3.7e-4, 2e-3}) check_loop(law, false, step);
}

TEST(J2Plasticity, BkinHysteresisLoopEqualsClosedForm) {
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, true);
  for (double step : {1e-5, 3.7e-4, 2e-3}) check_loop(law, true, step);
}

TEST(J2Plasticity, BkinReverseYieldAtTwiceYieldStressBelow) {
  // Bauschinger effect: after loading to σ1, reverse yield at σ1 − 2σy (isotropic: at −σ1).
  const auto kin = J2Plasticity::bilinear(kE, kNu, kSy, kEt, true);
  UniaxialPlasticState s, next;
  kin.uniaxial(s, 0.01, &next);
  const double s1 = next.stress;
  EXPECT_NEAR(s1, kSy + kEt * (0.01 - kSy / kE), 1e-9 * kSy);
  const double e_rev = 0.01 - (2.0 * kSy - 1e-6) / kE;  // just inside the elastic range
  EXPECT_FALSE(kin.uniaxial(next, e_rev, nullptr).yielding);
  EXPECT_TRUE(kin.uniaxial(next, e_rev - 1e-8, nullptr).yielding);
}

TEST(J2Plasticity, MisoFollowsTheCurveAndIsFlatBeyondIt) {
  const std::vector<std::pair<double, double>> curve = {
      {0.0, 250.0}, {0.002, 300.0}, {0.01, 360.0}, {0.05, 400.0}};
  const auto law = J2Plasticity::multilinear(kE, kNu, curve);
  // Loading in uneven steps to points on the curve: σ(ε) with ε = ε_p + σ/E.
  UniaxialPlasticState state;
  double checked = 0;
  for (double ep = 0.0005; ep < 0.08; ep += 0.0031) {
    double expected = 400.0;
    for (std::size_t j = 0; j + 1 < curve.size(); ++j)
      if (ep <= curve[j + 1].first) {
        expected = curve[j].second + (curve[j + 1].second - curve[j].second) /
                                         (curve[j + 1].first - curve[j].first) *
                                         (ep - curve[j].first);
        break;
      }
    UniaxialPlasticState next;
    const auto r = law.uniaxial(state, ep + expected / kE, &next);
    EXPECT_NEAR(r.stress, expected, 1e-9 * kSy) << "ep " << ep;
    EXPECT_NEAR(next.alpha, ep, 1e-12) << "ep " << ep;
    state = next;
    ++checked;
  }
  EXPECT_GT(checked, 20);
  // Unloading is elastic with E, reverse yield at −σ (isotropic).
  const double s = state.stress;
  const auto r = law.uniaxial(state, state.plastic_strain + (s - 2.0 * s + 1e-6) / kE, nullptr);
  EXPECT_FALSE(r.yielding);
  EXPECT_NEAR(r.tangent, kE, 1e-9 * kE);
}

TEST(J2Plasticity, UniaxialTangentMatchesFiniteDifferences) {
  const std::vector<J2Plasticity> laws = {
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, false),
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, true),
      J2Plasticity::multilinear(kE, kNu, {{0.0, 250.0}, {0.002, 300.0}, {0.01, 360.0}})};
  for (const auto& law : laws) {
    UniaxialPlasticState committed;
    law.uniaxial(UniaxialPlasticState{}, 0.004, &committed);  // a plastic history
    for (double e : {0.0041, 0.009, -0.003, 0.0035}) {
      const auto r = law.uniaxial(committed, e, nullptr);
      const double h = 1e-7;
      const double fd = (law.uniaxial(committed, e + h, nullptr).stress -
                         law.uniaxial(committed, e - h, nullptr).stress) /
                        (2.0 * h);
      EXPECT_NEAR(r.tangent, fd, 1e-6 * kE) << "strain " << e;
    }
  }
}

Vector6d strain6(double a, double b, double c, double d, double e, double f) {
  Vector6d v;
  v << a, b, c, d, e, f;
  return v;
}

TEST(J2Plasticity, SolidTangentMatchesFiniteDifferences) {
  const std::vector<J2Plasticity> laws = {
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, false),
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, true),
      J2Plasticity::bilinear(kE, kNu, kSy, 0.0, false),  // perfectly plastic
      J2Plasticity::multilinear(kE, kNu, {{0.0, 250.0}, {0.002, 300.0}, {0.02, 360.0}})};
  const Vector6d first = strain6(0.003, -0.001, 0.0005, 0.002, -0.0007, 0.001);
  const Vector6d second = strain6(0.0045, -0.0025, 0.0012, 0.0031, 0.0004, -0.0008);
  for (const auto& law : laws) {
    PlasticState committed;
    ASSERT_TRUE(law.solid(PlasticState{}, first, &committed).yielding);
    const auto r = law.solid(committed, second, nullptr);
    ASSERT_TRUE(r.yielding);
    Matrix6d fd;
    const double h = 1e-8;
    for (int j = 0; j < 6; ++j) {
      Vector6d ep = second, em = second;
      ep(j) += h;
      em(j) -= h;
      fd.col(j) =
          (law.solid(committed, ep, nullptr).stress - law.solid(committed, em, nullptr).stress) /
          (2.0 * h);
    }
    EXPECT_LT((r.tangent - fd).norm(), 1e-6 * r.tangent.norm()) << r.tangent << "\n\n" << fd;
    EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), 1e-10 * r.tangent.norm());
    // The returned stress lies on the yield surface k(α).
    PlasticState next;
    law.solid(committed, second, &next);
    EXPECT_NEAR(von_mises(next.stress - next.back_stress), law.flow_stress(next.alpha), 1e-9 * kSy);
  }
}

TEST(J2Plasticity, PlaneStressTangentMatchesFiniteDifferences) {
  const std::vector<J2Plasticity> laws = {
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, false),
      J2Plasticity::bilinear(kE, kNu, kSy, kEt, true),
      J2Plasticity::multilinear(kE, kNu, {{0.0, 250.0}, {0.002, 300.0}, {0.02, 360.0}})};
  Vector5d first, second;
  first << 0.003, -0.0005, 0.002, 0.0003, -0.0002;
  second << 0.004, 0.001, 0.0025, 0.0005, 0.0001;
  for (const auto& law : laws) {
    PlasticState committed;
    ASSERT_TRUE(law.plane_stress(PlasticState{}, first, &committed).yielding);
    EXPECT_NEAR(committed.stress(2), 0.0, 1e-9 * kSy);
    const auto r = law.plane_stress(committed, second, nullptr);
    ASSERT_TRUE(r.yielding);
    Matrix5d fd;
    const double h = 1e-8;
    for (int j = 0; j < 5; ++j) {
      Vector5d ep = second, em = second;
      ep(j) += h;
      em(j) -= h;
      fd.col(j) = (law.plane_stress(committed, ep, nullptr).stress -
                   law.plane_stress(committed, em, nullptr).stress) /
                  (2.0 * h);
    }
    EXPECT_LT((r.tangent - fd).norm(), 1e-6 * r.tangent.norm()) << r.tangent << "\n\n" << fd;
  }
}

TEST(J2Plasticity, UniaxialStressIn3dAndPlaneStressEqualsThe1dLaw) {
  // Uniaxial stress σxx with σyy = σzz = 0: J2 flow is incompressible, so the axial response of
  // the 3-D and the plane-stress returns equals the 1-D law with the same E, σy, Et.
  for (bool kinematic : {false, true}) {
    const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, kinematic);
    PlasticState ps;
    UniaxialPlasticState u1;
    const auto path = cyclic_path(0.006, 4e-4);
    double max_error = 0.0;
    for (double e : path) {
      // Newton on εyy (plane stress holds σzz = 0) until σyy = 0.
      Vector5d strain = Vector5d::Zero();
      strain(0) = e;
      strain(1) = ps.plastic_strain(1) - kNu * (e - ps.plastic_strain(0));
      PlaneStressResponse r;
      for (int it = 0; it < 30; ++it) {
        r = law.plane_stress(ps, strain, nullptr);
        if (std::abs(r.stress(1)) < 1e-11 * kSy) break;
        strain(1) -= r.stress(1) / r.tangent(1, 1);
      }
      PlasticState next;
      law.plane_stress(ps, strain, &next);
      ps = next;
      UniaxialPlasticState n1;
      const auto r1 = law.uniaxial(u1, e, &n1);
      u1 = n1;
      max_error = std::max(max_error, std::abs(r.stress(0) - r1.stress));
    }
    EXPECT_LT(max_error, 1e-7 * kSy);
    EXPECT_NEAR(ps.alpha, u1.alpha, 1e-9);
    EXPECT_NEAR(ps.plastic_work, u1.plastic_work, 1e-6 * u1.plastic_work);
  }
}

TEST(J2Plasticity, PlasticWorkOfAMonotonicBarIsTheAreaAboveTheElasticLine) {
  // Monotonic BISO to strain e: W_p = ∫σ dε_p = σy ε_p + Et-hardening triangle, i.e.
  // (σy + σ)/2 · ε_p with σ = σy + H ε_p — exact for the trapezoidal rule on a linear curve.
  const auto law = J2Plasticity::bilinear(kE, kNu, kSy, kEt, false);
  // The first step ends at first yield, so no step straddles it.
  UniaxialPlasticState s;
  law.uniaxial(UniaxialPlasticState{}, kSy / kE, &s);
  for (int k = 1; k <= 37; ++k) {
    UniaxialPlasticState next;
    law.uniaxial(s, kSy / kE + (0.01 - kSy / kE) * k / 37.0, &next);
    s = next;
  }
  EXPECT_NEAR(s.plastic_work, 0.5 * (kSy + s.stress) * s.plastic_strain, 1e-9 * s.plastic_work);
}

}  // namespace
}  // namespace impactfe::test_j2_plasticity
