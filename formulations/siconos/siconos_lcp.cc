#include "formulations/siconos/siconos_lcp.h"

#include <cmath>
#include <stdexcept>

#include "model/complementarity_model.h"

namespace cb {

namespace {

bool IsLcpModel(const StepProblem& step) {
  return dynamic_cast<const ComplementarityModel*>(step.model) != nullptr &&
         step.model->is_linear();
}

// K = hess pi(u^k), factorised; null with the reason when it is singular. A sparse Cholesky or
// LU of a matrix singular only by its rigid-body modes may not see a zero pivot in floating
// point, so the factors are also tried on a right-hand side that is generically outside the
// range of a singular K: a backward-stable solve of a nonsingular K leaves a residual of the
// order of the rounding, a singular one of the order of the right-hand side.
std::unique_ptr<LinearSolver> FactorStiffness(const StepProblem& step,
                                              const std::string& linear_solver,
                                              std::string* message) {
  SpMat k;
  step.model->Stiffness(step.base.u, &k);
  auto solver = MakeLinearSolver(linear_solver);
  if (!solver->Factorize(k)) {
    *message = solver->message();
    return nullptr;
  }
  Vec probe(k.rows()), x;
  for (Eigen::Index i = 0; i < probe.size(); ++i) probe[i] = std::sin(1.0 + static_cast<double>(i));
  constexpr double kSingularResidual = 1e-6;  // relative; rounding leaves ~1e-16 * cond(K)
  if (!solver->Solve(probe, &x) || !x.allFinite() ||
      (k * x - probe).norm() > kSingularResidual * probe.norm()) {
    *message = "a solve with its factors leaves a relative residual above 1e-6";
    return nullptr;
  }
  return solver;
}

}  // namespace

bool SteppedLcp::CheckStep(const std::string& formulation, const StepProblem& step, int max_size,
                           std::string* why) {
  if (step.constraint.kind != ConstraintKind::kFixedLoad) {
    *why = formulation + " cannot express the step constraint '" + ToString(step.constraint.kind) +
           "' (an LCP has no load factor among its unknowns: fixed-load steps only)";
    return false;
  }
  if (!step.model->is_linear()) {
    *why = formulation +
           ": the model is not linear (large deformation or a curved obstacle), so the step is "
           "no LCP; Siconos 4.4's MCP solver, which could take it, is not used (its "
           "Fischer-Burmeister Jacobian with equality rows is wrong before 4.5; "
           "docs/backend-siconos.md)";
    return false;
  }
  const int n = step.num_pairs();
  if (n < 1) {
    *why = formulation + ": the model has no contact pairs, so there is no LCP to solve";
    return false;
  }
  if (n > max_size) {
    *why = formulation + ": the LCP would have " + std::to_string(n) +
           " unknowns, above the dense limit max_size = " + std::to_string(max_size) +
           " (Siconos's LCP solvers work on a dense M)";
    return false;
  }
  return true;
}

bool SteppedLcp::CanReduce(const std::string& formulation, const StepProblem& step, int max_size,
                           const std::string& linear_solver, std::string* why) {
  if (!CheckStep(formulation, step, max_size, why)) return false;
  if (IsLcpModel(step)) return true;
  std::string message;
  if (FactorStiffness(step, linear_solver, &message) == nullptr) {
    *why = formulation +
           ": the stiffness K is singular (a body held only by its contacts has rigid-body "
           "modes), so the displacements cannot be eliminated into an LCP (" +
           message + ")";
    return false;
  }
  return true;
}

SteppedLcp::SteppedLcp(const StepProblem& step, const std::string& linear_solver)
    : SteppedLcp(step, linear_solver,
                 IsLcpModel(step) ? Kind::kAsGiven : Kind::kEliminatedDisplacements) {}

SteppedLcp::SteppedLcp(const StepProblem& step, const std::string& linear_solver, Kind kind)
    : step_(step), kind_(kind) {
  std::string why;
  if (!CheckStep("SteppedLcp", step, step.num_pairs(), &why)) {
    throw std::invalid_argument(why);
  }
  if (kind == Kind::kAsGiven) {
    if (!IsLcpModel(step)) {
      throw std::invalid_argument("SteppedLcp: kind kAsGiven needs a linear ComplementarityModel");
    }
    BuildAsGiven();
  } else {
    BuildEliminated(linear_solver);
  }
}

// M^ = (L / R) M, q^ = (q - lambda f) / R, with M = hess pi and q - lambda f = grad pi(0) - lambda
// f.
void SteppedLcp::BuildAsGiven() {
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const double lambda = step_.constraint.target;
  SpMat k;
  step_.model->Stiffness(step_.base.u, &k);
  m_ = (length / force) * Mat(k);
  Vec f0;
  step_.model->InternalForce(Vec::Zero(step_.num_dofs()), &f0);
  q_ = (f0 - lambda * step_.model->load_pattern()) / force;
}

// M^ = (R / L) G K^-1 G^T, q^ = -(phi(u^k) + G K^-1 b) / L (the top of the header).
void SteppedLcp::BuildEliminated(const std::string& linear_solver) {
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const StepProblem& s = step_;
  std::string message;
  auto k = FactorStiffness(s, linear_solver, &message);
  if (k == nullptr) throw std::invalid_argument("SteppedLcp: K is singular: " + message);
  Vec internal, phi;
  s.model->InternalForce(s.base.u, &internal);
  s.model->Gaps(s.base.u, &phi);
  const Vec b = s.constraint.target * s.model->load_pattern() - internal;
  if (!k->Solve(b, &k_inv_b_)) throw std::invalid_argument("SteppedLcp: " + k->message());
  SpMat g;
  s.model->GapJacobian(s.base.u, &g);
  const Mat gt = Mat(SpMat(g.transpose()));
  k_inv_gt_.resize(s.num_dofs(), s.num_pairs());
  Vec column;
  for (int p = 0; p < s.num_pairs(); ++p) {
    if (!k->Solve(gt.col(p), &column)) throw std::invalid_argument("SteppedLcp: " + k->message());
    k_inv_gt_.col(p) = column;
  }
  m_ = (force / length) * (g * k_inv_gt_);
  m_ = 0.5 * (m_ + m_.transpose()).eval();  // symmetric to rounding, as G K^-1 G^T is
  q_ = -(phi + g * k_inv_b_) / length;
}

Vec SteppedLcp::ZFromPoint(const Vec& du, const Vec& r) const {
  if (kind_ == Kind::kAsGiven) return ((step_.base.u + du) / step_.scales.length).cwiseMax(0.0);
  return (-r / step_.scales.force).cwiseMax(0.0);
}

StepPoint SteppedLcp::PointFromZ(const Vec& z) const {
  const StepProblem& s = step_;
  StepPoint point;
  point.dlambda = s.constraint.target - s.base.lambda;
  if (kind_ == Kind::kAsGiven) {
    // u = z, and r from (29): r = lambda f - grad pi(u) (= -w).
    const Vec u = s.scales.length * z;
    point.du = u - s.base.u;
    Vec internal;
    s.model->InternalForce(u, &internal);
    point.r = s.constraint.target * s.model->load_pattern() - internal;
  } else {
    point.r = -s.scales.force * z;
    point.du = k_inv_b_ + k_inv_gt_ * point.r;
  }
  Vec phi;
  s.model->Gaps(s.base.u + point.du, &phi);
  point.g = -phi;
  return point;
}

}  // namespace cb
