#include "formulations/siconos/siconos_lcp.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "model/complementarity_model.h"
#include "solvers/linear_solver.h"

namespace cb {

namespace {

bool IsLcpModel(const StepProblem& step) {
  return dynamic_cast<const ComplementarityModel*>(step.model) != nullptr &&
         step.model->is_linear();
}

// The largest LCP a step can have (max_size counts the pairs).
bool CheckStep(const std::string& formulation, const StepProblem& step, int max_size,
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
           " pairs, above the dense limit max_size = " + std::to_string(max_size) +
           " (Siconos's LCP solvers work on a dense M)";
    return false;
  }
  return true;
}

// `k` factorised, or null when it is singular. A sparse Cholesky or LU of a matrix singular only
// by its rigid-body modes may not meet a zero pivot in floating point, so the factors are also
// tried on a right-hand side that is generically outside the range of a singular matrix: a
// backward-stable solve with a nonsingular one leaves a residual of the order of the rounding,
// with a singular one of the order of the right-hand side.
std::unique_ptr<LinearSolver> Factor(const SpMat& k, const std::string& linear_solver) {
  auto solver = MakeLinearSolver(linear_solver);
  if (!solver->Factorize(k)) return nullptr;
  Vec probe(k.rows()), x;
  for (Eigen::Index i = 0; i < probe.size(); ++i) probe[i] = std::sin(1.0 + static_cast<double>(i));
  constexpr double kSingularResidual = 1e-6;  // relative; rounding leaves ~1e-16 cond(K)
  if (!solver->Solve(probe, &x) || !x.allFinite() ||
      (k * x - probe).norm() > kSingularResidual * probe.norm()) {
    return nullptr;
  }
  return solver;
}

// c of K_c = K + c G^T G (the top of the header): 1e-3 times the smallest diagonal entry of K
// on a dof that a contact pair touches.
double RigidPenalty(const SpMat& k, const SpMat& g) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < g.outerSize(); ++j) {
    for (SpMat::InnerIterator it(g, j); it; ++it) {
      if (it.value() != 0.0) smallest = std::min(smallest, std::abs(k.coeff(j, j)));
    }
  }
  return std::isfinite(smallest) && smallest > 0.0 ? 1e-3 * smallest : 1.0;
}

// K factorised, or K_c with *penalty = c when K is singular; null when neither factorises (the
// contacts do not hold the body). Fills *k and *g.
std::unique_ptr<LinearSolver> FactorStiffness(const StepProblem& step,
                                              const std::string& linear_solver, SpMat* k, SpMat* g,
                                              double* penalty) {
  step.model->Stiffness(step.base.u, k);
  step.model->GapJacobian(step.base.u, g);
  *penalty = 0.0;
  if (auto solver = Factor(*k, linear_solver)) return solver;
  if (!step.model->has_energy()) return nullptr;  // the rigid modes need a symmetric K
  *penalty = RigidPenalty(*k, *g);
  const SpMat kc = *k + *penalty * SpMat(g->transpose() * *g);
  return Factor(kc, linear_solver);
}

}  // namespace

const char* SteppedLcp::KindName(Kind kind) {
  switch (kind) {
    case Kind::kAsGiven:
      return "as given";
    case Kind::kEliminatedDisplacements:
      return "displacements eliminated (M = G K^-1 G^T)";
    case Kind::kEliminatedWithRigidModes:
      return "displacements eliminated, rigid-body modes kept (K_c = K + c G^T G)";
  }
  return "?";
}

bool SteppedLcp::CanReduce(const std::string& formulation, const StepProblem& step, int max_size,
                           const std::string& linear_solver, std::string* why) {
  if (!CheckStep(formulation, step, max_size, why)) return false;
  if (IsLcpModel(step)) return true;
  SpMat k, g;
  double penalty = 0.0;
  if (FactorStiffness(step, linear_solver, &k, &g, &penalty) == nullptr) {
    *why = formulation +
           ": the stiffness K is singular and the contact pairs do not hold the body (nor is K "
           "symmetric), so the displacements cannot be eliminated into an LCP";
    return false;
  }
  return true;
}

