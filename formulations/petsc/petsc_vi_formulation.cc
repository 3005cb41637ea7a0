// The formulation petsc-rsls and petsc-ssls share: the step as the MCP of petsc_mcp.h, handed to
// one SNESVI (petsc_adapter.h) that the formulation keeps across the steps of a path.
//
// Starts (MakeMcpStart, petsc_mcp.h): warm, docs/method.md section 4, (38)-(41); SNESVI has no
// separate input for an active set, so the previous step's contact status enters through that
// point: pairs open at the known state start at r^ = 0, closed ones at their bound g^ = 0, which
// is where RSLS's first active set comes from. Cold: du0 = 0, dlambda0 fitted to the
// constraint, g^0 = 0, r^0 = -1. What is reused from one step to the next is the formulation's
// own: the SNES, the preallocated AIJ matrix (the pattern set once per path) and the step
// equations' pattern cache; StepResult::warm_state stays empty.
#include <memory>
#include <string>

#include "formulations/petsc/petsc_adapter.h"

namespace cb {

namespace {

class PetscViFormulation final : public Formulation {
 public:
  PetscViFormulation(std::string name, std::string snes_type, const std::string& user_options)
      : name_(std::move(name)),
        snes_type_(std::move(snes_type)),
        user_options_(user_options),
        snes_(snes_type_, user_options),
        cache_(StepEquationSystem::MakePatternCache()) {}

  std::string name() const override { return name_; }
  std::string solver() const override { return "petsc-" + snes_type_; }
  std::string settings() const override { return "petsc_options=" + snes_.options(); }

 private:
  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    McpStepEquations system(step, cache_);
    const McpBounds bounds = MakeMcpBounds(step);
    Vec x = MakeMcpStart(step, start, bounds);
    snes_.Solve(system, bounds, controls, &x, result);
    const StepEquationLayout& l = system.layout();
    result->point.du = x.segment(l.du(), l.d);
    result->point.g = step.scales.length * x.segment(l.g(), l.nc);
    result->point.r = step.scales.force * x.segment(l.r(), l.nc);
    result->point.dlambda = x[l.dlambda()];
  }

  std::string name_;
  std::string snes_type_;
  std::string user_options_;
  SnesVi snes_;
  std::shared_ptr<StepEquationSystem::PatternCache> cache_;
};

}  // namespace

std::unique_ptr<Formulation> MakePetscViFormulation(const std::string& name,
                                                    const std::string& snes_type,
                                                    const FormulationConfig& config) {
  // `petsc_options` is free text in PETSc's syntax, passed through as given.
  OptionReader reader(name, config.options);
  const std::string user_options = reader.GetText("petsc_options", "");
  reader.Finish();
  return std::make_unique<PetscViFormulation>(name, snes_type, user_options);
}

}  // namespace cb
