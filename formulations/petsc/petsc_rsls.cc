// petsc-rsls: the step as the MCP of petsc_mcp.h solved by PETSc's SNESVINEWTONRSLS, the
// reduced-space active-set Newton method (Benson and Munson, Optim. Methods Softw. 21 (2006)):
// at each iterate the unknowns at a bound whose row pushes outward (here the pairs with r^_p = 0
// and -g^_p < 0, i.e. open with a positive gap) are held at the bound, and Newton with a
// backtracking line search runs on the rest, the reduced Jacobian factorised by the direct
// solve of petsc_adapter.h. Close to the suite's active-set formulation; the active set is
// PETSc's. Starts, reuse and options: petsc_vi_formulation.cc, petsc_adapter.h.
#include "formulations/petsc/petsc.h"
#include "formulations/petsc/petsc_adapter.h"

namespace cb {

std::unique_ptr<Formulation> MakePetscRsls(const FormulationConfig& config) {
  return MakePetscViFormulation("petsc-rsls", SNESVINEWTONRSLS, config);
}

}  // namespace cb
