// The dist-* formulations: each builds its serial step equations on the contact-only step
// (dist_steps.h) and its start exactly as its serial counterpart does, and hands both to one
// DistributedSteps kept across the steps of a path:
//   dist-implicit-fb    ImplicitFbSystem, start MakeImplicitFbStart ((38)-(43)), SNES newtonls;
//   dist-nonsmooth-fb   NonsmoothSystem (FB), start MakeStepEquationStart, SNES newtonls;
//   dist-active-set     NonsmoothSystem (min), the same start, SNES newtonls;
//   dist-petsc-rsls     the MCP of petsc_mcp.h, start MakeMcpStart, SNESVINEWTONRSLS;
//   dist-petsc-ssls     the same, SNESVINEWTONSSLS.
// The equations take the serial Newton's line search with the serial solvers' settings for the
// start (SolverOptionsFor; dist_line_search.h). What the serial ones add around their Newton is
// not repeated: nonsmooth-fb's restart from the cold start, implicit-fb's alternative solvers
// (dogleg, quasi-Newton): PETSc's own are chosen with -snes_type.
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "formulations/common/start_solvers.h"
#include "formulations/implicit_fb/implicit_fb.h"
#include "formulations/nonsmooth/nonsmooth.h"
#include "formulations/petsc/petsc_adapter.h"
#include "formulations/petsc/petsc_mcp.h"
#include "formulations/petsc_dist/dist_steps.h"
#include "formulations/petsc_dist/petsc_dist.h"

namespace cb {

namespace {

enum class DistKind { kImplicitFb, kNonsmoothFb, kActiveSet, kRsls, kSsls };

bool IsVi(DistKind kind) { return kind == DistKind::kRsls || kind == DistKind::kSsls; }

// The linear solves `linear=` names. direct: MUMPS on the whole system. amg: FGMRES with the
// augmented Schur-complement field split of field_split.h (a PCSHELL whose inner field split,
// options prefix "al_", sees the system with gamma B^T B added to the stiffness block where
// pairs are closed): GAMG on the du block, whose rigid modes can be free where contact alone
// holds the body (so the coarsest level is solved by SVD, a pseudo-inverse), and MUMPS on the
// small selfp Schur complement of the contact rows. Its relative tolerance only paces Newton
// (the stopping test ||F||_inf <= residual_tol is on the true residual); 1e-8 keeps the direct
// solve's Newton iterations.
std::string LinearOptions(const std::string& linear) {
  if (linear == "amg") {
    return " -ksp_type fgmres -ksp_gmres_restart 100 -ksp_rtol 1e-8 -ksp_max_it 1000"
           " -pc_type shell -augmented_alpha 10 -augmented_cutoff 1e-2 -al_pc_fieldsplit_type schur"
           " -al_pc_fieldsplit_schur_fact_type upper -al_pc_fieldsplit_schur_precondition selfp"
           " -al_fieldsplit_0_ksp_type preonly -al_fieldsplit_0_pc_type gamg"
           " -al_fieldsplit_0_mg_coarse_sub_pc_type svd"
           " -al_fieldsplit_0_mg_coarse_sub_pc_svd_zero_sing 1e-8"
           " -al_fieldsplit_1_ksp_type preonly -al_fieldsplit_1_pc_type lu"
           " -al_fieldsplit_1_pc_factor_mat_solver_type mumps";
  }
  return " -ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";
}

// The defaults of dist_steps.h for a kind.
std::string DefaultOptions(DistKind kind, const SolverOptions& solver, const std::string& linear) {
  if (IsVi(kind)) {
    return std::string("-snes_type ") +
           (kind == DistKind::kRsls ? "vinewtonrsls" : "vinewtonssls") + LinearOptions(linear) +
           " -snes_atol 1e-10 -snes_rtol 0 -snes_max_it 200";
  }
  return "-snes_type newtonls" + LinearOptions(linear) + " -snes_max_it " +
         std::to_string(solver.max_iterations);
}

// The MCP's Jacobian (petsc_mcp.h) as a column-compressed matrix for DistributedSteps, made once
// per pattern of the step equations' Jacobian and afterwards filled in place (the matrix of the
// previous call, which DistributedSteps passes again).
class McpJacobianInPlace {
 public:
  void Fill(McpStepEquations& system, const Vec& y, SpMat* jacobian) {
    system.Jacobian(y, &s_);
    if (rows_.size == 0 || !SamePattern(rows_, s_) || jacobian != shaped_) {
      rows_ = MakeMcpRowMap(system.layout(), s_);
      *jacobian = McpJacobian(rows_, s_);
      shaped_ = jacobian;
      StoragePositions(*jacobian);
    }
    FillMcpValues(rows_, s_, values_.data());
    double* to = jacobian->valuePtr();
    for (std::size_t k = 0; k < values_.size(); ++k) to[positions_[k]] = values_[k];
  }

