// CombinationGap (COMBIN40): gap open/close, hook geometry, Coulomb slider, break-away,
// lock-up, mass placement (thesis eq. 3-6), forces (eq. 3-5), stiffness (eq. 3-7). Spec §11.4.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/errors.h"
#include "elements/combination_gap.h"
#include "elements/element.h"

namespace impactfe::test_combination_gap {
namespace {

struct GapSpec {
  double k1 = 0.0, c = 0.0, m = 0.0, gap = 0.0, fslide = 0.0, k2 = 0.0;
  int keyopt1 = 0, keyopt3 = 3, keyopt6 = 0;
  double zi = 0.0, zj = 0.0;  // node positions along Z (irrelevant to the algebra)
};

Model gap_model(const GapSpec& s) {
  Model m;
  m.nodes[68] = Node{68, Vec3(0, 0, s.zi)};
  m.nodes[43] = Node{43, Vec3(0, 0, s.zj)};
  ElementType et;
  et.id = 3;
  et.ansys_name = "COMBIN40";
  et.keyopt[1] = s.keyopt1;
  et.keyopt[3] = s.keyopt3;
  et.keyopt[6] = s.keyopt6;
  m.element_types[3] = et;
  m.real_sets[3] = RealSet{3, {s.k1, s.c, s.m, s.gap, s.fslide, s.k2}};
  return m;
}

ElementRecord gap_record() {
  ElementRecord r;
  r.id = 70;
  r.type = 3;
  r.real = 3;
  r.nodes = {68, 43};
  r.where = SourceLocation{"helmet.inp", 88, "E"};
  return r;
}

std::unique_ptr<Element> build(const GapSpec& s) {
  const Model m = gap_model(s);
  return create_element(ElementBuildContext{m, {}}, gap_record());
}

/// u = (u_I, u_J).
Eigen::VectorXd uv(double ui, double uj) {
  Eigen::VectorXd u(2);
  u << ui, uj;
  return u;
}

struct Eval {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  ElementResultValues r;  // FORC F1 F2 STAT DELTA SLIDE
};

Eval eval(const Element& e, const Eigen::VectorXd& u) {
  Eval out;
  e.tangent(ElementContext{}, u, out.K, out.f);
  e.results(ElementContext{}, u, Eigen::VectorXd::Zero(2), out.r);
  return out;
}

const ElementContext kCtx{};

TEST(CombinationGap, DofsFromKeyopt3AndResultNames) {
  GapSpec s;
  s.k1 = 1000;
  s.gap = 1.0;
  auto e = build(s);
  EXPECT_STREQ(e->family(), "CombinationGap");
  ASSERT_EQ(e->n_dofs(), 2);
  EXPECT_EQ(e->dofs()[0], (DofKey{68, Dof::UZ}));
  EXPECT_EQ(e->dofs()[1], (DofKey{43, Dof::UZ}));
  const std::vector<std::string> names = {"FORC", "F1", "F2", "STAT", "DELTA", "SLIDE", "SENE"};
  EXPECT_EQ(e->result_names(), names);
  s.keyopt3 = 0;
  EXPECT_EQ(build(s)->dofs()[0].dof, Dof::UX);
  s.keyopt3 = 6;
  EXPECT_EQ(build(s)->dofs()[1].dof, Dof::ROTZ);
}

TEST(CombinationGap, HelmetGroundGapOpensAndCloses) {
  // Helmet–ground element: R,3,1000,,,1.0, I = ground node 68, J = helmet crown 43 (gap 1 in).
  GapSpec s;
  s.k1 = 1000;
  s.gap = 1.0;
  auto e = build(s);
  EXPECT_TRUE(e->is_nonlinear(kCtx));
  EXPECT_TRUE(e->has_status());
  EXPECT_EQ(e->status(), GapStatus::Open);
  Eval a = eval(*e, uv(0, -0.5));  // open: no force, no stiffness
  EXPECT_EQ(a.K.norm(), 0.0);
  EXPECT_EQ(a.f.norm(), 0.0);
  EXPECT_EQ(a.r[3], 0.0);
  EXPECT_DOUBLE_EQ(a.r[4], 0.5);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -0.5)));

  // J moves down 1.2 in: Δ + GAP = −0.2 ≤ 0 -> closed, F = 1000·(−0.2) = −200 (compression).
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -1.2)));
  EXPECT_EQ(e->status(), GapStatus::Closed);
  Eval b = eval(*e, uv(0, -1.2));
  EXPECT_NEAR(b.r[0], -200.0, 1e-9);
  EXPECT_NEAR(b.f(0), 200.0, 1e-9);  // eq. 3-5: f = F[−1, +1]
  EXPECT_NEAR(b.f(1), -200.0, 1e-9);
  Eigen::Matrix2d k;
  k << 1000, -1000, -1000, 1000;  // eq. 3-7
  EXPECT_TRUE(b.K.isApprox(k));
  EXPECT_EQ(b.r[3], 1.0);
  EXPECT_NEAR(b.r[4], -0.2, 1e-12);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -1.1)));  // still compressed

  // Rebound: Δ + GAP = +0.05 -> tension -> opens.
  EXPECT_TRUE(e->update_status(kCtx, uv(0.1, -0.85)));
  EXPECT_EQ(e->status(), GapStatus::Open);
}

