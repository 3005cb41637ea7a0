// The turn-back guard of the arc-length path (path/turn_back.h) on plane geometry: the previous
// step and the answers are 2-vectors (one displacement, the load parameter) whose distances to
// the segment just traced are known.
#include "path/turn_back.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace cb {
namespace {

StepPoint Answer(double du, double dlambda) {
  StepPoint p;
  p.du = Vec::Constant(1, du);
  p.dlambda = dlambda;
  return p;
}

Increment Previous(double du, double dlambda) { return {Vec::Constant(1, du), dlambda}; }

// The trail of one segment: x_{k-1} = x_k - previous.
std::vector<Increment> Behind(const Increment& previous) {
  return {{-previous.du, -previous.dlambda}};
}

// The answer at angle `degrees` from the previous step, of length theta.
StepPoint AnswerAt(double degrees, double theta) {
  const double a = degrees * std::numbers::pi / 180.0;
  return Answer(theta * std::cos(a), theta * std::sin(a));
}

TEST(TurnBackTest, AnAnswerAheadOfThePreviousStepGoesOn) {
  const Increment previous = Previous(1.0, 0.0);
  for (double degrees : {0.0, 30.0, -60.0, 89.0}) {
    EXPECT_FALSE(TurnsBack(AnswerAt(degrees, 1.0), previous, Behind(previous), 1.0, 1.0))
        << degrees;
    EXPECT_FALSE(TurnsBack(AnswerAt(degrees, 1.0), previous, {}, 1.0, 1.0)) << degrees;
  }
}

// With theta unchanged the other root of (33) is x_{k-1} itself.
TEST(TurnBackTest, TheOtherRootAtThePreviousStateTurnsBack) {
  EXPECT_TRUE(
      TurnsBack(Answer(-0.6, -0.8), Previous(0.6, 0.8), Behind(Previous(0.6, 0.8)), 1.0, 1.0));
  // After a cut-back (theta halved) the other root is the midpoint of the segment.
  EXPECT_TRUE(
      TurnsBack(Answer(-0.3, -0.4), Previous(0.6, 0.8), Behind(Previous(0.6, 0.8)), 0.5, 1.0));
}

// A kink turning the path by 120 degrees: the answer points backwards (negative inner
// product) but is theta sin(60 deg) away from the segment, so it is the path going on.
TEST(TurnBackTest, ASharpTurnAwayFromTheSegmentIsNotTurningBack) {
  EXPECT_FALSE(
      TurnsBack(AnswerAt(120.0, 1.0), Previous(1.0, 0.0), Behind(Previous(1.0, 0.0)), 1.0, 1.0));
  // On the first step there is no segment, only the tangent: any backward answer turns back.
  EXPECT_TRUE(TurnsBack(AnswerAt(120.0, 1.0), Previous(1.0, 0.0), {}, 1.0, 1.0));
}

// The answer x_k + (-1/2, h) is at distance |h| from the segment [x_k - (1, 0), x_k]: turned
// back within 5% of theta, going on beyond.
TEST(TurnBackTest, TheBoundaryIsFivePercentOfThetaFromTheSegment) {
  const Increment previous = Previous(1.0, 0.0);
  EXPECT_TRUE(TurnsBack(Answer(-0.5, 0.049), previous, Behind(previous), 1.0, 1.0));
  EXPECT_FALSE(TurnsBack(Answer(-0.5, 0.051), previous, Behind(previous), 1.0, 1.0));
  // Beyond x_{k-1} the distance is to that end point: (-1.5, 0) is 0.5 from it.
  EXPECT_FALSE(TurnsBack(Answer(-1.5, 0.0), previous, Behind(previous), 1.0, 1.0));
  EXPECT_TRUE(TurnsBack(Answer(-1.5, 0.0), previous, Behind(previous), 10.0, 1.0));
}

// theta back to its nominal value after a cut-back: the other root lies behind x_{k-1}, on the
// segment before it, which the trail holds.
TEST(TurnBackTest, TheOtherRootBehindThePreviousStateTurnsBackOnTheTrail) {
  const Increment previous = Previous(0.5, 0.0);  // the cut-back step, x_{k-1} at (-0.5, 0)
  const std::vector<Increment> trail{{Vec::Constant(1, -0.5), 0.0}, {Vec::Constant(1, -1.5), 0.0}};
  EXPECT_TRUE(TurnsBack(Answer(-1.0, 0.01), previous, trail, 1.0, 1.0));
  // The previous segment alone does not reach it.
  EXPECT_FALSE(TurnsBack(Answer(-1.0, 0.01), previous, Behind(previous), 1.0, 1.0));
  // Off the trail by more than 5% of theta: the path going on (a sharp turn).
  EXPECT_FALSE(TurnsBack(Answer(-1.0, 0.06), previous, trail, 1.0, 1.0));
}

// The load parameter counts with weight w: with w = 2 the answer (-0.5, 0.02) is 0.04 from the
// segment, with w = 3 it is 0.06.
TEST(TurnBackTest, TheLoadParameterIsWeightedByW) {
  const Increment previous = Previous(1.0, 0.0);
  EXPECT_TRUE(TurnsBack(Answer(-0.5, 0.02), previous, Behind(previous), 1.0, 2.0));
  EXPECT_FALSE(TurnsBack(Answer(-0.5, 0.02), previous, Behind(previous), 1.0, 3.0));
}

}  // namespace
}  // namespace cb
