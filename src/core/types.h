// Vector and matrix aliases and the Status every solver and formulation reports.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace cb {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
// Column-major sparse matrix; the sparse direct solvers we wrap want this storage.
using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

// A small point in 2-D or 3-D without heap allocation (dynamic size, fixed capacity 3).
using Point = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using PointMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;

// Outcome of a solve. The meaning is fixed across the library:
//  kConverged       the method's own stopping test was met (the verdict may still disagree);
//  kLimitReached    stopped at an iteration/evaluation limit with a usable point;
//  kTimeLimit       stopped at SolveControls::time_limit_s: the solve did not finish, so the
//                   step fails (the path cuts it back like any other failed step);
//  kFailed          no usable point (singular system, non-finite values, line search failure);
//  kStoppedByCaller the caller interrupted the solve (SIGINT/SIGTERM through the interrupt hook);
//  kNotRun          nothing has been attempted yet.
enum class Status { kNotRun, kConverged, kLimitReached, kTimeLimit, kFailed, kStoppedByCaller };

const char* ToString(Status status);

}  // namespace cb