TEST(CombinationGap, RevertCommitAndFreeze) {
  GapSpec s;
  s.k1 = 1650;
  s.gap = 0.1;
  auto e = build(s);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.3)));
  e->revert();
  EXPECT_EQ(e->status(), GapStatus::Open);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.3)));
  e->commit(uv(0, -0.3));
  e->revert();
  EXPECT_EQ(e->status(), GapStatus::Closed);
  // Frozen: no status change even though the gap would open.
  e->freeze_status(true);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, 0.5)));
  EXPECT_EQ(e->status(), GapStatus::Closed);
  e->freeze_status(false);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, 0.5)));
  EXPECT_EQ(e->status(), GapStatus::Open);
}

TEST(CombinationGap, HookGeometryClosesWhenNodesSeparate) {
  // Thesis Fig. 3-2: node I above node J is a hook; it closes when J drops more than GAP below
  // its initial position relative to I, and then pulls J back up toward I.
  GapSpec s;
  s.k1 = 500;
  s.gap = 0.1;
  s.zi = 1.0;
  s.zj = 0.0;
  auto e = build(s);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -0.05)));  // slack hook
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.3)));
  const Eval a = eval(*e, uv(0, -0.3));
  EXPECT_NEAR(a.r[0], -100.0, 1e-9);  // 500·(−0.2)
  // Restoring forces −f_int: +z (toward I) on J, −z (toward J) on I.
  EXPECT_GT(-a.f(1), 0.0);
  EXPECT_LT(-a.f(0), 0.0);
  EXPECT_NEAR(-a.f(1), 100.0, 1e-9);
}

TEST(CombinationGap, ZeroGapIsAlwaysClosedAndLinear) {
  GapSpec s;
  s.k1 = 300;
  s.k2 = 200;
  auto e = build(s);
  EXPECT_FALSE(e->is_nonlinear(kCtx));
  EXPECT_FALSE(e->has_status());
  EXPECT_EQ(e->status(), GapStatus::Closed);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, 2.0)));
  const Eval a = eval(*e, uv(0, 0.01));  // tension carried: F = (K1 + K2)·Δ = 5
  EXPECT_NEAR(a.r[0], 5.0, 1e-12);
  EXPECT_NEAR(a.r[1], 3.0, 1e-12);
  EXPECT_NEAR(a.r[2], 2.0, 1e-12);
  EXPECT_NEAR(a.K(0, 0), 500.0, 1e-12);
}

TEST(CombinationGap, InterferenceStartsClosedWithPreload) {
  GapSpec s;
  s.k1 = 100;
  s.gap = -0.02;
  auto e = build(s);
  EXPECT_EQ(e->status(), GapStatus::Closed);
  const Eval a = eval(*e, uv(0, 0));
  EXPECT_NEAR(a.r[0], -2.0, 1e-12);
  EXPECT_NEAR(a.f(0), 2.0, 1e-12);
}

TEST(CombinationGap, LockUpStaysClosedInTension) {
  GapSpec s;
  s.k1 = 1000;
  s.gap = 0.1;
  s.keyopt1 = 1;
  auto e = build(s);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.2)));
  e->commit(uv(0, -0.2));
  EXPECT_FALSE(e->update_status(kCtx, uv(0, 0.5)));
  EXPECT_EQ(e->status(), GapStatus::Closed);
  const Eval a = eval(*e, uv(0, 0.5));
  EXPECT_NEAR(a.r[0], 600.0, 1e-9);  // 1000·(0.5 + 0.1), tension
}

