// The distributed backend without PETSc: unavailable, one process.
#include <stdexcept>

#include "formulations/petsc_dist/parallel_libraries.h"
#include "formulations/petsc_dist/petsc_dist.h"

namespace cb {

namespace {

[[noreturn]] std::unique_ptr<Formulation> Unavailable() {
  throw std::invalid_argument("the distributed formulations need PETSc, which this build lacks");
}

}  // namespace

bool DistAvailable() { return false; }
std::string SequentialStandIn() { return ""; }
std::string ParallelLibrariesPreload() { return ""; }
std::unique_ptr<Formulation> MakeDistImplicitFb(const FormulationConfig&) { Unavailable(); }
std::unique_ptr<Formulation> MakeDistNonsmoothFb(const FormulationConfig&) { Unavailable(); }
std::unique_ptr<Formulation> MakeDistActiveSet(const FormulationConfig&) { Unavailable(); }
std::unique_ptr<Formulation> MakeDistPetscRsls(const FormulationConfig&) { Unavailable(); }
std::unique_ptr<Formulation> MakeDistPetscSsls(const FormulationConfig&) { Unavailable(); }

}  // namespace cb
