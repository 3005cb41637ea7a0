// What the registry finds when PETSc was not found at configure time (petsc.cmake builds this
// file instead of the adapter and the formulations).
#include <stdexcept>

#include "formulations/petsc/petsc.h"

namespace cb {

bool PetscAvailable() { return false; }
std::string PetscVersion() { return ""; }

std::unique_ptr<Formulation> MakePetscRsls(const FormulationConfig&) {
  throw std::invalid_argument("petsc-rsls: this build has no PETSc");
}

std::unique_ptr<Formulation> MakePetscSsls(const FormulationConfig&) {
  throw std::invalid_argument("petsc-ssls: this build has no PETSc");
}

// Nothing to finalise without PETSc. User-provided rather than defaulted: the class is the same
// in both builds, whose other definition finalises PETSc.
PetscProcessScope::~PetscProcessScope() {}  // NOLINT(modernize-use-equals-default)

}  // namespace cb
