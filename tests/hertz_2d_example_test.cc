// examples/hertz-2d.json: the 2-D Hertz problem on its Gmsh mesh (a quarter disc of radius R on a
// rigid floor, symmetry on x = 0, pressure p on its top), solved and held to two closed forms:
// equilibrium (the floor carries the whole load p R t) and Hertz's half-width for a cylinder on a
// rigid flat in plane stress, a^2 = 4 P R / (pi E) with P = 2 p R the load per unit thickness of
// the whole disc. The measured half-width comes from the reactions' second moment, which is
// a^2 / 4 for Hertz's pressure p0 sqrt(1 - x^2 / a^2).
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "io/problem_file.h"
#include "path/path.h"
#include "problems/problem.h"
#include "source_tree.h"
#include "verdict/verdict.h"

namespace cb {
namespace {

constexpr double kRadius = 10.0, kPressure = 15.0, kThickness = 1.0, kYoungs = 1000.0;

double HalfWidthFromReactions(const Problem& p, const Vec& r) {
  const ElasticBody& body = p.body->body();
  double total = 0.0, second_moment = 0.0;
  for (int q = 0; q < p.body->num_pairs(); ++q) {
    const double x = body.reference(p.body->pairs()[static_cast<std::size_t>(q)].node)[0];
    total += -r[q];  // r <= 0 presses the body
    second_moment += -r[q] * x * x;
  }
  return 2.0 * std::sqrt(second_moment / total);
}

TEST(Hertz2dExampleTest, TheFloorCarriesTheLoadOverHertzsHalfWidth) {
  const auto file = ::cb::testing_support::SourceRoot() / "examples" / "hertz-2d.json";
  const Problem p = io::LoadProblemFile(file.string());
  ImplicitFb formulation;
  const fixtures::JudgedSolve a = fixtures::SolveAndJudge(p, formulation, 1.0);
  const PathSummary& s = a.summary;
  const Verdict& v = a.verdict;
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_TRUE(v.verified) << v.eq_res << " " << v.comp_res << " " << v.feas_res;

  EXPECT_NEAR(s.final_state.r.sum(), -kPressure * kRadius * kThickness, 1e-8);
  const double load_per_thickness = 2.0 * kPressure * kRadius;
  const double hertz = std::sqrt(4.0 * load_per_thickness * kRadius / (std::acos(-1.0) * kYoungs));
  EXPECT_NEAR(HalfWidthFromReactions(p, s.final_state.r) / hertz, 1.0, 0.02);
}

}  // namespace
}  // namespace cb
