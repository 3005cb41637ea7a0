// Shared test fixtures with known answers (docs/architecture.md, house rule 5): each is a step (or
// an arc-length path) of a contact model with a CheckSolution that judges an accepted state against
// the answer known independently of any formulation. Every formulation's tests run the same
// fixtures (tests/formulations_test.cc).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/complementarity_model.h"
#include "path/path.h"
#include "problems/problem.h"
#include "step/formulation.h"
#include "verdict/verdict.h"

namespace cb::fixtures {

struct Fixture {
  std::string name;  // letters, digits and '_' (a test-name part)
  Problem problem;   // the model, its scales and the parameters of the closed forms
  // false: one step from `base` under `constraint`; true: an arc-length path of `steps` steps of
  // size `theta` from the zero state.
  bool path = false;
  State base;
  StepConstraint constraint;
  int steps = 0;
  double theta = 0.0;
  // The answer is unique, so every formulation must agree with implicit-fb on it.
  bool unique = true;
  // The report's cold start g^0 = -1, r^0 = +1 is meaningful (a fixed start far from a path's
  // later steps is not: docs/findings.md "Known limitations"; nor on the Kojima-Shindo NCP, see
  // there).
  bool cold_start = true;
  std::function<::testing::AssertionResult(const State&)> check;

  // Whether `state` (the base plus a step's increment) is the known answer.
  ::testing::AssertionResult CheckSolution(const State& state) const { return check(state); }
  StepProblem Step() const { return {problem.model.get(), base, constraint, problem.scales}; }
};

// A Problem around a generic complementarity model, with L = R = 1 (the verdict is then the
// problem's own natural residual).
inline Problem ComplementarityProblem(const std::string& name,
                                      std::shared_ptr<const ContactModel> model) {
  Problem p;
  p.name = name;
  p.description = "complementarity problem";
  p.units = "none";
  p.model = std::move(model);
  p.scales = {1.0, 1.0};
  p.loading = LoadingKind::kFixedLoad;
  p.load = 0.0;
  return p;
}

// ||a - b||_inf <= tol * max(||b||_inf, floor).
inline ::testing::AssertionResult RelativelyClose(const Vec& a, const Vec& b, double tol,
                                                  double floor, const std::string& what) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << what << ": sizes differ";
  if (a.size() == 0) return ::testing::AssertionSuccess();
  const double diff = (a - b).lpNorm<Eigen::Infinity>();
  const double scale = std::max(b.lpNorm<Eigen::Infinity>(), floor);
  if (diff <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << what << " differs by " << diff << " (relative " << diff / scale << " > " << tol << ")";
}

// A complementarity fixture: z is the state's u, w = -r (with lambda = 0). The base state is
// where a warm start begins (z0 = u + du0 with du0 = 0): u = `start` (zero by default) and
// r = -max(F(start), 0).
inline Fixture ComplementarityFixture(const std::string& name,
                                      std::shared_ptr<const ComplementarityModel> model,
                                      std::vector<Vec> solutions, const Vec& start = Vec()) {
  Fixture f;
  f.name = name;
  f.problem = ComplementarityProblem(name, model);
  f.base = ZeroState(*model);
  if (start.size() > 0) f.base.u = start;
  // r = -max(w, 0) at the base (the warm start's r0): (29) holds at the start where F(z0) >= 0,
  // and the start has no adhesion (r0 > 0 is a start on the wrong side, where Newton stalls).
  Vec w0;
  model->InternalForce(f.base.u, &w0);
  f.base.r = -w0.cwiseMax(0.0);
  f.constraint = StepConstraint::FixedLoad(0.0);
  f.unique = solutions.size() == 1;
  f.check = [model = std::move(model),
             solutions = std::move(solutions)](const State& s) -> ::testing::AssertionResult {
    Vec w;
    model->InternalForce(s.u, &w);
    if ((w + s.r).lpNorm<Eigen::Infinity>() > 1e-8) {
      return ::testing::AssertionFailure() << "r != -w: " << (w + s.r).transpose();
    }
    std::ostringstream tried;
    for (const Vec& z : solutions) {
      if ((s.u - z).lpNorm<Eigen::Infinity>() <= 1e-6) return ::testing::AssertionSuccess();
      tried << " (" << z.transpose() << ")";
    }
    return ::testing::AssertionFailure()
           << "z = " << s.u.transpose() << " is none of" << tried.str();
  };
  return f;
}

// The LCP M = [[2, 1], [1, 2]], q = (-5, -6): z = (4/3, 7/3), w = 0 (M symmetric: an energy).
inline std::shared_ptr<const ComplementarityModel> Lcp2Model() {
  Mat m(2, 2);
  m << 2, 1, 1, 2;
  Vec q(2);
  q << -5, -6;
  return std::make_shared<ComplementarityModel>(ComplementarityModel::Lcp(m, q));
}

// The 4 x 4 LCP of the issue (M positive semidefinite, not symmetric): z = (2.8, 0, 0.8, 1.2),
// w = (0, 0.4, 0, 0). Unique: two solutions of a monotone LCP differ by d with
// (M + M^T) d = 0, i.e. d3 = d4 = 0, and keeping w3 = w4 = 0 (z3, z4 > 0) forces
// d1 - d2 = d1 + 2 d2 = 0.
inline std::shared_ptr<const ComplementarityModel> Lcp4Model() {
  Mat m(4, 4);
  m << 0, 0, -1, -1, 0, 0, 1, -2, 1, -1, 2, -2, 1, 2, -2, 4;
  Vec q(4);
  q << 2, 2, -2, -6;
  return std::make_shared<ComplementarityModel>(
      ComplementarityModel::Lcp(SpMat(m.sparseView()), q));
}

// The Kojima-Shindo NCP: solutions (1, 0, 3, 0) (nondegenerate) and (sqrt(6)/2, 0, 0, 1/2)
// (degenerate: z3 = w3 = 0).
inline std::shared_ptr<const ComplementarityModel> KojimaShindoModel() {
  auto f = [](const Vec& x, Vec* v) {
    v->resize(4);
    (*v)[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
    (*v)[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 10 * x[2] + 2 * x[3] - 2;
    (*v)[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 9 * x[3] - 9;
    (*v)[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
  };
  auto j = [](const Vec& x, Mat* m) {
    m->resize(4, 4);
    *m << 6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3,  //
        4 * x[0] + 1, 2 * x[1], 10, 2,                     //
        6 * x[0] + x[1], x[0] + 4 * x[1], 2, 9,            //
        2 * x[0], 6 * x[1], 2, 3;
  };
  return std::make_shared<ComplementarityModel>(ComplementarityModel::Ncp(4, f, j));
}

// A fixed-load solve of a problem from its unloaded state and the verdict on its answer.
struct JudgedSolve {
  PathSummary summary;
  Verdict verdict;
};

// Solves `p` at the load `lambda` from the unloaded state with `formulation` (`start`: the warm
// start from the unloaded state, as `contactbench run`, or the formulation's cold start) and
// judges the final state as the answer of that one step (tolerance 1e-8).
inline JudgedSolve SolveAndJudge(const Problem& p, Formulation& formulation, double lambda,
                                 StartKind start = StartKind::kWarm) {
  PathOptions options;
  options.start = start;
  JudgedSolve out;
  out.summary = SolveFixedLoad(*p.model, p.scales, ZeroState(*p.model), lambda, formulation,
                               options, nullptr);
  const StepProblem step{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(lambda),
                         p.scales};
  const State& s = out.summary.final_state;
  out.verdict = Judge(step, {s.u, Vec(), s.r, lambda}, 1e-8);
  return out;
}

// Two-bar truss closed form (src/problems/verification.cc): lambda(w), w the apex height.
struct TwoBarClosedForm {
  double b, h, ea, load;
  double Lambda(double w) const {
    const double l = std::sqrt(b * b + w * w);
    const double length = std::sqrt(b * b + h * h);
    return 2.0 * ea / load * (1.0 / l - 1.0 / length) * w;
  }
  double LimitHeight() const {  // l^3 = b^2 L
    const double length = std::sqrt(b * b + h * h);
    const double l = std::cbrt(b * b * length);
    return std::sqrt(l * l - b * b);
  }
};

inline TwoBarClosedForm TwoBarOf(const Problem& p) {
  const Parameters& q = p.parameters;
  return {q.Real("half_span"), q.Real("height"), q.Real("axial_stiffness"), q.Real("load")};
}

// The apex on the floor at w = floor_height carries r = -(lambda - lambda(floor)) P (P = 1);
// above it lambda = lambda(w).
inline ::testing::AssertionResult CheckTwoBarObstacle(const Problem& p, const State& s) {
  const TwoBarClosedForm t = TwoBarOf(p);
  const double floor = p.parameters.Real("floor_height");
  const double w = t.h + s.u[p.control_dof];
  if (s.r[0] < -1e-9 || std::abs(w - floor) < 1e-9) {
    if (std::abs(w - floor) > 1e-8 || std::abs(s.r[0] + (s.lambda - t.Lambda(floor))) > 1e-8) {
      return ::testing::AssertionFailure()
             << "on the floor: w = " << w << " (floor " << floor << "), r = " << s.r[0]
             << " (closed form " << -(s.lambda - t.Lambda(floor)) << ")";
    }
    return ::testing::AssertionSuccess();
  }
  if (std::abs(s.lambda - t.Lambda(w)) > 1e-8) {
    return ::testing::AssertionFailure()
           << "free: lambda = " << s.lambda << ", closed form " << t.Lambda(w) << " at w = " << w;
  }
  return ::testing::AssertionSuccess();
}

inline std::vector<Fixture> MakeFixtures() {
  std::vector<Fixture> out;
  {
    Vec z(2);
    z << 4.0 / 3.0, 7.0 / 3.0;
    out.push_back(ComplementarityFixture("lcp2", Lcp2Model(), {z}));
  }
  {
    Vec z(4);
    z << 2.8, 0.0, 0.8, 1.2;
    out.push_back(ComplementarityFixture("lcp4", Lcp4Model(), {z}));
  }
  {
    Vec z1(4), z2(4);
    z1 << 1.0, 0.0, 3.0, 0.0;
    z2 << std::sqrt(6.0) / 2.0, 0.0, 0.0, 0.5;
    // Started at z = (1, 1, 1, 1): at z = 0 the Jacobian of F has a zero column (x2 enters
    // only quadratically), and Newton-type methods stall there.
    // The cold start (g^0 = -1, r^0 = +1, ignoring z0) is left out: from it Newton on the FB,
    // smoothed-FB and min equations stalls at a stationary point of the merit away from both
    // solutions (measured: implicit-fb, nonsmooth-fb and active-set alike).
    out.push_back(
        ComplementarityFixture("kojima_shindo", KojimaShindoModel(), {z1, z2}, Vec::Ones(4)));
    out.back().cold_start = false;
  }
  {
    // Bar against a wall at lambda = 2 > lambda_c = E A gap / (P L) = 1: u = gap, r = -1.
    Fixture f;
    f.name = "bar_wall";
    f.problem = MakeProblem("bar-wall");
    f.base = ZeroState(*f.problem.model);
    f.constraint = StepConstraint::FixedLoad(2.0);
    const Problem& p = f.problem;
    const double ea = p.parameters.Real("axial_stiffness");
    const double gap = p.parameters.Real("gap");
    const double length = p.parameters.Real("length");
    const double load = p.parameters.Real("load");
    const int dof = p.control_dof;
    f.check = [=](const State& s) -> ::testing::AssertionResult {
      const double lambda_c = ea * gap / (load * length);
      const double u = s.lambda <= lambda_c ? s.lambda * load * length / ea : gap;
      const double r = s.lambda <= lambda_c ? 0.0 : -(s.lambda * load - ea * gap / length);
      if (std::abs(s.u[dof] - u) > 1e-10 || std::abs(s.r[0] - r) > 1e-8) {
        return ::testing::AssertionFailure()
               << "u = " << s.u[dof] << " (" << u << "), r = " << s.r[0] << " (" << r << ")";
      }
      return ::testing::AssertionSuccess();
    };
    out.push_back(std::move(f));
  }
  {
    // The two-bar truss onto a floor, ~60 arc-length steps of 0.02 through the contact kink
    // (as tests/path_test.cc): every accepted state on the closed form.
    Fixture f;
    f.name = "two_bar_obstacle_path";
    f.problem = MakeProblem("two-bar-obstacle");
    f.path = true;
    f.base = ZeroState(*f.problem.model);
    f.steps = 60;
    f.theta = 0.02;
    f.cold_start = false;
    // The path is unique, but the states sampled on it depend on each formulation's cut-backs:
    // the closed form, not implicit-fb's samples, is the answer to compare with.
    f.unique = false;
    const Problem p = f.problem;
    f.check = [p](const State& s) { return CheckTwoBarObstacle(p, s); };
    out.push_back(std::move(f));
  }
  {
    // The same truss at the fixed load lambda = 0.6, above the limit load lambda(w*) ~ 0.384 of
    // the free branch (w* the limit height): no free equilibrium exists above the floor
    // (lambda(w) <= lambda(w*) for floor <= w <= h), so the only answer is the apex on the
    // floor with r = -(0.6 - lambda(floor)). (Between lambda(floor) ~ 0.201 and the limit load
    // there would be three equilibria.) The step starts from the state where the apex just
    // touches the floor (lambda(floor), r = 0): from the unloaded state Newton meets the
    // limit point, where the free branch's stiffness is singular, and stops there.
    Fixture f;
    f.name = "two_bar_obstacle_step";
    f.problem = MakeProblem("two-bar-obstacle");
    const Problem p = f.problem;
    f.base = ZeroState(*f.problem.model);
    f.base.u[p.control_dof] = p.parameters.Real("floor_height") - TwoBarOf(p).h;
    f.base.lambda = TwoBarOf(p).Lambda(p.parameters.Real("floor_height"));
    f.constraint = StepConstraint::FixedLoad(0.6);
    f.check = [p](const State& s) -> ::testing::AssertionResult {
      const double floor = p.parameters.Real("floor_height");
      const double w = TwoBarOf(p).h + s.u[p.control_dof];
      if (std::abs(w - floor) > 1e-8) {
        return ::testing::AssertionFailure() << "apex at " << w << ", not on the floor " << floor;
      }
      return CheckTwoBarObstacle(p, s);
    };
    out.push_back(std::move(f));
  }
  {
    // P1 at n = 10, the report's fixed-load solve: the wall and the floor carry the two 10 kN
    // components of the edge traction (-0.5 MPa x 2 m x 0.01 m each way); the rest of the
    // answer is compared with implicit-fb (unique: small deformation, convex energy).
    Fixture f;
    f.name = "block_n10";
    f.problem = MakeProblem("block", {{"n", "10"}});
    f.base = ZeroState(*f.problem.model);
    f.constraint = StepConstraint::FixedLoad(f.problem.load);
    constexpr int n = 10;
    f.check = [](const State& s) -> ::testing::AssertionResult {
      const double wall = s.r.head(n + 1).sum();
      const double floor = s.r.tail(n + 1).sum();
      if (std::abs(wall + 1e4) > 1e-4 || std::abs(floor + 1e4) > 1e-4) {
        return ::testing::AssertionFailure()
               << "wall carries " << wall << ", floor " << floor << " (expected -1e4 each)";
      }
      return ::testing::AssertionSuccess();
    };
    out.push_back(std::move(f));
  }
  return out;
}

inline const std::vector<Fixture>& Fixtures() {
  static const std::vector<Fixture> fixtures = MakeFixtures();
  return fixtures;
}

inline const Fixture& FindFixture(const std::string& name) {
  for (const Fixture& f : Fixtures()) {
    if (f.name == name) return f;
  }
  throw std::invalid_argument("no fixture " + name);
}

// A step constraint of each kind on `model`, as the derivative tests use them: an arc length
// with a lambda weight other than 1, a fixed load, a displacement of dof 0, the kink condition
// (53) of the last pair, a hyperplane whose normal has every dof and the load.
inline StepConstraint ConstraintOf(ConstraintKind kind, const ContactModel& model) {
  switch (kind) {
    case ConstraintKind::kArcLength:
      return StepConstraint::ArcLength(0.1, 0.7);
    case ConstraintKind::kFixedLoad:
      return StepConstraint::FixedLoad(4.0);
    case ConstraintKind::kDisplacement:
      return StepConstraint::Displacement(0, 0.01);
    case ConstraintKind::kKink:
      return StepConstraint::Kink(model.num_pairs() - 1);
    case ConstraintKind::kHyperplane: {
      Vec normal(model.num_dofs());
      for (int j = 0; j < normal.size(); ++j) normal[j] = j % 3 == 0 ? 1.0 : -0.5;
      return StepConstraint::Hyperplane(normal, 0.3, 0.1);
    }
  }
  return {};
}

// Every constraint kind.
inline constexpr ConstraintKind kAllConstraintKinds[] = {
    ConstraintKind::kArcLength, ConstraintKind::kFixedLoad, ConstraintKind::kDisplacement,
    ConstraintKind::kKink, ConstraintKind::kHyperplane};

}  // namespace cb::fixtures
