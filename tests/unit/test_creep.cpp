// Implicit creep material point (TB,CREEP in src/materials/j2_plasticity): the time laws under
// constant uniaxial stress against their closed form, Norton relaxation under fixed strain against
// its closed form, and the consistent tangent of the 3-D return against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "materials/j2_plasticity.h"

namespace impactfe::test_creep {
namespace {

constexpr double kE = 200e3, kNu = 0.3;

struct CreepPoint {
  std::shared_ptr<CreepClock> clock = std::make_shared<CreepClock>();
  J2Plasticity law;
  CreepPoint(int option, std::vector<double> c)
      : law(J2Plasticity::creep(kE, kNu, CreepLaw{option, std::move(c)}, clock)) {
    clock->active = true;
  }
  void advance(double t_end, double dt) {
    clock->time = t_end;
    clock->dt = dt;
  }
};

/// Uniaxial creep at constant stress: each step finds the strain that keeps σ by Newton on the
/// consistent tangent; returns the creep strain at t_end.
double creep_at_constant_stress(CreepPoint& s, double sigma, double t_end, int steps) {
  UniaxialPlasticState state;
  double strain = sigma / kE;
  for (int i = 1; i <= steps; ++i) {
    const double t = t_end * i / steps;
    s.advance(t, t_end / steps);
    UniaxialResponse r;
    for (int it = 0; it < 50; ++it) {
      r = s.law.uniaxial(state, strain, nullptr);
      if (std::abs(r.stress - sigma) <= 1e-12 * sigma) break;
      strain += (sigma - r.stress) / r.tangent;
    }
    EXPECT_NEAR(r.stress, sigma, 1e-9 * sigma);
    UniaxialPlasticState next;
    s.law.uniaxial(state, strain, &next);
    state = next;
  }
  return state.plastic_strain;
}

TEST(Creep, ModifiedTimeHardeningMatchesTheClosedFormAtAnyStep) {
  // TBOPT 6 is given as a strain, ε_cr(t) = C1 σ^C2 t^(C3+1) e^(−C4/T) / (C3+1): its difference
  // over each substep reproduces it at constant stress whatever the step.
  const double c1 = 2e-12, c2 = 3.0, c3 = -0.5, c4 = 300.0, temperature = 500.0;
  const double sigma = 120.0, t_end = 400.0;
  const double exact = c1 * std::pow(sigma, c2) * std::pow(t_end, c3 + 1.0) *
                       std::exp(-c4 / temperature) / (c3 + 1.0);
  CreepPoint s(6, {c1, c2, c3, c4});
  s.clock->temperature = temperature;
  EXPECT_NEAR(creep_at_constant_stress(s, sigma, t_end, 7), exact, 1e-9 * exact);
}

TEST(Creep, TimeHardeningIsBackwardEulerAtTheEndOfEachSubstep) {
  // TBOPT 2 is given as a rate, ε̇ = C1 σ^C2 t^C3 e^(−C4/T); MAPDL's implicit creep takes it at
  // t_n+1, so at constant stress ε_cr(t_N) = Σ_k C1 σ^C2 t_k^C3 e^(−C4/T) Δt (the rectangle rule,
  // below the closed form for C3 < 0). NAFEMS R0049 CR1b: C1 = 1.5625e-14, σ = 200, C2 = 5,
  // C3 = −0.5, Δt = 100: ε(1000) = 0.005 Σ_k (100 k)^−0.5 Δt = 0.2511 (the closed form 0.3162).
  const double c1 = 1.5625e-14, c2 = 5.0, c3 = -0.5, sigma = 200.0, t_end = 1000.0;
  const int steps = 10;
  double rectangle = 0.0;
  for (int k = 1; k <= steps; ++k)
    rectangle += c1 * std::pow(sigma, c2) * std::pow(t_end * k / steps, c3) * (t_end / steps);
  EXPECT_NEAR(rectangle, 0.2511, 1e-4);  // the CR1b graph value 0.251
  CreepPoint s(2, {c1, c2, c3, 0.0});
  EXPECT_NEAR(creep_at_constant_stress(s, sigma, t_end, steps), rectangle, 1e-9 * rectangle);
  // Refined, it converges to the closed form C1 σ^C2 t^(C3+1)/(C3+1) (error ~ Δt^(C3+1)).
  const double exact = c1 * std::pow(sigma, c2) * std::pow(t_end, c3 + 1.0) / (c3 + 1.0);
  CreepPoint fine(2, {c1, c2, c3, 0.0});
  EXPECT_NEAR(creep_at_constant_stress(fine, sigma, t_end, 20000), exact, 1e-2 * exact);
}

TEST(Creep, GeneralizedExponentialIsBackwardEulerAtTheEndOfEachSubstep) {
  // TBOPT 3, ε̇ = C1 σ^C2 r e^(−rt), r = C5 σ^C3 e^(−C4/T): the rate at t_n+1 times Δt.
  const double c1 = 1e-8, c2 = 2.0, c3 = 0.5, c5 = 0.01, sigma = 100.0, t_end = 40.0;
  const int steps = 4;
  const double r = c5 * std::pow(sigma, c3);
  double rectangle = 0.0;
  for (int k = 1; k <= steps; ++k)
    rectangle += c1 * std::pow(sigma, c2) * r * std::exp(-r * t_end * k / steps) * (t_end / steps);
  CreepPoint s(3, {c1, c2, c3, 0.0, c5});
  EXPECT_NEAR(creep_at_constant_stress(s, sigma, t_end, steps), rectangle, 1e-9 * rectangle);
}

TEST(Creep, CombinedTimeHardeningAddsTheSecondaryTerm) {
  const double sigma = 80.0, t_end = 50.0;
  CreepPoint s(11, {1e-10, 2.0, 0.0, 0.0, 3e-12, 4.0, 0.0});
  const double exact = 1e-10 * sigma * sigma * t_end + 3e-12 * std::pow(sigma, 4.0) * t_end;
  EXPECT_NEAR(creep_at_constant_stress(s, sigma, t_end, 5), exact, 1e-9 * exact);
}

TEST(Creep, StrainHardeningAtConstantStressApproachesTheClosedForm) {
  // Modified strain hardening at constant σ integrates to the time-hardening curve
  // ε = [C1 σ^C2 ... ] — for C3 = 0 both are ε = C1 σ^C2 t (backward Euler is then exact).
  const double sigma = 100.0, t_end = 10.0;
  CreepPoint s(7, {1e-9, 2.0, 0.0, 0.0});
  const double exact = 1e-9 * sigma * sigma * t_end;
  EXPECT_NEAR(creep_at_constant_stress(s, sigma, t_end, 4), exact, 1e-9 * exact);
}

TEST(Creep, NortonRelaxationUnderFixedStrainMatchesTheClosedForm) {
  // σ̇ = −E C1 σ^n at fixed total strain: σ(t) = [σ0^(1−n) + (n − 1) E C1 t]^(1/(1−n)).
  const double c1 = 1e-14, n = 4.0, sigma0 = 200.0, t_end = 100.0;
  CreepPoint s(10, {c1, n, 0.0});
  const double strain = sigma0 / kE;
  UniaxialPlasticState state;
  const int steps = 4000;
  double sigma = 0.0;
  for (int i = 1; i <= steps; ++i) {
    s.advance(t_end * i / steps, t_end / steps);
    UniaxialPlasticState next;
    sigma = s.law.uniaxial(state, strain, &next).stress;
    state = next;
  }
  const double exact =
      std::pow(std::pow(sigma0, 1.0 - n) + (n - 1.0) * kE * c1 * t_end, 1.0 / (1.0 - n));
  EXPECT_LT(exact, 0.8 * sigma0);  // the test relaxes the stress substantially
  EXPECT_NEAR(sigma, exact, 1e-3 * exact);
}

TEST(Creep, NoCreepWhenTheClockIsOff) {
  CreepPoint s(10, {1e-10, 3.0, 0.0});
  s.advance(10.0, 10.0);
  s.clock->active = false;  // RATE,OFF
  UniaxialPlasticState next;
  const UniaxialResponse r = s.law.uniaxial(UniaxialPlasticState{}, 1e-3, &next);
  EXPECT_DOUBLE_EQ(r.stress, kE * 1e-3);
  EXPECT_EQ(next.plastic_strain, 0.0);
}

TEST(Creep, SolidTangentMatchesFiniteDifferences) {
  for (int option : {1, 2, 3, 6, 7, 10, 11}) {
    CreepPoint s(option, {1e-12, 3.0, option == 3 ? 1.0 : -0.3, 0.0, 0.02, 2.0, 0.0});
    s.advance(2.0, 1.0);
    s.clock->temperature = 500.0;  // Norton reads C3 as its temperature constant
    PlasticState committed;
    committed.alpha = 1e-4;
    committed.plastic_strain << 5e-5, -2e-5, -3e-5, 1e-5, 0.0, 2e-5;
    Vector6d strain;
    strain << 1.2e-3, -0.4e-3, 0.1e-3, 0.6e-3, -0.2e-3, 0.3e-3;
    const PlasticResponse r = s.law.solid(committed, strain, nullptr);
    ASSERT_TRUE(r.yielding) << option;
    const double h = 1e-9;
    for (int j = 0; j < 6; ++j) {
      Vector6d plus = strain, minus = strain;
      plus(j) += h;
      minus(j) -= h;
      const Vector6d column = (s.law.solid(committed, plus, nullptr).stress -
                               s.law.solid(committed, minus, nullptr).stress) /
                              (2.0 * h);
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(r.tangent(i, j), column(i), 1e-4 * kE) << option << " " << i << "," << j;
    }
  }
}

}  // namespace
}  // namespace impactfe::test_creep
