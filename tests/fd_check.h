// Finite-difference derivative checks shared by the tests (docs/architecture.md, house rule 4, in
// the manner of Ceres' GradientChecker): central differences with a step scaled to each entry.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/types.h"

namespace cb::fd_check {

// Central-difference Jacobian of f: R^n -> R^m at x.
inline Mat FiniteDifferenceJacobian(const std::function<Vec(const Vec&)>& f, const Vec& x,
                                    double relative_step = 1e-6) {
  const Vec f0 = f(x);
  Mat jac(f0.size(), x.size());
  Vec xp = x;
  for (int j = 0; j < x.size(); ++j) {
    const double h = relative_step * std::max(1.0, std::abs(x[j]));
    xp[j] = x[j] + h;
    const Vec fp = f(xp);
    xp[j] = x[j] - h;
    const Vec fm = f(xp);
    xp[j] = x[j];
    jac.col(j) = (fp - fm) / (2.0 * h);
  }
  return jac;
}

// Central-difference gradient of a scalar function.
inline Vec FiniteDifferenceGradient(const std::function<double(const Vec&)>& f, const Vec& x,
                                    double relative_step = 1e-6) {
  auto wrapped = [&](const Vec& y) { return Vec::Constant(1, f(y)); };
  return FiniteDifferenceJacobian(wrapped, x, relative_step).row(0).transpose();
}

// Max-norm relative error ||a - b||_max / max(1e-12 scale floor, ||b||_max).
inline double RelativeError(const Mat& a, const Mat& b) {
  const double scale = std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

}  // namespace cb::fd_check

// Asserts that analytic `actual` matches finite-difference `expected` to relative `tol`.
#define EXPECT_DERIVATIVE_NEAR(actual, expected, tol)                          \
  do {                                                                         \
    const ::cb::Mat& cb_actual_ = (actual);                                    \
    const ::cb::Mat& cb_expected_ = (expected);                                \
    ASSERT_EQ(cb_actual_.rows(), cb_expected_.rows());                         \
    ASSERT_EQ(cb_actual_.cols(), cb_expected_.cols());                         \
    EXPECT_LT(::cb::fd_check::RelativeError(cb_actual_, cb_expected_), (tol))  \
        << "analytic:\n"                                                       \
        << cb_actual_.topLeftCorner(std::min<long>(6, cb_actual_.rows()),      \
                                    std::min<long>(6, cb_actual_.cols()))      \
        << "\nfinite difference:\n"                                            \
        << cb_expected_.topLeftCorner(std::min<long>(6, cb_expected_.rows()),  \
                                      std::min<long>(6, cb_expected_.cols())); \
  } while (0)
