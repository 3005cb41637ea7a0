#include "path/stability.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "core/abandonable_work.h"

namespace cb {

int UnstableModes(const ContactModel& model, const ContactScales& scales, const State& state) {
  return BorderedStiffness(model, scales, state, BorderedStiffness::Use::kModes).unstable_modes();
}

Vec GapsAt(const ContactModel& model, const Vec& u) {
  Vec phi;
  model.Gaps(u, &phi);
  return -phi;
}

std::vector<bool> ClosedPairs(const ContactScales& scales, const Vec& g, const Vec& r) {
  std::vector<bool> closed(g.size());
  for (int p = 0; p < g.size(); ++p) closed[p] = g[p] / scales.length + r[p] / scales.force < 0.0;
  return closed;
}

BorderedStiffness::BorderedStiffness(const ContactModel& model, const ContactScales& scales,
                                     const State& state, Use use)
    : dofs_(model.num_dofs()), pairs_(model.num_pairs()) {
  const std::vector<bool> closed = ClosedPairs(scales, GapsAt(model, state.u), state.r);
  for (int p = 0; p < pairs_; ++p) {
    if (closed[p]) closed_pairs_.push_back(p);
  }
  Build(model, state, use);
}

BorderedStiffness::BorderedStiffness(const ContactModel& model, const ContactScales& /*scales*/,
                                     const State& state, const std::vector<bool>& closed)
    : dofs_(model.num_dofs()), pairs_(model.num_pairs()) {
  for (int p = 0; p < pairs_; ++p) {
    if (closed[p]) closed_pairs_.push_back(p);
  }
  Build(model, state, Use::kModesAndSolves);
}

void BorderedStiffness::Build(const ContactModel& model, const State& state, Use use) {
  const int d = dofs_;
  SpMat stiffness, curvature, gap_jacobian;
  model.Stiffness(state.u, &stiffness);
  model.GapCurvature(state.u, state.r, &curvature);
  model.GapJacobian(state.u, &gap_jacobian);
  const int m = num_closed();
  std::vector<Triplet> t;
  t.reserve(stiffness.nonZeros() + curvature.nonZeros() + 4 * gap_jacobian.nonZeros());
  for (int j = 0; j < stiffness.outerSize(); ++j) {
    for (SpMat::InnerIterator it(stiffness, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  }
  for (int j = 0; j < curvature.outerSize(); ++j) {
    for (SpMat::InnerIterator it(curvature, j); it; ++it) t.emplace_back(it.row(), j, -it.value());
  }
  // Row index of each closed pair in the bordered system.
  std::vector<int> border(model.num_pairs(), -1);
  for (int k = 0; k < m; ++k) border[closed_pairs_[k]] = d + k;
  for (int j = 0; j < gap_jacobian.outerSize(); ++j) {
    for (SpMat::InnerIterator it(gap_jacobian, j); it; ++it) {
      const int row = border[it.row()];
      if (row < 0) continue;
      t.emplace_back(row, j, it.value());   // G_c
      t.emplace_back(j, row, -it.value());  // -G_c^T
    }
  }
  SpMat bordered(d + m, d + m);
  bordered.setFromTriplets(t.begin(), t.end());
  bordered.makeCompressed();

  // K_t + rho G_c^T G_c (the first d x d block of A plus the penalty) for the inertia.
  SpMat penalised = bordered.topLeftCorner(d, d);
  double diagonal = 0.0;
  for (int j = 0; j < d; ++j) diagonal = std::max(diagonal, std::abs(penalised.coeff(j, j)));
  SpMat closed_rows(m, d);
  {
    std::vector<Triplet> g;
    for (int j = 0; j < gap_jacobian.outerSize(); ++j) {
      for (SpMat::InnerIterator it(gap_jacobian, j); it; ++it) {
        if (border[it.row()] >= 0) g.emplace_back(border[it.row()] - d, j, it.value());
      }
    }
    closed_rows.setFromTriplets(g.begin(), g.end());
  }
  penalised += (1e6 * std::max(diagonal, 1e-300)) * SpMat(closed_rows.transpose() * closed_rows);
  bool finite = true;
  for (int k = 0; k < bordered.nonZeros(); ++k)
    finite = finite && std::isfinite(bordered.valuePtr()[k]);
  if (!finite) {
    message_ = "the bordered stiffness has a non-finite entry";
    return;
  }
  Factorize(&penalised, &bordered, use);
}

namespace {

// What the factorisations' worker owns: the matrices (taken over) and what it makes of them.
struct StiffnessJob {
  SpMat penalised, bordered;
  bool solves = false;
  int unstable_modes = -1;
  std::shared_ptr<Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>>> lu;
};

void FactorizeJob(StiffnessJob* job) {
  const Eigen::SimplicialLDLT<SpMat> ldlt(job->penalised);
  if (ldlt.info() == Eigen::Success) {
    job->unstable_modes = static_cast<int>((ldlt.vectorD().array() < 0.0).count());
  }
  if (job->solves) job->lu->compute(job->bordered);
}

}  // namespace

void BorderedStiffness::Factorize(SpMat* penalised, SpMat* bordered, Use use) {
  auto job = std::make_shared<StiffnessJob>();
  job->solves = use == Use::kModesAndSolves;
  if (job->solves) job->lu = std::make_shared<Lu>();
  const bool large = bordered->nonZeros() >= kAbandonableMinNonZeros;
  const Eigen::Index rows = bordered->rows();
  job->penalised.swap(*penalised);  // taken over, not copied
  job->bordered.swap(*bordered);
  if (!large) {
    FactorizeJob(job.get());
  } else if (RunAbandonably(
                 kInterruptibleStiffnessThreadName, [job] { FactorizeJob(job.get()); }, [] {}) !=
             WorkEnd::kFinished) {
    interrupted_ = true;
    message_ = "the factorisation of the " + std::to_string(rows) +
               "-row bordered stiffness was abandoned on an interrupt";
    return;
  }
  unstable_modes_ = job->unstable_modes;
  if (use == Use::kModes) {
    message_ = "factorised for the unstable modes only";
    return;
  }
  lu_ = job->lu;
  if (lu_->info() != Eigen::Success) {
    message_ = "the stiffness bordered by the closed contacts is singular (" +
               lu_->lastErrorMessage() + ")";
    return;
  }
  ok_ = true;
}

bool BorderedStiffness::SolveDisplacement(const Vec& rhs, Vec* du) const {
  if (!ok_) return false;
  Vec full = Vec::Zero(dofs_ + num_closed());
  full.head(dofs_) = rhs;
  const Vec solution = lu_->solve(full);
  if (!solution.allFinite()) return false;
  *du = solution.head(dofs_);
  return true;
}

bool BorderedStiffness::Solve(const Vec& rhs, Vec* du, Vec* dr) const {
  if (!ok_) return false;
  Vec full = Vec::Zero(dofs_ + num_closed());
  full.head(dofs_) = rhs;
  const Vec solution = lu_->solve(full);
  if (!solution.allFinite()) return false;
  *du = solution.head(dofs_);
  *dr = Vec::Zero(pairs_);
  for (int k = 0; k < num_closed(); ++k) (*dr)[closed_pairs_[k]] = solution[dofs_ + k];
  return true;
}

bool BorderedStiffness::NullSpace(int k, int iterations, Mat* basis) const {
  if (!ok_ || k < 1) return false;
  // Fixed, generic starts (no random state: runs are reproducible). Inverse iteration on the
  // whole bordered vectors; the border part is the change of the closed reactions.
  const int n = dofs_ + num_closed();
  Mat x(n, k);
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < n; ++i) x(i, j) = 1.0 + 0.1 * std::sin((j + 1.0) * (1.0 + i));
  }
  for (int it = 0; it < iterations; ++it) {
    Mat y(n, k);
    for (int j = 0; j < k; ++j) y.col(j) = lu_->solve(Vec(x.col(j)));
    if (!y.allFinite()) return false;
    x = Eigen::HouseholderQR<Mat>(y).householderQ() * Mat::Identity(n, k);
  }
  const Mat u = x.topRows(dofs_);
  Eigen::HouseholderQR<Mat> qr(u);
  *basis = qr.householderQ() * Mat::Identity(dofs_, k);
  return basis->allFinite();
}

}  // namespace cb
