// The turn-back guard of the arc-length path (path/turn_back.h) on plane geometry: the previous
// step and the answers are 2-vectors (one displacement, the load parameter) whose distances to
// the segment just traced are known.
#include "path/turn_back.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cb {
namespace {

StepPoint Answer(double du, double dlambda) {
  StepPoint p;
  p.du = Vec::Constant(1, du);
  p.dlambda = dlambda;
  return p;
}

Increment Previous(double du, double dlambda) { return {Vec::Constant(1, du), dlambda}; }

// The answer at angle `degrees` from the previous step, of length theta.
StepPoint AnswerAt(double degrees, double theta) {
  const double a = degrees * std::numbers::pi / 180.0;
  return Answer(theta * std::cos(a), theta * std::sin(a));
}

TEST(TurnBackTest, AnAnswerAheadOfThePreviousStepGoesOn) {
  const Increment previous = Previous(1.0, 0.0);
  for (double degrees : {0.0, 30.0, -60.0, 89.0}) {
    EXPECT_FALSE(TurnsBack(AnswerAt(degrees, 1.0), previous, true, 1.0, 1.0)) << degrees;
    EXPECT_FALSE(TurnsBack(AnswerAt(degrees, 1.0), previous, false, 1.0, 1.0)) << degrees;
  }
}

// With theta unchanged the other root of (33) is x_{k-1} itself.
TEST(TurnBackTest, TheOtherRootAtThePreviousStateTurnsBack) {
  EXPECT_TRUE(TurnsBack(Answer(-0.6, -0.8), Previous(0.6, 0.8), true, 1.0, 1.0));
  // After a cut-back (theta halved) the other root is the midpoint of the segment.
  EXPECT_TRUE(TurnsBack(Answer(-0.3, -0.4), Previous(0.6, 0.8), true, 0.5, 1.0));
}

// A kink turning the path by 120 degrees: the answer points backwards (negative inner
// product) but is theta sin(60 deg) away from the segment, so it is the path going on.
TEST(TurnBackTest, ASharpTurnAwayFromTheSegmentIsNotTurningBack) {
  EXPECT_FALSE(TurnsBack(AnswerAt(120.0, 1.0), Previous(1.0, 0.0), true, 1.0, 1.0));
  // On the first step there is no segment, only the tangent: any backward answer turns back.
  EXPECT_TRUE(TurnsBack(AnswerAt(120.0, 1.0), Previous(1.0, 0.0), false, 1.0, 1.0));
}

// The answer x_k + (-1/2, h) is at distance |h| from the segment [x_k - (1, 0), x_k]: turned
// back within 5% of theta, going on beyond.
TEST(TurnBackTest, TheBoundaryIsFivePercentOfThetaFromTheSegment) {
  const Increment previous = Previous(1.0, 0.0);
  EXPECT_TRUE(TurnsBack(Answer(-0.5, 0.049), previous, true, 1.0, 1.0));
  EXPECT_FALSE(TurnsBack(Answer(-0.5, 0.051), previous, true, 1.0, 1.0));
  // Beyond x_{k-1} the distance is to that end point: (-1.5, 0) is 0.5 from it.
  EXPECT_FALSE(TurnsBack(Answer(-1.5, 0.0), previous, true, 1.0, 1.0));
  EXPECT_TRUE(TurnsBack(Answer(-1.5, 0.0), previous, true, 10.0, 1.0));
}

// The load parameter counts with weight w: with w = 2 the answer (-0.5, 0.02) is 0.04 from the
// segment, with w = 3 it is 0.06.
TEST(TurnBackTest, TheLoadParameterIsWeightedByW) {
  const Increment previous = Previous(1.0, 0.0);
  EXPECT_TRUE(TurnsBack(Answer(-0.5, 0.02), previous, true, 1.0, 2.0));
  EXPECT_FALSE(TurnsBack(Answer(-0.5, 0.02), previous, true, 1.0, 3.0));
}

}  // namespace
}  // namespace cb
