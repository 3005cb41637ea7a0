// A formulation whose method is a callable given at run time (a Python function through the
// module, python/module.cc, or a C++ plug-in's function): it receives the step as data
// (step_system.h) and the suite's start, and returns a point with its counts. Everything else is
// the suite's: Formulation::Solve times the call, the path driver judges the point with the one
// verdict, cuts back and records it as it does a built-in formulation's.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "formulations/common/config.h"
#include "formulations/external/step_system.h"
#include "formulations/registry.h"
#include "step/formulation.h"

namespace cb {

// What a method returns: the point in the scaled unknowns of step_system.h, what it claims
// (kConverged: "found"; the verdict decides, whatever the claim) and what it counted.
struct ExternalAnswer {
  Vec x;
  Status status = Status::kConverged;
  std::string message;
  SolveCounts counts;
  std::vector<IterationRecord> history;
};

// What a method is given besides the system: the start point x0 (the suite's warm or cold
// start, step_system.h), which start it is, the formulation's KEY=VALUE options (compare's
// --option NAME:KEY=VALUE) and the harness's limits.
struct ExternalCall {
  Vec x0;
  StartKind start = StartKind::kWarm;
  const std::map<std::string, std::string>* options = nullptr;
  const SolveControls* controls = nullptr;
};

using ExternalMethod = std::function<ExternalAnswer(ExternalStepSystem&, const ExternalCall&)>;

class CallbackFormulation final : public Formulation {
 public:
  CallbackFormulation(std::string name, std::string solver, ExternalMethod method,
                      std::map<std::string, std::string> options);
  std::string name() const override { return name_; }
  std::string solver() const override { return solver_; }
  std::string settings() const override;

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override;

  std::string name_, solver_;
  ExternalMethod method_;
  std::map<std::string, std::string> options_;
};

// The registry entry of a method: `name` and `description` as `list` shows them; `solver` the
// records' solver column ("" for "external"). The entry's factory hands every instance the
// configuration's options (FormulationConfig::options); the common settings (solver, eta) do
// not apply to it.
FormulationInfo ExternalFormulationInfo(const std::string& name, const std::string& description,
                                        const std::string& solver, ExternalMethod method);

}  // namespace cb
