#include "formulations/petsc_dist/dist_formulation.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "formulations/common/start_solvers.h"
#include "formulations/common/step_equations.h"
#include "formulations/petsc_dist/petsc_dist.h"
#include "formulations/petsc_dist/petsc_dist_adapter.h"

namespace cb {

namespace {

bool IsVi(const std::string& snes_type) { return snes_type != "newtonls"; }

// The linear solves `linear=` names. direct: MUMPS on the whole system. amg: FGMRES with the
// augmented Schur-complement field split of field_split.h (a PCSHELL whose inner field split,
// options prefix "al_", sees the system with gamma B^T B added to the stiffness block where
// pairs are closed): GAMG on the du block, whose rigid modes can be free where contact alone
// holds the body (so the coarsest level is solved by SVD, a pseudo-inverse), and MUMPS on the
// small selfp Schur complement of the contact rows. Its relative tolerance only paces Newton
// (the stopping test ||F||_inf <= residual_tol is on the true residual); 1e-8 keeps the direct
// solve's Newton iterations. MUMPS orders with AMD (ICNTL(7) = 0): the METIS and SCOTCH
// orderings of this build make the factor, and so the answer's last digits, differ from one run
// to the next, and PORD stops the process on the smallest systems (docs/findings.md, "MUMPS's
// ordering and reproducibility").
std::string LinearOptions(const std::string& linear) {
  if (linear == "amg") {
    return " -ksp_type fgmres -ksp_gmres_restart 100 -ksp_rtol 1e-8 -ksp_max_it 1000"
           " -pc_type shell -augmented_alpha 10 -augmented_cutoff 1e-2 -al_pc_fieldsplit_type schur"
           " -al_pc_fieldsplit_schur_fact_type upper -al_pc_fieldsplit_schur_precondition selfp"
           " -al_fieldsplit_0_ksp_type preonly -al_fieldsplit_0_pc_type gamg"
           " -al_fieldsplit_0_mg_coarse_sub_pc_type svd"
           " -al_fieldsplit_0_mg_coarse_sub_pc_svd_zero_sing 1e-8"
           " -al_fieldsplit_1_ksp_type preonly -al_fieldsplit_1_pc_type lu"
           " -al_fieldsplit_1_pc_factor_mat_solver_type mumps -al_fieldsplit_1_mat_mumps_icntl_7 0";
  }
  return " -ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps -mat_mumps_icntl_7 0";
}

// The defaults of petsc_dist_adapter.h for a SNES type.
std::string DefaultOptions(const std::string& snes_type, const SolverOptions& solver,
                           const std::string& linear) {
  if (IsVi(snes_type)) {
    return "-snes_type " + snes_type + LinearOptions(linear) +
           " -snes_atol 1e-10 -snes_rtol 0 -snes_max_it 200";
  }
  return "-snes_type newtonls" + LinearOptions(linear) + " -snes_max_it " +
         std::to_string(solver.max_iterations);
}

class DistFormulation final : public Formulation {
 public:
  DistFormulation(DistRecipe recipe, const ImplicitFbOptions& options, const std::string& linear,
                  const std::string& user_options, ElementSplit* element_split)
      : recipe_(std::move(recipe)),
        options_(options),
        steps_(DefaultOptions(recipe_.snes_type, options.solver_options, linear), user_options,
               element_split),
        cache_(StepEquationSystem::MakePatternCache()) {}

  std::string name() const override { return recipe_.name; }
  std::string solver() const override { return "petsc-" + recipe_.snes_type; }
  std::string settings() const override { return "petsc_options=" + steps_.options(); }

 private:
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    return CanDistribute(step, why);
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const StepProblem& local = steps_.ContactOnlyStep(
        step, StepEquationLayout{step.num_dofs(), step.num_pairs(), recipe_.has_rho}.size());
    // The serial solver's settings for this start (its line search's window; StartSolvers).
    const SolverOptions solver = SolverOptionsFor(start, options_.solver_options);
    const StepRows rows = recipe_.rows(step, local, start, options_, cache_);
    Vec x = rows.start;
    steps_.Solve(step, rows, solver, controls, &x, result);
    if (rows.finish) rows.finish(x, result);
    result->point = PointFromScaled(step, {step.num_dofs(), step.num_pairs(), false}, x);
  }

  DistRecipe recipe_;
  ImplicitFbOptions options_;
  DistributedSteps steps_;
  std::shared_ptr<StepEquationSystem::PatternCache> cache_;
};

}  // namespace

std::unique_ptr<Formulation> MakeDistFormulation(const DistRecipe& recipe,
                                                 const FormulationConfig& config) {
  OptionReader reader(recipe.name, config.options);
  const std::string user_options = reader.GetText("petsc_options", "");
  const std::string linear =
      IsVi(recipe.snes_type) ? "direct" : reader.GetChoice("linear", "direct", {"direct", "amg"});
  ImplicitFbOptions options;
  options.eta = static_cast<EtaCase>(config.eta);
  options.solver_options = config.solver_options;
  if (recipe.read_options) recipe.read_options(reader, &options);
  reader.Finish();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(recipe.name + " options: " + why);
  return std::make_unique<DistFormulation>(recipe, options, linear, user_options,
                                           config.element_split);
}

}  // namespace cb
