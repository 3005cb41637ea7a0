#include "formulations/siconos/siconos_lcp.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>

#include "model/complementarity_model.h"

// A sparse Cholesky of K: CHOLMOD's supernodal one where the build has SuiteSparse (dense
// kernels on the many right-hand sides of the reduction), else Eigen's.
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif

namespace cb {

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
using SpdFactorization = Eigen::CholmodSupernodalLLT<SpMat>;
// Nothing in the library prints: CHOLMOD reports a matrix that is not positive definite (a
// singular K, expected here) on stderr unless told not to.
void Quiet(SpdFactorization* factor) {
  factor->cholmod().print = 0;
  factor->cholmod().error_handler = nullptr;
}
#else
using SpdFactorization = Eigen::SimplicialLDLT<SpMat>;
void Quiet(SpdFactorization*) {}
#endif

struct SteppedLcp::Factor {
  std::unique_ptr<SpdFactorization> factorization;
};

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
           "no LCP (Siconos's MCP solvers, which could take it, are not used: "
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

// Cholesky's requirement, and the rigid modes' (the eigen-decomposition of a symmetric A).
bool IsSymmetric(const SpMat& k) { return (k - SpMat(k.transpose())).norm() <= 1e-12 * k.norm(); }

// `k` (symmetric) factorised, or null when it is singular. A Cholesky factorisation of a matrix
// singular only by its rigid-body modes may not meet a zero pivot in floating point, so the
// factors are also tried on a right-hand side that is generically outside the range of a
// singular matrix: a solve with a nonsingular one leaves a residual of the order of the
// rounding, with a singular one of the order of the right-hand side.
std::unique_ptr<SpdFactorization> Factorize(const SpMat& k) {
  auto factor = std::make_unique<SpdFactorization>();
  Quiet(factor.get());
  factor->compute(k);
  if (factor->info() != Eigen::Success) return nullptr;
  Vec probe(k.rows());
  for (Eigen::Index i = 0; i < probe.size(); ++i) probe[i] = std::sin(1.0 + static_cast<double>(i));
  const Vec x = factor->solve(probe);
  constexpr double kSingularResidual = 1e-6;  // relative; rounding leaves ~1e-16 cond(K)
  if (factor->info() != Eigen::Success || !x.allFinite() ||
      (k * x - probe).norm() > kSingularResidual * probe.norm()) {
    return nullptr;
  }
  return factor;
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

// K factorised, or K_c with *penalty = c when K is singular; null when K is not symmetric or
// neither factorises (the contacts do not hold the body). Fills *g.
std::unique_ptr<SpdFactorization> FactorStiffness(const StepProblem& step, SpMat* g,
                                                  double* penalty) {
  SpMat k;
  step.model->Stiffness(step.base.u, &k);
  step.model->GapJacobian(step.base.u, g);
  *penalty = 0.0;
  if (!IsSymmetric(k)) return nullptr;
  if (auto factor = Factorize(k)) return factor;
  *penalty = RigidPenalty(k, *g);
  return Factorize(k + *penalty * SpMat(g->transpose() * *g));
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
                           std::string* why) {
  if (!CheckStep(formulation, step, max_size, why)) return false;
  if (IsLcpModel(step)) return true;
  SpMat g;
  double penalty = 0.0;
  if (FactorStiffness(step, &g, &penalty) == nullptr) {
    *why = formulation +
           ": the stiffness K is not symmetric, or singular with rigid-body modes that the "
           "contact pairs do not hold, so the displacements cannot be eliminated into an LCP";
    return false;
  }
  return true;
}

SteppedLcp::~SteppedLcp() = default;

SteppedLcp::SteppedLcp(const StepProblem& step, bool eliminate) : step_(step) {
  std::string why;
  if (!CheckStep("SteppedLcp", step, step.num_pairs(), &why)) throw std::invalid_argument(why);
  if (IsLcpModel(step) && !eliminate) {
    kind_ = Kind::kAsGiven;
    BuildAsGiven();
  } else {
    BuildEliminated();
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
void SteppedLcp::BuildEliminated() {
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const StepProblem& s = step_;
  const int nc = s.num_pairs();
  factor_ = std::make_unique<Factor>();
  factor_->factorization = FactorStiffness(s, &g_, &penalty_);
  const SpdFactorization* k = factor_->factorization.get();
  if (k == nullptr) {
    throw std::invalid_argument(
        "SteppedLcp: K is singular and the contact pairs do not hold the body, or K is not "
        "symmetric");
  }
  Vec internal, phi;
  s.model->InternalForce(s.base.u, &internal);
  s.model->Gaps(s.base.u, &phi);
  rhs_ = s.constraint.target * s.model->load_pattern() - internal -
         penalty_ * Vec(g_.transpose() * phi);
  const Vec k_inv_b = k->solve(rhs_);
  // A = G K_c^-1 G^T, a block of right-hand sides at a time (d x block at most in memory).
  const SpMat gt = g_.transpose();
  constexpr int kBlock = 64;
  Mat a(nc, nc);
  for (int first = 0; first < nc; first += kBlock) {
    const int cols = std::min(kBlock, nc - first);
    const Mat x = k->solve(Mat(gt.middleCols(first, cols)));
    a.middleCols(first, cols) = g_ * x;
  }
  a = 0.5 * (a + a.transpose()).eval();  // symmetric to rounding, as G K_c^-1 G^T is
  const Vec h = -phi - g_ * k_inv_b;
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
  rigid_ = CanonicalRigidBasis(v.rightCols(rigid));
  const Vec s2 = s_all.head(elastic);
  const Vec one_minus = (1.0 - penalty_ * s2.array()).matrix();
  const Mat m_elastic =
      v2 * (s2.array() / one_minus.array()).matrix().asDiagonal() * v2.transpose();
  const Vec q_elastic = v2 * (v2.transpose() * h).cwiseQuotient(one_minus);
  // V1^T (I - c A) = 0 and V1^T A = S1 V1^T with S1 = V1^T A V1 (~ I / c; diagonal only for
  // eigenvectors, which the canonical basis is not), so (I - c A) g = h - A r gives
  // V1^T z = e = -S1^-1 V1^T h.
  const Mat s1 = rigid_.transpose() * a * rigid_;
  const Vec e = -s1.ldlt().solve(rigid_.transpose() * h);
  // Both rows of each rigid equality relaxed by delta, so that no solution is degenerate (the
  // top of the header).
  relaxation_ = kRigidRelaxation * std::max(1.0, (e / force).lpNorm<Eigen::Infinity>());
  const int n = nc + 2 * rigid;
  m_ = Mat::Zero(n, n);
  q_ = Vec::Zero(n);
  m_.topLeftCorner(nc, nc) = (force / length) * m_elastic;
  m_.block(0, nc, nc, rigid) = rigid_;
  m_.block(0, nc + rigid, nc, rigid) = -rigid_;
  m_.block(nc, 0, rigid, nc) = -rigid_.transpose();
  m_.block(nc + rigid, 0, rigid, nc) = rigid_.transpose();
  q_.head(nc) = q_elastic / length;
  q_.segment(nc, rigid) = (e / force).array() + relaxation_;
  q_.segment(nc + rigid, rigid) = (-e / force).array() + relaxation_;
}

Mat SteppedLcp::CanonicalRigidBasis(const Mat& v1) {
  const Eigen::Index rows = v1.rows();
  const Eigen::Index cols = v1.cols();
  // Fixed reference vectors: std::mt19937's sequence is the standard's, the same everywhere,
  // and generic, so that their projections are independent (the rigid gaps of a model need not
  // be known here, only K and G).
  std::mt19937 generator(5489U);
  Mat x(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      x(i, j) = (static_cast<double>(generator()) + 0.5) / 4294967296.0 - 0.5;
    }
  }
  const Eigen::HouseholderQR<Mat> qr(Mat(v1 * (v1.transpose() * x)));
  Mat basis = qr.householderQ() * Mat::Identity(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    if (qr.matrixQR()(j, j) < 0.0) basis.col(j) = -basis.col(j);
  }
  return basis;
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
    // K_c du = b - c G^T phi(u^k) + G^T (r - c g) with g = L (M^ z^ + q^ + V1 a^); c = 0:
    // K du = b + G^T r.
    point.r = -s.scales.force * z.head(nc);
    Vec reaction = point.r;
    if (kind_ == Kind::kEliminatedWithRigidModes) {
      const int m = num_rigid_modes();
      const Vec a = z.segment(nc, m) - z.segment(nc + m, m);
      reaction -= penalty_ * s.scales.length *
                  (m_.topLeftCorner(nc, nc) * z.head(nc) + q_.head(nc) + rigid_ * a);
    }
    point.du = factor_->factorization->solve(Vec(rhs_ + g_.transpose() * reaction));
  }
  Vec phi;
  s.model->Gaps(s.base.u + point.du, &phi);
  point.g = -phi;
  return point;
}

}  // namespace cb
