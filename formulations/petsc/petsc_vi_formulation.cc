// The PETSc formulations, each the step as the MCP of petsc_mcp.h handed to one SNESVI
// (petsc_adapter.h, options there) that the formulation keeps across the steps of a path:
//
// petsc-rsls: the step as the MCP of petsc_mcp.h solved by PETSc's SNESVINEWTONRSLS, the
// reduced-space active-set Newton method (Benson and Munson, Optim. Methods Softw. 21 (2006)):
// at each iterate the unknowns at a bound whose row pushes outward (here the pairs with r^_p = 0
// and -g^_p < 0, i.e. open with a positive gap) are held at the bound, and Newton with a
// backtracking line search runs on the rest, the reduced Jacobian factorised by the direct
// solve of petsc_adapter.h. Close to the suite's active-set formulation; the active set is
// PETSc's.
//
// petsc-ssls: the step as the MCP of petsc_mcp.h solved by PETSc's SNESVINEWTONSSLS, the
// semismooth Newton method on the Fischer-Burmeister reformulation of the bounds (Munson,
// Facchinei, Ferris, Fischer and Kanzow, INFORMS J. Comput. 13 (2001)): for r^_p <= 0 with row
// -g^_p, PETSc's FB function of (-r^_p, g^_p), (12) with rho = 0 as nonsmooth-fb has it, and
// the free rows as they are; Newton with a line search on 1/2 ||FB||^2 over the full system.
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

#include "formulations/common/step_equations.h"
#include "formulations/petsc/petsc.h"
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
    result->point = PointFromScaled(step, system.layout(), x);
  }

  std::string name_;
  std::string snes_type_;
  std::string user_options_;
  SnesVi snes_;
  std::shared_ptr<StepEquationSystem::PatternCache> cache_;
};

std::unique_ptr<Formulation> MakePetscViFormulation(const std::string& name,
                                                    const std::string& snes_type,
                                                    const FormulationConfig& config) {
  // `petsc_options` is free text in PETSc's syntax, passed through as given.
  OptionReader reader(name, config.options);
  const std::string user_options = reader.GetText("petsc_options", "");
  reader.Finish();
  return std::make_unique<PetscViFormulation>(name, snes_type, user_options);
}

}  // namespace

std::unique_ptr<Formulation> MakePetscRsls(const FormulationConfig& config) {
  return MakePetscViFormulation("petsc-rsls", SNESVINEWTONRSLS, config);
}

std::unique_ptr<Formulation> MakePetscSsls(const FormulationConfig& config) {
  return MakePetscViFormulation("petsc-ssls", SNESVINEWTONSSLS, config);
}

}  // namespace cb