TEST(CombinationGap, CoulombSliderLimitsSpringOneForce) {
  // K1 = 1000 with FSLIDE = 50 in parallel with K2 = 200, no gap.
  GapSpec s;
  s.k1 = 1000;
  s.fslide = 50;
  s.k2 = 200;
  auto e = build(s);
  EXPECT_TRUE(e->is_nonlinear(kCtx));
  // Sticking: Δ = −0.03 -> F1 = −30, F2 = −6.
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -0.03)));
  Eval a = eval(*e, uv(0, -0.03));
  EXPECT_NEAR(a.r[1], -30.0, 1e-12);
  EXPECT_NEAR(a.r[0], -36.0, 1e-12);
  EXPECT_NEAR(a.K(0, 0), 1200.0, 1e-12);
  // Δ = −0.08: |K1 δ| = 80 > 50 -> sliding, F1 = −50, slip = −0.08 + 0.05 = −0.03, S1 = 0.
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.08)));
  EXPECT_EQ(e->status(), GapStatus::Sliding);
  a = eval(*e, uv(0, -0.08));
  EXPECT_NEAR(a.r[1], -50.0, 1e-12);
  EXPECT_NEAR(a.r[2], -16.0, 1e-12);
  EXPECT_NEAR(a.r[3], 2.0, 0.0);
  EXPECT_NEAR(a.r[5], -0.03, 1e-12);
  EXPECT_NEAR(a.K(0, 0), 200.0, 1e-12);
  // Further sliding keeps |F1| at the limit.
  a = eval(*e, uv(0, -0.5));
  EXPECT_NEAR(a.r[1], -50.0, 1e-12);
  EXPECT_NEAR(a.r[0], -150.0, 1e-12);
  e->commit(uv(0, -0.08));
  // Unloading reverses the slip increment -> sticks with the committed slip −0.03:
  // F1 = 1000·(−0.07 + 0.03) = −40.
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.07)));
  EXPECT_EQ(e->status(), GapStatus::Closed);
  a = eval(*e, uv(0, -0.07));
  EXPECT_NEAR(a.r[1], -40.0, 1e-9);
  EXPECT_NEAR(a.r[5], -0.03, 1e-12);
  // Back at Δ = 0 the slip is a permanent set: F1 = +30 (tension, no gap to open).
  EXPECT_FALSE(e->update_status(kCtx, uv(0, 0)));
  EXPECT_NEAR(eval(*e, uv(0, 0)).r[1], 30.0, 1e-9);
}

TEST(CombinationGap, SlidingTangentMatchesFiniteDifference) {
  GapSpec s;
  s.k1 = 1000;
  s.fslide = 50;
  s.k2 = 200;
  s.gap = 0.05;
  auto e = build(s);
  for (double uj : {-0.07, -0.3}) {  // sticking, then sliding
    e->update_status(kCtx, uv(0.01, uj));
    const double h = 1e-6;
    Eigen::MatrixXd K, Kd;
    Eigen::VectorXd f, fp, fm;
    e->tangent(kCtx, uv(0.01, uj), K, f);
    for (int j = 0; j < 2; ++j) {
      Eigen::VectorXd up = uv(0.01, uj), um = up;
      up(j) += h;
      um(j) -= h;
      e->tangent(kCtx, up, Kd, fp);
      e->tangent(kCtx, um, Kd, fm);
      EXPECT_LT(((fp - fm) / (2 * h) - K.col(j)).norm(), 1e-6 * K.norm()) << uj;
    }
    EXPECT_TRUE(K.isApprox(K.transpose()));
  }
  EXPECT_EQ(e->status(), GapStatus::Sliding);
}

TEST(CombinationGap, SlipGivesPermanentSetBeforeReclosing) {
  // K1 = 1000, FSLIDE = 50, GAP = 0.1: slide to δ = −0.2 (slip −0.15), unload: the gap opens
  // once F1 > 0 (δ > −0.15) and re-closes only when δ ≤ −0.15.
  GapSpec s;
  s.k1 = 1000;
  s.fslide = 50;
  s.gap = 0.1;
  auto e = build(s);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.3)));
  EXPECT_EQ(e->status(), GapStatus::Sliding);
  e->commit(uv(0, -0.3));
  EXPECT_NEAR(eval(*e, uv(0, -0.3)).r[5], -0.15, 1e-12);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.22)));  // δ = −0.12: F1 = +30 -> opens
  EXPECT_EQ(e->status(), GapStatus::Open);
  e->commit(uv(0, -0.22));
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -0.23)));  // δ = −0.13 ≤ 0 but F1 would be +20
  EXPECT_EQ(e->status(), GapStatus::Open);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.26)));  // δ = −0.16: closes with F1 = −10
  EXPECT_EQ(e->status(), GapStatus::Closed);
  EXPECT_NEAR(eval(*e, uv(0, -0.26)).r[0], -10.0, 1e-9);
}