 private:
  // Where the map's entries (row by row) lie in the column-compressed storage of `m`.
  void StoragePositions(const SpMat& m) {
    positions_.clear();
    for (int i = 0; i < rows_.size; ++i) {
      for (int k = rows_.row_start[i]; k < rows_.row_start[i + 1]; ++k) {
        const int column = rows_.columns[k];
        const int* first = m.innerIndexPtr() + m.outerIndexPtr()[column];
        const int* last = m.innerIndexPtr() + m.outerIndexPtr()[column + 1];
        positions_.push_back(
            static_cast<int>(std::lower_bound(first, last, i) - m.innerIndexPtr()));
      }
    }
    values_.assign(positions_.size(), 0.0);
  }

  SpMat s_;
  McpRowMap rows_;
  const SpMat* shaped_ = nullptr;
  std::vector<int> positions_;
  std::vector<double> values_;
};

class DistFormulation final : public Formulation {
 public:
  DistFormulation(std::string name, DistKind kind, const ImplicitFbOptions& options,
                  const std::string& linear, const std::string& user_options,
                  ElementSplit* element_split)
      : name_(std::move(name)),
        kind_(kind),
        options_(options),
        steps_(DefaultOptions(kind, options.solver_options, linear), user_options, element_split),
        cache_(StepEquationSystem::MakePatternCache()) {}

  std::string name() const override { return name_; }
  std::string solver() const override {
    return IsVi(kind_) ? std::string("petsc-") +
                             (kind_ == DistKind::kRsls ? "vinewtonrsls" : "vinewtonssls")
                       : "petsc-newtonls";
  }
  std::string settings() const override { return "petsc_options=" + steps_.options(); }

 private:
  bool DoAccepts(const StepProblem& step, std::string* why) const override {
    return CanDistribute(step, why);
  }

  void DoSolve(const StepProblem& step, const StartPoint& start, const SolveControls& controls,
               StepResult* result) override {
    const bool has_rho = kind_ == DistKind::kImplicitFb;
    const StepProblem& local = steps_.ContactOnlyStep(
        step, StepEquationLayout{step.num_dofs(), step.num_pairs(), has_rho}.size());
    // The serial solver's settings for this start (its line search's window; StartSolvers).
    const SolverOptions solver = SolverOptionsFor(start, options_.solver_options);
    Vec x;
    switch (kind_) {
      case DistKind::kImplicitFb: {
        const ImplicitFbStart initial = MakeImplicitFbStart(step, start, options_);
        ImplicitFbSystem system(local, EtaEquation{options_.eta, initial.gamma}, cache_);
        x = initial.x;
        steps_.Solve(step, Equations(system), nullptr, solver, controls, &x, result);
        result->details["gamma"] = std::to_string(initial.gamma);
        result->details["rho"] = std::to_string(x[system.layout().rho()]);
        break;
      }
      case DistKind::kNonsmoothFb:
      case DistKind::kActiveSet: {
        NonsmoothSystem system(local,
                               kind_ == DistKind::kActiveSet
                                   ? ComplementarityFunction::kMin
                                   : ComplementarityFunction::kFischerBurmeister,
                               cache_);
        x = MakeStepEquationStart(step, start, system.layout().size());
        steps_.Solve(step, Equations(system), nullptr, solver, controls, &x, result);
        break;
      }
      case DistKind::kRsls:
      case DistKind::kSsls: {
        McpStepEquations system(local, cache_);
        const McpBounds bounds = MakeMcpBounds(step);
        x = MakeMcpStart(step, start, bounds);
        McpJacobianInPlace mcp;
        LocalStepEquations equations{
            [&](const Vec& y, Vec* f) { return McpFunction(system, y, f); },
            [&](const Vec& y, SpMat* jacobian) { mcp.Fill(system, y, jacobian); }, system.layout()};
        const DistBounds dist_bounds{bounds.lower, bounds.upper};
        steps_.Solve(step, equations, &dist_bounds, solver, controls, &x, result);
        break;
      }
    }
    FillPoint(step, x, result);
  }

