// The counts and dimensions docs/problems.md states, and parameter validation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "model/truss.h"
#include "problems/problem.h"
#include "refusal.h"

namespace cb {
namespace {

TEST(ProblemsTest, BlockCountsForN50) {
  const Problem p = MakeProblem("block");
  EXPECT_EQ(p.model->num_dofs(), 5202);  // 2 (n + 1)^2
  EXPECT_EQ(p.model->num_pairs(), 102);  // 2 (n + 1)
  EXPECT_TRUE(p.model->is_linear());
  // The right-edge traction integrates to 0.5 MPa x 2 m x 10 mm = 10 kN per direction.
  const Vec& f = p.model->load_pattern();
  double fx = 0.0, fy = 0.0;
  for (int i = 0; i < f.size(); i += 2) {
    fx += f[i];
    fy += f[i + 1];
  }
  EXPECT_NEAR(fx, -1e4, 1e-6);
  EXPECT_NEAR(fy, -1e4, 1e-6);
}

TEST(ProblemsTest, BlockMeshSizeIsAParameter) {
  const Problem p = MakeProblem("block", {{"n", "10"}});
  EXPECT_EQ(p.model->num_dofs(), 2 * 11 * 11);
  EXPECT_EQ(p.model->num_pairs(), 22);
}

// Depth of the lowest node below the supports, H1 of docs/problems.md.
double LowestNodeDepth(const Problem& p) {
  const ElasticBody& body = p.body->body();
  double lowest = 0.0;
  for (int n = 0; n < body.num_nodes(); ++n) lowest = std::min(lowest, body.reference(n)[1]);
  return -lowest;
}

const Truss& TrussOf(const Problem& p) { return dynamic_cast<const Truss&>(p.body->body()); }

double CentreArea(const Problem& p) {
  double smallest = 1e300;
  for (const auto& m : TrussOf(p).members()) smallest = std::min(smallest, m.area);
  return smallest;
}

TEST(ProblemsTest, ArchFlatCountsAndGeometry) {
  const Problem p = MakeProblem("arch-flat");
  EXPECT_EQ(p.model->num_dofs(), 119);
  EXPECT_EQ(p.model->num_pairs(), 90);
  EXPECT_EQ(p.body->body().num_nodes(), 61);
  EXPECT_EQ(TrussOf(p).members().size(), 119u);
  EXPECT_NEAR(LowestNodeDepth(p), 2.3225, 5e-5);
  EXPECT_NEAR(CentreArea(p), 0.05, 1e-12);
  double largest = 0.0;
  for (const auto& m : TrussOf(p).members()) largest = std::max(largest, m.area);
  EXPECT_NEAR(largest, 0.33, 1e-12);
  // Supports (a) and (b) sit on the upper obstacle's surface y = 0.
  EXPECT_NEAR(p.body->body().reference(0)[1], 0.0, 1e-12);
  EXPECT_NEAR(p.body->body().reference(29)[0], 7.5, 1e-12);
  EXPECT_FALSE(p.model->is_linear());
}

TEST(ProblemsTest, ArchCurvedCountsAndGeometry) {
  const Problem p = MakeProblem("arch-curved");
  EXPECT_EQ(p.model->num_dofs(), 279);
  EXPECT_EQ(p.model->num_pairs(), 210);
  EXPECT_EQ(p.body->body().num_nodes(), 141);
  EXPECT_NEAR(LowestNodeDepth(p), 2.6373, 5e-5);
  EXPECT_NEAR(CentreArea(p), 0.05, 1e-12);
  // The lower centre node is H2 = 0.1 m above the cylinder: its gap is 0.1.
  Vec phi;
  p.model->Gaps(Vec::Zero(p.model->num_dofs()), &phi);
  double closest = 1e300;
  for (int q = 0; q < p.model->num_pairs(); ++q) {
    if (p.body->pairs()[q].obstacle == 1) closest = std::min(closest, -phi[q]);
  }
  EXPECT_NEAR(closest, 0.1, 1e-9);
}

TEST(ProblemsTest, EveryInitialGapIsNonNegative) {
  for (const auto& name : ProblemNames()) {
    const Problem p = MakeProblem(name);
    Vec phi;
    p.model->Gaps(Vec::Zero(p.model->num_dofs()), &phi);
    if (phi.size() > 0) {
      EXPECT_LE(phi.maxCoeff(), 1e-12) << name;
    }
  }
}

TEST(ProblemsTest, UnknownProblemListsValidNames) {
  try {
    MakeProblem("nope");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    // The name given and every valid one.
    EXPECT_TRUE(testing_support::Names(e.what(), {"nope"}));
    EXPECT_TRUE(testing_support::Names(e.what(), ProblemNames()));
  }
}

TEST(ProblemsTest, BadParameterIsNamed) {
  try {
    MakeProblem("block", {{"mesh", "3"}});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    // The problem, the parameter given and the block's own parameters.
    EXPECT_TRUE(testing_support::RefusedAt(
        e.what(), "problem 'block'",
        testing_support::At("", {"mesh", "side", "thickness", "youngs_modulus", "poisson_ratio"})));
  }
  EXPECT_THROW(MakeProblem("block", {{"n", "0"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("block", {{"n", "2.5"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("block", {{"poisson_ratio", "0.5"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("arch-flat", {{"length_scale", "0"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("arch-flat", {{"lower_obstacle", "round"}}), std::invalid_argument);
  EXPECT_THROW(MakeProblem("arch-flat", {{"youngs_modulus", "nan"}}), std::invalid_argument);
}

// The message of a refused value, for the assertions below.
std::string RefusalOf(const std::string& problem, const std::string& name,
                      const std::string& text) {
  try {
    MakeProblem(problem, {{name, text}});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ProblemsTest, AnIntegerParameterIsWrittenAsDigits) {
  EXPECT_EQ(MakeProblem("block", {{"n", "4"}}).model->num_dofs(), 2 * 5 * 5);
  for (const char* text : {"1e1", "4.0", "4e0", "0x4", "", "-"}) {
    // Refused at the parameter n, naming the text as given.
    EXPECT_TRUE(testing_support::RefusedAt(RefusalOf("block", "n", text), "problem 'block'",
                                           testing_support::At("parameter 'n'", {text})));
  }
}

TEST(ProblemsTest, AValueOutOfRangeNamesTheBoundItPassesExactly) {
  // poisson_ratio is in (-1, 0.4999999]: 0.5 passes the upper bound, printed as it is.
  // Each refusal gives the value and then the bound, as written (0.4999999, not 0.5).
  const testing_support::Refusal at = testing_support::At("parameter 'poisson_ratio'");
  const std::string above = RefusalOf("block", "poisson_ratio", "0.5");
  EXPECT_TRUE(testing_support::RefusedAt(above, "problem 'block'", at));
  EXPECT_EQ(testing_support::NumbersIn(above), (std::vector<double>{0.5, 0.4999999})) << above;
  const std::string below = RefusalOf("block", "poisson_ratio", "-1");
  EXPECT_TRUE(testing_support::RefusedAt(below, "problem 'block'", at));
  EXPECT_EQ(testing_support::NumbersIn(below), (std::vector<double>{-1.0, -1.0})) << below;
}

TEST(ProblemsTest, ReconstructionChoicesAreParameters) {
  // The printed W = 75 m of P3 can be tried as a half-span: H1 becomes 4.2746 m.
  const Problem p = MakeProblem("arch-curved", {{"half_span", "75"}});
  EXPECT_NEAR(LowestNodeDepth(p), 4.2746, 5e-5);
  const Problem flat = MakeProblem("arch-curved", {{"lower_obstacle", "flat"}});
  EXPECT_EQ(flat.name, "arch-curved");
  EXPECT_TRUE(flat.model->num_pairs() == 210);
}

}  // namespace
}  // namespace cb
