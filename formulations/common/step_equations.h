// What the equation formulations of a step (implicit-fb, nonsmooth-fb, active-set) share: the
// scaled unknowns, the rows (29) / R, (30) / L and the step constraint (33) (or its
// replacements), their Jacobian blocks assembled through one cached ScatterPattern, the start
// points of docs/method.md section 4, and the bookkeeping of a solve. Each formulation adds only
// its complementarity rows (and, for implicit-fb, the smoothing unknown rho with its row (32)).
//
// Unknowns x = (du, g^, r^, dlambda[, rho]) with g^ = g / L, r^ = r / R; rows
//   F1 = (grad pi(u) - lambda f) / R - grad phi(u)^T r^       (29) / R,   d rows
//   F2 = g^ + phi(u) / L                                        (30) / L,   nc rows
//   F3_p = C(g^_p, -r^_p[, rho])                                (31) or its nonsmooth variant
//          (for the pair of a kink step, g^_p + r^_p: see StepEquationSystem::Residual)
//  [F4 = the formulation's extra row (implicit-fb: (32) / nc)]
//   F5 = step constraint c (StepConstraintValue)                (33) etc., 1 row.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "core/sparse.h"
#include "core/timer.h"
#include "solvers/equation_solver.h"
#include "step/formulation.h"

namespace cb {

// Positions of the unknowns and rows. `has_rho` adds the unknown rho after dlambda and one row
// (the formulation's own) between the complementarity rows and the step-constraint row.
struct StepEquationLayout {
  int d = 0;
  int nc = 0;
  bool has_rho = false;
  int du() const { return 0; }
  int g() const { return d; }
  int r() const { return d + nc; }
  int dlambda() const { return d + 2 * nc; }
  int rho() const { return d + 2 * nc + 1; }  // only when has_rho
  int complementarity_row() const { return d + nc; }
  int extra_row() const { return d + 2 * nc; }  // only when has_rho
  int constraint_row() const { return size() - 1; }
  int size() const { return d + 2 * nc + 1 + (has_rho ? 1 : 0); }
};

// psi(a, b, rho) = sqrt(a^2 + b^2 + 2 rho^2) - (a + b), (12); rho = 0 is the plain
// Fischer-Burmeister function.
double SmoothedFischerBurmeister(double a, double b, double rho);

// An element of the generalised Jacobian of psi at (a, b, rho): the gradient where
// s = sqrt(a^2 + b^2 + 2 rho^2) > 0, and at s = 0 (a = b = rho = 0) the element
// (1/sqrt2 - 1, 1/sqrt2 - 1, 0). That is the limit of the gradient along a = b = t -> 0+,
// hence an element of the B-subdifferential (the construction of De Luca, Facchinei and
// Kanzow, Math. Prog. 75 (1996), with the direction z = e_g - e_r on the degenerate pair,
// i.e. (a, b) moving along (1, 1)); the Clarke Jacobian there is the disc
// {(xi - 1, eta - 1) : xi^2 + eta^2 <= 1}, and this element keeps both partials negative,
// so the row stays a regular combination of the "gap" and "reaction" equations.
void FischerBurmeisterElement(double a, double b, double rho, double* d_a, double* d_b,
                              double* d_rho);

// ||min(g^, -r^)||_inf over the pairs of x laid out as `layout` (the history's comp_res).
double ComplementarityResidual(const StepEquationLayout& layout, const Vec& x);

// Moves (du, dlambda) onto the step constraint where that is a matter of the increment alone:
// onto the arc-length sphere by scaling, or to the prescribed load / displacement.
void FitIncrementToConstraint(const StepProblem& step, Eigen::Ref<Vec> du, double* dlambda);

// The start of docs/method.md section 4 in the scaled unknowns (du, g^, r^, dlambda) of a vector of
// size `size` (entries beyond dlambda are left zero):
//  warm: du0, dlambda0 from `start` fitted to the constraint (38), (41), r^0 = r^k / R (40),
//        g^0 = -phi(u^k + du0) / L (39), so (30) and (33) hold exactly;
//  cold (report section 5.1): du0 = 0, g^0 = -1, r^0 = +1, dlambda0 fitted to the constraint.
Vec MakeStepEquationStart(const StepProblem& step, const StartPoint& start, int size);

// The answer in physical units from the scaled unknowns x of `layout`: du and dlambda as they
// are, g = L g^ and r = R r^ (the scales of psi, docs/method.md section 4).
StepPoint PointFromScaled(const StepProblem& step, const StepEquationLayout& layout, const Vec& x);

// The square system of one step with the common blocks; derived classes provide the
// complementarity rows and, with rho, the extra row.
class StepEquationSystem : public EquationSystem {
 public:
  // The Jacobian pattern, built on first use and reusable by later systems of the same model,
  // constraint kind and index, and layout (a path analyses it once).
  struct PatternCache;
  // An empty cache to share between the systems of a formulation's steps.
  static std::shared_ptr<PatternCache> MakePatternCache();

