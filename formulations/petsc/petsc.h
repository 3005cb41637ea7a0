// The PETSc backend: `petsc-rsls` (SNESVINEWTONRSLS, reduced-space active set) and `petsc-ssls`
// (SNESVINEWTONSSLS, semismooth Fischer-Burmeister), both on the step as the mixed
// complementarity problem of petsc_mcp.h (petsc_vi_formulation.cc), through the adapter of
// petsc_adapter.h; PETSc's process is petsc_process.h's. Without PETSc, petsc_stub.cc stands in
// (petsc.cmake chooses).
#pragma once

#include <memory>
#include <string>

#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has PETSc (defined by the adapter, or false by the stub).
bool PetscAvailable();
// The version of PETSc this build is linked with, from its headers or library; "" without it.
std::string PetscVersion();
// Registry factories; without PETSc they throw std::invalid_argument. Backend option
// `petsc_options`: a PETSc options string ("-snes_max_it 20 -pc_factor_mat_solver_type
// superlu"), applied over the formulation's defaults (petsc_adapter.h).
std::unique_ptr<Formulation> MakePetscRsls(const FormulationConfig& config);
std::unique_ptr<Formulation> MakePetscSsls(const FormulationConfig& config);

// PETSc starts once per process, on the first PETSc formulation made (an MPI start costs about
// half a second, which no command without PETSc should pay); a host that owns the process (the
// harness's main) keeps this object for its lifetime, and PETSc (and MPI, when PETSc started
// it) is finalised when it goes. Without such an owner, PETSc is finalised at exit.
class PetscProcessScope {
 public:
  PetscProcessScope() = default;
  ~PetscProcessScope();
  PetscProcessScope(const PetscProcessScope&) = delete;
  PetscProcessScope& operator=(const PetscProcessScope&) = delete;
};

}  // namespace cb
