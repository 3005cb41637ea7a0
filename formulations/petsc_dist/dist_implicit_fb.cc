// dist-implicit-fb: implicit-fb's rows (ImplicitFbRows: the system (29)-(33), the start
// (38)-(43)) over the processes, PETSc SNES newtonls (dist_formulation.h); backend options
// gamma_tol and rho_min as implicit-fb's.
#include <memory>
#include <utility>

#include "formulations/petsc_dist/dist_formulation.h"
#include "formulations/petsc_dist/petsc_dist.h"

namespace cb {

std::unique_ptr<Formulation> MakeDistImplicitFb(const FormulationConfig& config) {
  DistRecipe recipe{"dist-implicit-fb", "newtonls", true, ImplicitFbRows, nullptr};
  recipe.read_options = [](OptionReader& reader, ImplicitFbOptions* options) {
    options->gamma_tol = reader.GetReal("gamma_tol", options->gamma_tol);
    options->rho_min = reader.GetReal("rho_min", options->rho_min);
  };
  return MakeDistFormulation(recipe, config);
}

}  // namespace cb
