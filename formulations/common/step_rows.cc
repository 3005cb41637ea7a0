#include "formulations/common/step_rows.h"

#include <utility>

namespace cb {

StepRows RowsOfSystem(std::shared_ptr<StepEquationSystem> system, Vec start) {
  StepEquationSystem* s = system.get();
  StepRows rows;
  rows.residual = [s](const Vec& x, Vec* f) { return s->Residual(x, f); };
  rows.jacobian = [s](const Vec& x, SpMat* jacobian) { s->Jacobian(x, jacobian); };
  rows.layout = s->layout();
  rows.start = std::move(start);
  rows.owner = std::move(system);
  return rows;
}

}  // namespace cb
