// CNVTOL semantics of the convergence test (src/nonlinear/convergence.h).
#include <gtest/gtest.h>

#include "nonlinear/convergence.h"

namespace impactfe::test_convergence {
namespace {

TEST(ConvergenceTest, ForceCriterionIsRelativeToTheReference) {
  ConvergenceOptions o;  // TOLER 0.005, MINREF 0.01 (MAPDL defaults)
  const ConvergenceTest test(o);
  EXPECT_TRUE(test.force_converged(0.5, 100.0));  // 0.5 <= 0.005 * 100
  EXPECT_FALSE(test.force_converged(0.51, 100.0));
}

TEST(ConvergenceTest, MinrefFloorsTheReference) {
  ConvergenceOptions o;
  o.force_tolerance = 0.01;
  o.force_minref = 1.0;
  const ConvergenceTest test(o);
  // A vanishing load would make any residual fail: MINREF = 1 keeps 0.01 absolute.
  EXPECT_TRUE(test.force_converged(0.009, 1e-9));
  EXPECT_FALSE(test.force_converged(0.011, 1e-9));
  EXPECT_DOUBLE_EQ(test.reference(1e-9), 1.0);
  EXPECT_DOUBLE_EQ(test.reference(5.0), 5.0);
}

TEST(ConvergenceTest, DisplacementCriterionOnlyWhenRequested) {
  ConvergenceOptions o;
  EXPECT_TRUE(ConvergenceTest(o).displacement_converged(1e6, 1.0));  // CNVTOL,U not given
  o.displacement_tolerance = 0.05;
  const ConvergenceTest test(o);
  EXPECT_TRUE(test.displacement_converged(0.05, 1.0));
  EXPECT_FALSE(test.displacement_converged(0.051, 1.0));
  EXPECT_TRUE(test.displacement_converged(0.0, 0.0));  // no motion at all
}

}  // namespace
}  // namespace impactfe::test_convergence