TEST(CombinationGap, BreakAwaySliderReleasesSpringOne) {
  GapSpec s;
  s.k1 = 1000;
  s.fslide = -50;
  s.k2 = 100;
  auto e = build(s);
  EXPECT_FALSE(e->update_status(kCtx, uv(0, -0.04)));
  EXPECT_NEAR(eval(*e, uv(0, -0.04)).r[1], -40.0, 1e-12);
  EXPECT_TRUE(e->update_status(kCtx, uv(0, -0.06)));  // |F1| would be 60 > 50
  e->commit(uv(0, -0.06));
  for (double uj : {-0.06, -0.01, 0.02}) {
    EXPECT_FALSE(e->update_status(kCtx, uv(0, uj)));
    const Eval a = eval(*e, uv(0, uj));
    EXPECT_NEAR(a.r[1], 0.0, 1e-12);
    EXPECT_NEAR(a.r[0], 100.0 * uj, 1e-12);
    EXPECT_NEAR(a.K(0, 0), 100.0, 1e-12);
  }
}

TEST(CombinationGap, MassPlacementByKeyopt6) {
  // Thesis eq. 3-6 with M = 2.
  GapSpec s;
  s.k1 = 10;
  s.m = 2.0;
  const double expected[3][2] = {{2.0, 0.0}, {1.0, 1.0}, {0.0, 2.0}};
  for (int k6 = 0; k6 < 3; ++k6) {
    s.keyopt6 = k6;
    Eigen::MatrixXd M;
    build(s)->mass(kCtx, M);
    ASSERT_EQ(M.rows(), 2);
    EXPECT_DOUBLE_EQ(M(0, 0), expected[k6][0]);
    EXPECT_DOUBLE_EQ(M(1, 1), expected[k6][1]);
    EXPECT_DOUBLE_EQ(M(0, 1), 0.0);
    EXPECT_DOUBLE_EQ(M.sum(), 2.0);
  }
}

TEST(CombinationGap, DamperOnlyWhileClosed) {
  GapSpec s;
  s.k1 = 10;
  s.c = 3;
  s.gap = 0.1;
  auto e = build(s);
  ASSERT_TRUE(e->has_damping());
  Eigen::MatrixXd C;
  e->damping(kCtx, uv(0, 0), C);
  EXPECT_EQ(C.norm(), 0.0);
  e->update_status(kCtx, uv(0, -0.2));
  e->damping(kCtx, uv(0, -0.2), C);
  Eigen::Matrix2d expected;
  expected << 3, -3, -3, 3;
  EXPECT_TRUE(C.isApprox(expected));
}

TEST(CombinationGap, StrainEnergyOfBothSprings) {
  // K1 = 1000, K2 = 200, no gap, compressed by 0.1: F1 = -100, F2 = -20, SENE = 5 + 1.
  GapSpec s;
  s.k1 = 1000;
  s.k2 = 200;
  auto e = build(s);
  const Eval ev = eval(*e, uv(0.1, 0.0));
  ASSERT_EQ(ev.r.size(), 7u);
  EXPECT_NEAR(ev.r[6], 6.0, 1e-12);
}

TEST(CombinationGap, WithoutSpringsIsALinearDamperAndMass) {
  // vm9's R,3,,1.41,1: K1 = K2 = 0, C = 1.41, M = 1 (KEYOPT(6) = 2: mass at J).
  GapSpec s;
  s.c = 1.41;
  s.m = 1.0;
  s.keyopt6 = 2;
  auto e = build(s);
  EXPECT_FALSE(e->has_status());
  const Eval ev = eval(*e, uv(0.3, -0.7));
  EXPECT_EQ(ev.K.norm(), 0.0);
  EXPECT_EQ(ev.f.norm(), 0.0);
  Eigen::MatrixXd C, M;
  e->damping(kCtx, uv(0.3, -0.7), C);
  Eigen::Matrix2d expected;
  expected << 1.41, -1.41, -1.41, 1.41;
  EXPECT_TRUE(C.isApprox(expected));
  e->mass(kCtx, M);
  EXPECT_EQ(M(1, 1), 1.0);
  EXPECT_EQ(M(0, 0), 0.0);
}

TEST(CombinationGap, InputErrors) {
  auto expect_error = [](const GapSpec& s, const char* fragment) {
    try {
      build(s);
      FAIL() << fragment;
    } catch (const InputError& err) {
      EXPECT_EQ(err.where().line, 88);
      EXPECT_NE(err.message().find(fragment), std::string::npos) << err.message();
    }
  };
  GapSpec s;
  s.gap = 0.1;
  expect_error(s, "K1 and K2 are both zero, so GAP = 0.1");
  s.gap = 0.0;
  s.fslide = 5.0;
  expect_error(s, "FSLIDE = 5 would carry no force");
  s.fslide = 0.0;
  s.k1 = 10;
  s.keyopt3 = 7;
  expect_error(s, "KEYOPT(3)");
  s.keyopt3 = 1;
  s.keyopt6 = 3;
  expect_error(s, "KEYOPT(6)");
}

}  // namespace
}  // namespace impactfe::test_combination_gap