SteppedLcp::SteppedLcp(const StepProblem& step, const std::string& linear_solver, bool eliminate)
    : step_(step) {
  std::string why;
  if (!CheckStep("SteppedLcp", step, step.num_pairs(), &why)) throw std::invalid_argument(why);
  if (IsLcpModel(step) && !eliminate) {
    kind_ = Kind::kAsGiven;
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
  SpMat k;
  step_.model->Stiffness(step_.base.u, &k);
  m_ = (length / force) * Mat(k);
  Vec f0;
  step_.model->InternalForce(Vec::Zero(step_.num_dofs()), &f0);
  q_ = (f0 - step_.constraint.target * step_.model->load_pattern()) / force;
}

// The two eliminated kinds (the top of the header); c = 0 for a nonsingular K.
void SteppedLcp::BuildEliminated(const std::string& linear_solver) {
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const StepProblem& s = step_;
  const int nc = s.num_pairs();
  SpMat k, g;
  auto solver = FactorStiffness(s, linear_solver, &k, &g, &penalty_);
  if (solver == nullptr) {
    throw std::invalid_argument(
        "SteppedLcp: K is singular and the contact pairs do not hold the body");
  }
  Vec internal, phi;
  s.model->InternalForce(s.base.u, &internal);
  s.model->Gaps(s.base.u, &phi);
  const Vec rhs = s.constraint.target * s.model->load_pattern() - internal -
                  penalty_ * Vec(g.transpose() * phi);
  if (!solver->Solve(rhs, &k_inv_b_))
    throw std::invalid_argument("SteppedLcp: " + solver->message());
  const Mat gt = Mat(SpMat(g.transpose()));
  k_inv_gt_.resize(s.num_dofs(), nc);
  Vec column;
  for (int p = 0; p < nc; ++p) {
    if (!solver->Solve(gt.col(p), &column)) {
      throw std::invalid_argument("SteppedLcp: " + solver->message());
    }
    k_inv_gt_.col(p) = column;
  }
  Mat a = g * k_inv_gt_;
  a = 0.5 * (a + a.transpose()).eval();  // symmetric to rounding, as G K_c^-1 G^T is
  const Vec h = -phi - g * k_inv_b_;
  if (penalty_ == 0.0) {
    kind_ = Kind::kEliminatedDisplacements;
    m_ = (force / length) * a;
    q_ = h / length;
    rigid_.resize(nc, 0);
    return;
  }
  kind_ = Kind::kEliminatedWithRigidModes;
  const Eigen::SelfAdjointEigenSolver<Mat> eigen(a);
  const Vec& s_all = eigen.eigenvalues();
  const Mat& v = eigen.eigenvectors();
  int rigid = 0;
  for (int i = 0; i < nc; ++i) rigid += penalty_ * s_all[i] > 0.5 ? 1 : 0;
  // Eigenvalues ascending: the rigid ones (c s = 1) are the last `rigid`.
  const int elastic = nc - rigid;
  const Mat v2 = v.leftCols(elastic);
  rigid_ = v.rightCols(rigid);
  const Vec s2 = s_all.head(elastic);
  const Vec one_minus = (1.0 - penalty_ * s2.array()).matrix();
  const Mat m_elastic =
      v2 * (s2.array() / one_minus.array()).matrix().asDiagonal() * v2.transpose();
  const Vec q_elastic = v2 * (v2.transpose() * h).cwiseQuotient(one_minus);
  const Vec e = -(rigid_.transpose() * h).cwiseQuotient(s_all.tail(rigid));
  const int n = nc + 2 * rigid;
  m_ = Mat::Zero(n, n);
  q_ = Vec::Zero(n);
  m_.topLeftCorner(nc, nc) = (force / length) * m_elastic;
  m_.block(0, nc, nc, rigid) = rigid_;
  m_.block(0, nc + rigid, nc, rigid) = -rigid_;
  m_.block(nc, 0, rigid, nc) = -rigid_.transpose();
  m_.block(nc + rigid, 0, rigid, nc) = rigid_.transpose();
  q_.head(nc) = q_elastic / length;
  q_.segment(nc, rigid) = e / force;
  q_.segment(nc + rigid, rigid) = -e / force;
}

Vec SteppedLcp::ZFromPoint(const Vec& du, const Vec& r) const {
  if (kind_ == Kind::kAsGiven) return ((step_.base.u + du) / step_.scales.length).cwiseMax(0.0);
  Vec z = Vec::Zero(size());
  z.head(step_.num_pairs()) = (-r / step_.scales.force).cwiseMax(0.0);
  return z;
}

StepPoint SteppedLcp::PointFromZ(const Vec& z) const {
  const StepProblem& s = step_;
  const int nc = s.num_pairs();
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
    point.r = -s.scales.force * z.head(nc);
    point.du = k_inv_b_ + k_inv_gt_ * point.r;
    if (kind_ == Kind::kEliminatedWithRigidModes) {
      // K_c du = b - c G^T phi(u^k) + G^T (r - c g), g = L (M^ z^ + q^ + V1 a^).
      const int m = num_rigid_modes();
      const Vec a = z.segment(nc, m) - z.segment(nc + m, m);
      const Vec g =
          s.scales.length * (m_.topLeftCorner(nc, nc) * z.head(nc) + q_.head(nc) + rigid_ * a);
      point.du -= penalty_ * (k_inv_gt_ * g);
    }
  }
  Vec phi;
  s.model->Gaps(s.base.u + point.du, &phi);
  point.g = -phi;
  return point;
}

}  // namespace cb
