// Shared by the solver tests (linear_solver_test, equation_solver_test and the tests of each
// equation solver): a solver's name as a test-name part, the callback history, and nonlinear
// systems with known solutions.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "core/types.h"
#include "solvers/equation_solver.h"
#include "solvers/equation_system.h"

namespace cb::fixtures {

inline double InfNorm(const Vec& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

// Rosenbrock's function as equations: F = (10 (x2 - x1^2), 1 - x1), root (1, 1).
class RosenbrockSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(2);
    (*f)[0] = 10.0 * (x[1] - x[0] * x[0]);
    (*f)[1] = 1.0 - x[0];
    return true;
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    const std::vector<Triplet> entries = {{0, 0, -20.0 * x[0]}, {0, 1, 10.0}, {1, 0, -1.0}};
    j->resize(2, 2);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  static Vec Start() { return Vec{{-1.2, 1.0}}; }
  static Vec Solution() { return Vec{{1.0, 1.0}}; }
};

// Powell's badly scaled function: F = (1e4 x1 x2 - 1, exp(-x1) + exp(-x2) - 1.0001).
class PowellBadlyScaledSystem : public EquationSystem {
 public:
  int size() const override { return 2; }
  bool Residual(const Vec& x, Vec* f) override {
    f->resize(2);
    (*f)[0] = 1e4 * x[0] * x[1] - 1.0;
    (*f)[1] = std::exp(-x[0]) + std::exp(-x[1]) - 1.0001;
    return true;
  }
  void Jacobian(const Vec& x, SpMat* j) override {
    const std::vector<Triplet> entries = {
        {0, 0, 1e4 * x[1]}, {0, 1, 1e4 * x[0]}, {1, 0, -std::exp(-x[0])}, {1, 1, -std::exp(-x[1])}};
    j->resize(2, 2);
    j->setFromTriplets(entries.begin(), entries.end());
  }
  static Vec Start() { return Vec{{0.0, 1.0}}; }
  // x1 x2 = 1e-4 exactly, so x2 solves exp(-1e-4 / x2) + exp(-x2) = 1.0001 (decreasing on
  // [1, 20]); bisection to rounding.
  static Vec Solution() {
    auto g = [](double x2) { return std::exp(-1e-4 / x2) + std::exp(-x2) - 1.0001; };
    double lo = 1.0, hi = 20.0;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (g(mid) > 0.0 ? lo : hi) = mid;
    }
    const double x2 = 0.5 * (lo + hi);
    return Vec{{1e-4 / x2, x2}};
  }
};

// The discretised Bratu problem -u'' = lambda exp(u) on (0, 1), u(0) = u(1) = 0, with n
// interior nodes, made to have a known discrete solution: the right-hand side r is chosen so
// that the nodal values of the exact continuous solution
//   u(t) = -2 log(cosh((t - 1/2) theta / 2) / cosh(theta / 4)),  theta = sqrt(2 lambda) cosh(theta
//   / 4)
// solve the discrete equations exactly. r is O(h^2) (the discretisation error), so this is
// Bratu's problem up to a small perturbation.
class BratuSystem : public EquationSystem {
 public:
  BratuSystem(int n, double lambda) : n_(n), lambda_(lambda), solution_(n), r_(n) {
    double theta = 1.0;  // fixed point on the lower branch; the map is a contraction there
    for (int i = 0; i < 200; ++i) theta = std::sqrt(2.0 * lambda) * std::cosh(theta / 4.0);
    h_ = 1.0 / (n + 1);
    for (int i = 0; i < n; ++i) {
      const double t = (i + 1) * h_;
      solution_[i] = -2.0 * std::log(std::cosh((t - 0.5) * theta / 2.0) / std::cosh(theta / 4.0));
    }
    r_.setZero();
    Vec f(n);
    Residual(solution_, &f);
    r_ = f;
  }
  int size() const override { return n_; }
  bool Residual(const Vec& u, Vec* f) override {
    f->resize(n_);
    const double inv_h2 = 1.0 / (h_ * h_);
    for (int i = 0; i < n_; ++i) {
      const double left = i > 0 ? u[i - 1] : 0.0;
      const double right = i + 1 < n_ ? u[i + 1] : 0.0;
      (*f)[i] = (2.0 * u[i] - left - right) * inv_h2 - lambda_ * std::exp(u[i]) - r_[i];
    }
    return true;
  }
  // Fills the values in place once the pattern exists, as a model with a fixed pattern would.
  void Jacobian(const Vec& u, SpMat* j) override {
    const double inv_h2 = 1.0 / (h_ * h_);
    if (j->rows() != n_ || j->nonZeros() != 3 * n_ - 2) {
      std::vector<Triplet> entries;
      for (int i = 0; i < n_; ++i) {
        if (i > 0) entries.emplace_back(i, i - 1, 1.0);
        entries.emplace_back(i, i, 1.0);
        if (i + 1 < n_) entries.emplace_back(i, i + 1, 1.0);
      }
      j->resize(n_, n_);
      j->setFromTriplets(entries.begin(), entries.end());
    }
    for (int col = 0; col < n_; ++col) {
      for (SpMat::InnerIterator it(*j, col); it; ++it) {
        it.valueRef() = it.row() == col ? 2.0 * inv_h2 - lambda_ * std::exp(u[col]) : -inv_h2;
      }
    }
  }
  const Vec& solution() const { return solution_; }

 private:
  int n_;
  double lambda_;
  double h_ = 0.0;
  Vec solution_, r_;
};

// Records what the callback sees.
struct History {
  std::vector<int> iterations;
  std::vector<double> residual_inf;
  std::vector<double> merit;
  std::vector<Vec> x;
  IterationCallback Callback() {
    return [this](const IterationInfo& info) {
      iterations.push_back(info.iteration);
      residual_inf.push_back(info.residual_inf);
      merit.push_back(info.merit);
      x.push_back(*info.x);
      return true;
    };
  }
};

// A name (a solver's, say "quasi-newton") as a test-name part: letters, digits and '_'.
inline std::string Readable(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

inline std::string ParamName(const ::testing::TestParamInfo<std::string>& info) {
  return Readable(info.param);
}

}  // namespace cb::fixtures