  static LocalStepEquations Equations(StepEquationSystem& system) {
    return {[&system](const Vec& y, Vec* f) { return system.Residual(y, f); },
            [&system](const Vec& y, SpMat* jacobian) { system.Jacobian(y, jacobian); },
            system.layout()};
  }

  // The point in physical units from the scaled unknowns (common/step_equations.h).
  static void FillPoint(const StepProblem& step, const Vec& x, StepResult* result) {
    const StepEquationLayout l{step.num_dofs(), step.num_pairs(), false};
    result->point.du = x.segment(l.du(), l.d);
    result->point.g = step.scales.length * x.segment(l.g(), l.nc);
    result->point.r = step.scales.force * x.segment(l.r(), l.nc);
    result->point.dlambda = x[l.dlambda()];
  }

  std::string name_;
  DistKind kind_;
  ImplicitFbOptions options_;
  DistributedSteps steps_;
  std::shared_ptr<StepEquationSystem::PatternCache> cache_;
};

// `petsc_options` (free text), `linear` (the equations only: SNESVI solves on reduced rows,
// which the field split does not know), then the serial counterpart's typed options.
std::unique_ptr<Formulation> MakeDist(const std::string& name, DistKind kind,
                                      const FormulationConfig& config) {
  OptionReader reader(name, config.options);
  const std::string user_options = reader.GetText("petsc_options", "");
  const std::string linear =
      IsVi(kind) ? "direct" : reader.GetChoice("linear", "direct", {"direct", "amg"});
  ImplicitFbOptions options;
  options.eta = static_cast<EtaCase>(config.eta);
  options.solver_options = config.solver_options;
  if (kind == DistKind::kImplicitFb) {
    options.gamma_tol = reader.GetReal("gamma_tol", options.gamma_tol);
    options.rho_min = reader.GetReal("rho_min", options.rho_min);
  }
  reader.Finish();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(name + " options: " + why);
  return std::make_unique<DistFormulation>(name, kind, options, linear, user_options,
                                           config.element_split);
}

}  // namespace

std::unique_ptr<Formulation> MakeDistImplicitFb(const FormulationConfig& config) {
  return MakeDist("dist-implicit-fb", DistKind::kImplicitFb, config);
}
std::unique_ptr<Formulation> MakeDistNonsmoothFb(const FormulationConfig& config) {
  return MakeDist("dist-nonsmooth-fb", DistKind::kNonsmoothFb, config);
}
std::unique_ptr<Formulation> MakeDistActiveSet(const FormulationConfig& config) {
  return MakeDist("dist-active-set", DistKind::kActiveSet, config);
}
std::unique_ptr<Formulation> MakeDistPetscRsls(const FormulationConfig& config) {
  return MakeDist("dist-petsc-rsls", DistKind::kRsls, config);
}
std::unique_ptr<Formulation> MakeDistPetscSsls(const FormulationConfig& config) {
  return MakeDist("dist-petsc-ssls", DistKind::kSsls, config);
}

}  // namespace cb