  ~StepEquationSystem() override;
  int size() const override { return layout_.size(); }
  bool Residual(const Vec& x, Vec* residual) final;
  void Jacobian(const Vec& x, SpMat* jacobian) final;
  bool ResidualAndJacobian(const Vec& x, Vec* residual, SpMat* jacobian) final;
  bool shares_residual_and_jacobian() const final { return true; }
  // The rows of (29) / R sum the elements' forces, the load and the reactions: their floor is
  // kRoundingUnits eps (sum_e |f_e,i| + |lambda f_i|) / R + eps |grad phi^T r^|_i
  // (ContactModel::InternalForceMagnitudes), which a problem whose forces dwarf its force scale
  // R lifts above the absolute test. The other rows sum terms of the size of the scaled
  // unknowns and keep the absolute test (floor 0). Costs one residual evaluation and one of
  // the magnitudes.
  bool ResidualFloor(const Vec& x, Vec* floor) final;
  // The block structure of JacobianStructure with v = du, coupling = L (dF1/dr^ = -grad phi^T,
  // dF2/ddu = grad phi / L), y = (dlambda[, rho]); offered when the model has an energy (so
  // dF1/ddu is symmetric).
  const JacobianStructure* structure() const final {
    return has_structure_ ? &structure_ : nullptr;
  }
  // The pattern Jacobian() fills (its values unspecified): the cached one when the cache holds
  // this system's, otherwise built from the blocks' patterns at x without evaluating the
  // stiffness or any value of the Jacobian.
  const SpMat& JacobianPattern(const Vec& x);
  const StepEquationLayout& layout() const { return layout_; }
  const StepProblem& step() const { return step_; }

  // Adds values to a Jacobian in the order of the entries appended to the pattern.
  struct Cursor {
    double* values;
    const int* slots;
    std::size_t k;
    void Add(double value) { values[slots[k++]] += value; }
    void Skip() { ++k; }
  };

 protected:
  StepEquationSystem(const StepProblem& step, bool has_rho, std::shared_ptr<PatternCache> cache);

  // The complementarity row of a pair (a = g^_p, b = -r^_p, rho = 0 without rho).
  virtual double Complementarity(double a, double b, double rho) const = 0;
  // An element of its generalised Jacobian: partials in a, b and rho.
  virtual void ComplementarityElement(double a, double b, double rho, double* d_a, double* d_b,
                                      double* d_rho) const = 0;
  // With rho: the extra row's value, its pattern (appended in fill order) and its values.
  virtual double ExtraRow(const Vec& /*x*/) const { return 0.0; }
  virtual void AppendExtraRowEntries(std::vector<ScatterPattern::Entry>* /*entries*/) const {}
  virtual void FillExtraRow(const Vec& /*x*/, Cursor* /*cursor*/) const {}

 private:
  // The unknowns of x as views (see the top of the file); Split also sets u_ = u^k + du.
  struct Unknowns {
    Eigen::VectorBlock<const Vec> du, g, r;
    double dlambda, rho;  // rho = 0 without rho
  };
  Unknowns Split(const Vec& x);
  // Whether the cache holds the pattern of this model, constraint and layout.
  bool CacheHoldsThisSystem() const;
  // The cache's pattern from the blocks' patterns in curvature_ and gap_jacobian_.
  void BuildPattern();
  // The pieces of Residual and Jacobian, shared with ResidualAndJacobian.
  bool FillResidual(const Vec& x, const Unknowns& unknowns, Vec* residual) const;
  void StartJacobian(SpMat* jacobian);
  void FillJacobian(const Vec& x, const Unknowns& unknowns, SpMat* jacobian) const;

  const StepProblem& step_;
  StepEquationLayout layout_;
  std::shared_ptr<PatternCache> cache_;
  JacobianStructure structure_;
  bool has_structure_ = false;
  // Work storage reused across evaluations.
  Vec u_, internal_, phi_, reaction_, reaction_force_;
  SpMat curvature_, gap_jacobian_;
  Vec force_magnitudes_;  // ContactModel::InternalForceMagnitudes, for ResidualFloor
};

// The bookkeeping around a solve of the step equations, one for the full system
// (RunStepEquationSolver) and the reduced one (RunReducedStepSolver), which differ only in the
// iterate the solver sees. Made when the solve starts (its clock times the solve).
class StepSolveBookkeeping {
 public:
  StepSolveBookkeeping(const SolveControls& controls, StepResult* result)
      : controls_(controls), result_(result) {}
  // The solver's callback: appends the iterate to result->history with comp_res =
  // `comp_res(iterate)`, shows it to `on_iteration` (if given), then stops the solve on the
  // interrupt hook or past the time limit.
  IterationCallback Observer(std::function<double(const Vec&)> comp_res,
                             std::function<void(const Vec&)> on_iteration = {});
  // A stop of Observer's past the time limit as Status::kTimeLimit with TimeLimitMessage.
  void MarkTimeLimit(SolverSummary* summary) const;
  // Fills result from `summary` and the full scaled answer x: status, message, counts, the point
  // in physical units and details["final_merit"].
  void FillResult(const StepEquationSystem& system, const Vec& x,
                  const SolverSummary& summary) const;

 private:
  const SolveControls& controls_;
  StepResult* result_;
  Stopwatch clock_;
  bool timed_out_ = false;
};

// Runs `solver` on `system` from *x, recording the per-iteration history (with comp_res from
// the scaled g^, r^), honouring the time limit and the interrupt hook, and fills `result`:
// status, message, counts, the point in physical units and details["final_merit"].
// `on_iteration`, if given, sees each iterate after it is recorded.
SolverSummary RunStepEquationSolver(EquationSolver& solver, StepEquationSystem& system, Vec* x,
                                    const SolveControls& controls, StepResult* result,
                                    const std::function<void(const Vec&)>& on_iteration = {});

}  // namespace cb
