// The derivative checks every ElasticBody passes (trusses, Q4, hexahedra): the internal force is
// the gradient of the energy, the stiffness the Jacobian of the internal force (both against
// central differences), the stiffness is symmetric, and the streamed form (StiffnessEntries,
// AddStiffness) adds the same matrix as Stiffness().
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "fd_check.h"
#include "model/elastic_body.h"

namespace cb::fd_check {

inline void ExpectBodyDerivativesMatch(const ElasticBody& body, const Vec& u, double tol) {
  auto energy = [&](const Vec& v) { return body.Energy(v); };
  auto force = [&](const Vec& v) {
    Vec f;
    body.InternalForce(v, &f);
    return f;
  };
  Vec f;
  body.InternalForce(u, &f);
  EXPECT_DERIVATIVE_NEAR(f, FiniteDifferenceGradient(energy, u), tol);
  SpMat k;
  body.Stiffness(u, &k);
  const Mat dense = Mat(k);
  EXPECT_DERIVATIVE_NEAR(dense, FiniteDifferenceJacobian(force, u), tol);
  EXPECT_LE((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());

  const auto entries = body.StiffnessEntries();
  std::vector<int> slots(entries.size());
  for (std::size_t i = 0; i < slots.size(); ++i) slots[i] = static_cast<int>(i);
  std::vector<double> values(entries.size(), 0.0);
  body.AddStiffness(u, 2.0, slots.data(), values.data());
  Mat streamed = Mat::Zero(dense.rows(), dense.cols());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    streamed(entries[i].first, entries[i].second) += values[i];
  }
  EXPECT_LE((streamed - 2.0 * dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
}

}  // namespace cb::fd_check
