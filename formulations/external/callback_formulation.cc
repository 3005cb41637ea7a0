#include "formulations/external/callback_formulation.h"

#include <exception>
#include <utility>

namespace cb {

CallbackFormulation::CallbackFormulation(std::string name, std::string solver,
                                         ExternalMethod method,
                                         std::map<std::string, std::string> options)
    : name_(std::move(name)),
      solver_(std::move(solver)),
      method_(std::move(method)),
      options_(std::move(options)) {}

std::string CallbackFormulation::settings() const {
  std::string text;
  for (const auto& [key, value] : options_) text += (text.empty() ? "" : ";") + key + "=" + value;
  return text;
}

void CallbackFormulation::DoSolve(const StepProblem& step, const StartPoint& start,
                                  const SolveControls& controls, StepResult* result) {
  ExternalStepSystem system(step);
  const ExternalCall call{system.Start(start), start.kind, &options_, &controls};
  ExternalAnswer answer;
  try {
    answer = method_(system, call);
  } catch (const std::exception& e) {  // the method's own failure: recorded, not fatal
    answer = {call.x0, Status::kFailed, std::string("the method raised: ") + e.what(), {}, {}};
  }
  if (answer.x.size() != system.size()) {
    answer.message = "the method returned " + std::to_string(answer.x.size()) + " unknowns, not " +
                     std::to_string(system.size());
    answer.x = call.x0;
    answer.status = Status::kFailed;
  }
  result->point = system.ToPoint(answer.x);
  result->status = answer.status;
  result->message = answer.message;
  result->counts = answer.counts;
  result->history = std::move(answer.history);
}

FormulationInfo ExternalFormulationInfo(const std::string& name, const std::string& description,
                                        const std::string& solver, ExternalMethod method) {
  const std::string shown = solver.empty() ? "external" : solver;
  auto make = [name, shown, method = std::move(method)](const FormulationConfig& config) {
    return std::unique_ptr<Formulation>(
        std::make_unique<CallbackFormulation>(name, shown, method, config.options));
  };
  return {name, description, true, make};
}

}  // namespace cb
