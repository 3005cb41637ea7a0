// One loading step of a contact model, as every formulation receives it: the known state, the
// step constraint that closes the system, and the contact scales of docs/method.md section 2.
#pragma once

#include <string>

#include "core/types.h"
#include "model/contact_model.h"

namespace cb {

// An accepted equilibrium state (u^k, r^k, lambda^k).
struct State {
  Vec u;
  Vec r;
  double lambda = 0.0;
};

// Length scale L and force scale R of the smoothed Fischer-Burmeister function:
// psi(g_p / L, -r_p / R, rho), chosen so that both arguments are O(1) at the solution.
struct ContactScales {
  double length = 1.0;
  double force = 1.0;
};

enum class ConstraintKind { kArcLength, kFixedLoad, kDisplacement, kKink, kHyperplane };
const char* ToString(ConstraintKind kind);

// The row that closes (29)-(32). Each kind's residual c(du, dlambda, g, r), dimensionless:
//  kArcLength    (33): (||du||^2 + w^2 dlambda^2) / theta^2 - 1, i.e. ||(du, dlambda)||_H with
//                H = diag(I, w) (the report takes w = 1);
//  kFixedLoad:   dlambda - (target - lambda^k);
//  kDisplacement: (u^k_j + du_j - target) / L for the controlled dof j;
//  kKink      (53): g_p / L - r_p / R for the pair p whose status changes;
//  kHyperplane:  (n . du + n_lambda dlambda) / theta - 1: the hyperplane at distance theta from
//                the base along the unit normal (n, n_lambda), lambda free (Riks; Wagner &
//                Wriggers 1988). A branch switch takes its first step on the plane orthogonal to
//                the null vector, which the branch already traced does not cross near the
//                bifurcation point (docs/method.md section 5).
struct StepConstraint {
  ConstraintKind kind = ConstraintKind::kArcLength;
  double arc_length = 0.1;     // theta
  double lambda_weight = 1.0;  // w
  double target = 0.0;         // lambda (kFixedLoad) or u_j (kDisplacement), absolute
  int index = -1;              // dof j (kDisplacement) or pair p (kKink)
  Vec normal;                  // n (kHyperplane), of the dofs' size
  double normal_lambda = 0.0;  // n_lambda (kHyperplane)

  static StepConstraint ArcLength(double theta, double lambda_weight = 1.0);
  static StepConstraint FixedLoad(double lambda);
  static StepConstraint Displacement(int dof, double value);
  static StepConstraint Kink(int pair);
  // `normal` and `normal_lambda` are scaled together to unit Euclidean norm.
  static StepConstraint Hyperplane(Vec normal, double normal_lambda, double theta);
};

struct StepProblem {
  const ContactModel* model = nullptr;
  State base;
  StepConstraint constraint;
  ContactScales scales;

  int num_dofs() const { return model->num_dofs(); }
  int num_pairs() const { return model->num_pairs(); }
  // Throws std::invalid_argument naming the bad field (sizes, non-positive theta or scales,
  // an index out of range).
  void Validate() const;
};

// The step constraint's residual c (see StepConstraint) and its first derivatives.
double StepConstraintValue(const StepProblem& step, const Vec& du, double dlambda, const Vec& g,
                           const Vec& r);

// A point of a step: the increment and the contact variables at u^k + du.
struct StepPoint {
  Vec du;
  Vec g;
  Vec r;
  double dlambda = 0.0;
};

}  // namespace cb
