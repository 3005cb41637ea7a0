// nonsmooth-fb's and active-set's step as rows (common/step_rows.h): the system (29), (30),
// C(g^, -r^) = 0, step constraint, from the start of docs/method.md section 4.
#include <memory>

#include "formulations/nonsmooth/nonsmooth.h"

namespace cb {

StepRows NonsmoothRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                       ComplementarityFunction function,
                       std::shared_ptr<StepEquationSystem::PatternCache> cache) {
  auto system = std::make_shared<NonsmoothSystem>(local, function, std::move(cache));
  Vec x = MakeStepEquationStart(step, start, system->layout().size());
  return RowsOfSystem(std::move(system), std::move(x));
}

}  // namespace cb
