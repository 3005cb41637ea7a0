// dist-petsc-rsls: petsc-rsls's rows (McpRows: the MCP of petsc_mcp.h within its bounds) over
// the processes, SNESVINEWTONRSLS (dist_formulation.h).
#include <memory>
#include <utility>

#include "formulations/petsc/petsc_mcp.h"
#include "formulations/petsc_dist/dist_formulation.h"
#include "formulations/petsc_dist/petsc_dist.h"

namespace cb {

std::unique_ptr<Formulation> MakeDistPetscRsls(const FormulationConfig& config) {
  const auto rows = [](const StepProblem& step, const StepProblem& local, const StartPoint& start,
                       const ImplicitFbOptions&,
                       std::shared_ptr<StepEquationSystem::PatternCache> cache) {
    return McpRows(step, local, start, std::move(cache));
  };
  return MakeDistFormulation({"dist-petsc-rsls", "vinewtonrsls", false, rows, nullptr}, config);
}

}  // namespace cb
