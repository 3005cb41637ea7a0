// implicit-fb's step as rows (common/step_rows.h): the system (29)-(33) with the eta equation
// (32) of the start's gamma, from the start (38)-(43), as ImplicitFb::DoSolve builds them.
#include <memory>
#include <string>

#include "formulations/implicit_fb/implicit_fb.h"

namespace cb {

StepRows ImplicitFbRows(const StepProblem& step, const StepProblem& local, const StartPoint& start,
                        const ImplicitFbOptions& options,
                        std::shared_ptr<StepEquationSystem::PatternCache> cache) {
  const ImplicitFbStart initial = MakeImplicitFbStart(step, start, options);
  auto system = std::make_shared<ImplicitFbSystem>(local, EtaEquation{options.eta, initial.gamma},
                                                   std::move(cache));
  const int rho = system->layout().rho();
  StepRows rows = RowsOfSystem(std::move(system), initial.x);
  rows.finish = [gamma = initial.gamma, rho](const Vec& x, StepResult* result) {
    result->details["gamma"] = std::to_string(gamma);
    result->details["rho"] = std::to_string(x[rho]);
  };
  return rows;
}

}  // namespace cb
