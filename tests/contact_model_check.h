// The derivative checks every contact model with a body passes (trusses, hexahedra, against
// flat and curved obstacles): the gap Jacobian is the Jacobian of the gaps, the curvature
// sum_p r_p hess phi_p(u) the Jacobian of the generalised reaction grad phi(u)^T r (both
// against central differences), and the one-pass GapDerivatives gives the same two matrices.
#pragma once

#include <gtest/gtest.h>

#include "fd_check.h"
#include "model/contact_model.h"

namespace cb::fd_check {

inline void ExpectGapDerivativesMatch(const ContactModel& model, const Vec& u, const Vec& r,
                                      double tol) {
  auto gaps = [&](const Vec& v) {
    Vec phi;
    model.Gaps(v, &phi);
    return phi;
  };
  auto reaction = [&](const Vec& v) {
    Vec out;
    model.GeneralisedReaction(v, r, &out);
    return out;
  };
  SpMat jacobian, curvature;
  model.GapJacobian(u, &jacobian);
  model.GapCurvature(u, r, &curvature);
  ASSERT_EQ(jacobian.rows(), model.num_pairs());
  ASSERT_EQ(jacobian.cols(), model.num_dofs());
  ASSERT_EQ(curvature.rows(), model.num_dofs());
  ASSERT_EQ(curvature.cols(), model.num_dofs());
  EXPECT_DERIVATIVE_NEAR(Mat(jacobian), FiniteDifferenceJacobian(gaps, u), tol);
  EXPECT_GT(Mat(curvature).norm(), 0.0);
  EXPECT_DERIVATIVE_NEAR(Mat(curvature), FiniteDifferenceJacobian(reaction, u), tol);

  SpMat one_pass_jacobian, one_pass_curvature;
  model.GapDerivatives(u, r, &one_pass_jacobian, &one_pass_curvature);
  EXPECT_DERIVATIVE_NEAR(Mat(one_pass_jacobian), Mat(jacobian), 1e-12);
  EXPECT_DERIVATIVE_NEAR(Mat(one_pass_curvature), Mat(curvature), 1e-12);
}

}  // namespace cb::fd_check
