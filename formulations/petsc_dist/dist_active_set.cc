// dist-active-set: active-set's rows (NonsmoothRows with min(g, -r)) over the processes, PETSc
// SNES newtonls (dist_formulation.h).
#include <memory>
#include <utility>

#include "formulations/nonsmooth/nonsmooth.h"
#include "formulations/petsc_dist/dist_formulation.h"
#include "formulations/petsc_dist/petsc_dist.h"

namespace cb {

std::unique_ptr<Formulation> MakeDistActiveSet(const FormulationConfig& config) {
  const auto rows = [](const StepProblem& step, const StepProblem& local, const StartPoint& start,
                       const ImplicitFbOptions&,
                       std::shared_ptr<StepEquationSystem::PatternCache> cache) {
    return NonsmoothRows(step, local, start, ComplementarityFunction::kMin, std::move(cache));
  };
  return MakeDistFormulation({"dist-active-set", "newtonls", false, rows, nullptr}, config);
}

}  // namespace cb
