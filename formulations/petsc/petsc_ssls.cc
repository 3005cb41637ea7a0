// petsc-ssls: the step as the MCP of petsc_mcp.h solved by PETSc's SNESVINEWTONSSLS, the
// semismooth Newton method on the Fischer-Burmeister reformulation of the bounds (Munson,
// Facchinei, Ferris, Fischer and Kanzow, INFORMS J. Comput. 13 (2001)): for r^_p <= 0 with row
// -g^_p, PETSc's FB function of (-r^_p, g^_p), (12) with rho = 0 as nonsmooth-fb has it, and
// the free rows as they are; Newton with a line search on 1/2 ||FB||^2 over the full system.
// Starts, reuse and options: petsc_vi_formulation.cc, petsc_adapter.h.
#include "formulations/petsc/petsc.h"
#include "formulations/petsc/petsc_adapter.h"

namespace cb {

std::unique_ptr<Formulation> MakePetscSsls(const FormulationConfig& config) {
  return MakePetscViFormulation("petsc-ssls", SNESVINEWTONSSLS, config);
}

}  // namespace cb
