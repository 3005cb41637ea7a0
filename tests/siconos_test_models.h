// What the Siconos tests share: a fixed-load step from the zero state, and a small linear model
// with a nonsingular stiffness: two springs in series
// (k1 from the ground to dof 0, k2 from dof 0 to dof 1), the load lambda f on dof 1, and a wall
// at distance g0 ahead of dof 1 (phi(u) = u1 - g0, positive inside the wall). In closed form:
// free while lambda f (1/k1 + 1/k2) <= g0; in contact beyond, with
//   u1 = g0,  u0 = k2 g0 / (k1 + k2),  r = k1 k2 g0 / (k1 + k2) - lambda f  (< 0).
#pragma once

#include <limits>
#include <random>
#include <utility>

#include "model/contact_model.h"
#include "step/step_problem.h"

namespace cb::siconos_test {

class SpringsAgainstWall final : public ContactModel {
 public:
  SpringsAgainstWall(double k1, double k2, double f, double g0) : k1_(k1), k2_(k2), g0_(g0) {
    load_ = Vec::Zero(2);
    load_[1] = f;
  }
  int num_dofs() const override { return 2; }
  int num_pairs() const override { return 1; }
  bool is_linear() const override { return true; }
  double Energy(const Vec& u) const override {
    return 0.5 * k1_ * u[0] * u[0] + 0.5 * k2_ * (u[1] - u[0]) * (u[1] - u[0]);
  }
  void InternalForce(const Vec& u, Vec* force) const override {
    force->resize(2);
    (*force)[0] = k1_ * u[0] - k2_ * (u[1] - u[0]);
    (*force)[1] = nan_force_ ? std::numeric_limits<double>::quiet_NaN() : k2_ * (u[1] - u[0]);
  }
  // A broken model: the internal force of dof 1 is NaN.
  void set_nan_force(bool nan) { nan_force_ = nan; }
  void Stiffness(const Vec&, SpMat* stiffness) const override {
    Mat k(2, 2);
    k << k1_ + k2_, -k2_, -k2_, k2_;
    *stiffness = k.sparseView();
  }
  void Gaps(const Vec& u, Vec* phi) const override {
    phi->resize(1);
    (*phi)[0] = u[1] - g0_;
  }
  void GapJacobian(const Vec&, SpMat* jacobian) const override {
    Mat g(1, 2);
    g << 0.0, 1.0;
    *jacobian = g.sparseView();
  }
  void GapCurvature(const Vec&, const Vec&, SpMat* curvature) const override {
    *curvature = SpMat(2, 2);
  }
  const Vec& load_pattern() const override { return load_; }

  // The closed form of the top of the file, at load factor lambda.
  State Answer(double lambda) const {
    State s;
    s.lambda = lambda;
    s.u = Vec::Zero(2);
    s.r = Vec::Zero(1);
    const double free_u1 = lambda * load_[1] * (1.0 / k1_ + 1.0 / k2_);
    if (free_u1 <= g0_) {
      s.u << lambda * load_[1] / k1_, free_u1;
      return s;
    }
    s.u << k2_ * g0_ / (k1_ + k2_), g0_;
    s.r[0] = k1_ * k2_ * g0_ / (k1_ + k2_) - lambda * load_[1];
    return s;
  }

 private:
  double k1_, k2_, g0_;
  bool nan_force_ = false;
  Vec load_;
};

// `base` with each pair's row scaled by its own factor: phi_p -> s_p phi_p, so grad phi -> S grad
// phi and r_p -> r_p / s_p. The same contact problem (the same displacements, the reactions
// rescaled): with s = 1 + O(1e-14), a perturbation of the input at the level of its rounding.
class ScaledPairs final : public ContactModel {
 public:
  ScaledPairs(const ContactModel& base, Vec scale) : base_(base), scale_(std::move(scale)) {}
  // s_p = 1 + size u_p, u_p uniform in [-1, 1) from std::mt19937(seed) (the generator's raw
  // output: the same sequence on every platform).
  static Vec Factors(int pairs, double size, unsigned seed) {
    std::mt19937 generator(seed);
    Vec scale(pairs);
    for (int p = 0; p < pairs; ++p) {
      scale[p] = 1.0 + size * (2.0 * static_cast<double>(generator()) / 4294967296.0 - 1.0);
    }
    return scale;
  }
  int num_dofs() const override { return base_.num_dofs(); }
  int num_pairs() const override { return base_.num_pairs(); }
  bool has_energy() const override { return base_.has_energy(); }
  bool is_linear() const override { return base_.is_linear(); }
  double Energy(const Vec& u) const override { return base_.Energy(u); }
  void InternalForce(const Vec& u, Vec* force) const override { base_.InternalForce(u, force); }
  void Stiffness(const Vec& u, SpMat* stiffness) const override { base_.Stiffness(u, stiffness); }
  void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const override {
    base_.InternalForceMagnitudes(u, magnitudes);
  }
  void Gaps(const Vec& u, Vec* phi) const override {
    base_.Gaps(u, phi);
    *phi = phi->cwiseProduct(scale_);
  }
  void GapJacobian(const Vec& u, SpMat* jacobian) const override {
    SpMat g;
    base_.GapJacobian(u, &g);
    *jacobian = scale_.asDiagonal() * g;
  }
  void GapCurvature(const Vec& u, const Vec& r, SpMat* curvature) const override {
    base_.GapCurvature(u, Vec(r.cwiseProduct(scale_)), curvature);
  }
  const Vec& load_pattern() const override { return base_.load_pattern(); }

 private:
  const ContactModel& base_;
  Vec scale_;
};

// The step of `model` at fixed load `lambda` from the zero state, with scales L, R.
inline StepProblem FixedLoadStep(const ContactModel& model, double lambda, double length,
                                 double force) {
  StepProblem step;
  step.model = &model;
  step.base.u = Vec::Zero(model.num_dofs());
  step.base.r = Vec::Zero(model.num_pairs());
  step.constraint = StepConstraint::FixedLoad(lambda);
  step.scales = {length, force};
  return step;
}

}  // namespace cb::siconos_test
