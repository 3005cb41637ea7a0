// The closed form of the bar pushed against a wall (docs/problems.md): u = lambda L / EA until the
// bar touches the wall at lambda_c = EA gap / L (load P = 1), then u = gap and
// r = -(lambda - lambda_c).
#pragma once

#include "path/path.h"
#include "problems/problem.h"

namespace cb::fixtures {

struct BarWallClosedForm {
  explicit BarWallClosedForm(const Problem& p)
      : problem(&p),
        ea(p.parameters.Real("axial_stiffness")),
        gap(p.parameters.Real("gap")),
        length(p.parameters.Real("length")),
        lambda_c(ea * gap / length) {}

  // The state on the path at load lambda.
  State StateAt(double lambda) const {
    State s = ZeroState(*problem->model);
    s.u[problem->control_dof] = lambda < lambda_c ? lambda * length / ea : gap;
    s.r[0] = lambda < lambda_c ? 0.0 : -(lambda - lambda_c);
    s.lambda = lambda;
    return s;
  }

  const Problem* problem;
  double ea, gap, length, lambda_c;
};

}  // namespace cb::fixtures
