#include "path/stagnation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "refusal.h"

namespace cb {
namespace {

Increment Along(double x, double y, double dlambda) {
  Vec du(2);
  du << x, y;
  return {du, dlambda};
}

// A path accepted at ever smaller arc lengths is stagnating once max_slow_steps consecutive
// steps are below slow_fraction of the requested theta, and not one step earlier.
TEST(StagnationTest, ConsecutiveSlowStepsStopThePathAtTheLimit) {
  StagnationOptions options;
  options.max_slow_steps = 5;
  StagnationMonitor monitor(options, 0.05, 1.0);
  const double slow = 0.5 * options.slow_fraction * 0.05;
  EXPECT_FALSE(monitor.Observe(1, 0.05, Along(0.05, 0.0, 0.0)));
  for (int step = 2; step <= 5; ++step) {
    EXPECT_FALSE(monitor.Observe(step, slow, Along(slow, 0.0, 0.0))) << step;
  }
  const auto why = monitor.Observe(6, slow, Along(slow, 0.0, 0.0));
  ASSERT_TRUE(why);
  // The reason gives the slow steps (2 to 6), the largest of their arc lengths, the fraction
  // and the requested arc length.
  const std::vector<double> numbers = testing_support::NumbersIn(*why);
  ASSERT_EQ(numbers.size(), 5u) << *why;
  EXPECT_EQ(numbers[0], 2.0) << *why;
  EXPECT_EQ(numbers[1], 6.0) << *why;
  EXPECT_NEAR(numbers[2], slow, 1e-6 * slow) << *why;
  EXPECT_NEAR(numbers[3], options.slow_fraction, 1e-6 * options.slow_fraction) << *why;
  EXPECT_EQ(numbers[4], 0.05) << *why;
}

// One step at the full arc length in between starts the count again: a path that recovers
// after a few tiny steps (a kink passed by cut-backs) is not stagnating.
TEST(StagnationTest, ARecoveredStepResetsTheCount) {
  StagnationOptions options;
  options.max_slow_steps = 3;
  StagnationMonitor monitor(options, 1.0, 1.0);
  int step = 0;
  for (int round = 0; round < 10; ++round) {
    EXPECT_FALSE(monitor.Observe(++step, 1e-4, Along(1e-4, 0.0, 0.0)));
    EXPECT_FALSE(monitor.Observe(++step, 1e-4, Along(1e-4, 0.0, 0.0)));
    EXPECT_FALSE(monitor.Observe(++step, 1.0, Along(1.0, 0.0, 0.0)));
  }
}

// Increments that go back and forth over the same states retrace the path; the cosine of
// consecutive increments in the H inner product is -1 (w weights dlambda).
TEST(StagnationTest, BackAndForthIncrementsRetraceThePath) {
  StagnationOptions options;
  options.max_reversals = 3;
  options.max_slow_steps = 0;
  StagnationMonitor monitor(options, 0.1, 2.0);
  EXPECT_FALSE(monitor.Observe(1, 0.1, Along(0.06, 0.0, 0.04)));
  EXPECT_FALSE(monitor.Observe(2, 0.1, Along(-0.06, 0.0, -0.04)));
  EXPECT_FALSE(monitor.Observe(3, 0.1, Along(0.06, 0.0, 0.04)));
  const auto why = monitor.Observe(4, 0.1, Along(-0.06, 0.0, -0.04));
  ASSERT_TRUE(why);
  // The reason gives the steps that went back and forth, 1 to 4, and no arc length (the steps
  // were not slow).
  EXPECT_EQ(testing_support::NumbersIn(*why), (std::vector<double>{1.0, 4.0})) << *why;
}

// A single sharp turn (a kink where the load turns back: cosine -0.95) and a right angle are
// a path going on, however often they occur apart.
TEST(StagnationTest, SharpTurnsApartAreNotRetracing) {
  StagnationOptions options;
  StagnationMonitor monitor(options, 0.1, 1.0);
  const double c = -0.95, s = std::sqrt(1.0 - c * c);
  int step = 0;
  for (int k = 0; k < 20; ++k) {
    EXPECT_FALSE(monitor.Observe(++step, 0.1, Along(0.1, 0.0, 0.0)));
    EXPECT_FALSE(monitor.Observe(++step, 0.1, Along(0.1 * c, 0.1 * s, 0.0)));
    EXPECT_FALSE(monitor.Observe(++step, 0.1, Along(0.0, 0.0, 0.1)));
  }
}

TEST(StagnationTest, OptionsOutsideTheirRangesAreRefused) {
  std::string why;
  StagnationOptions options;
  EXPECT_TRUE(options.IsValid(&why));
  options.slow_fraction = 1.0;
  EXPECT_FALSE(options.IsValid(&why));
  options = StagnationOptions();
  options.reversal_cosine = 0.5;
  EXPECT_FALSE(options.IsValid(&why));
  options = StagnationOptions();
  options.max_reversals = -1;
  EXPECT_FALSE(options.IsValid(&why));
}

}  // namespace
}  // namespace cb
