// The distributed backend: the step systems of the equation formulations and of PETSc's SNESVI
// over MPI processes (docs/scale-out.md): `dist-implicit-fb`, `dist-nonsmooth-fb`,
// `dist-active-set` (PETSc SNES newtonls on the rows of implicit-fb, nonsmooth-fb, active-set)
// and `dist-petsc-rsls`, `dist-petsc-ssls` (SNESVI on the MCP of petsc-rsls / petsc-ssls), each
// its serial counterpart's rows (common/step_rows.h) in a file of its own (dist_formulation.h).
// Launched with `mpirun -n N contactbench run --formulation dist-...`; without mpirun, one
// process. Without PETSc, petsc_dist_stub.cc stands in (petsc_dist.cmake chooses).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "formulations/common/config.h"
#include "model/elastic_body.h"
#include "step/formulation.h"

namespace cb {

// Whether this build has the distributed backend (PETSc with MPI). The processes of the run
// (rank, count, collectives) are src/parallel/processes.h's.
bool DistAvailable();

// Registry factories; without PETSc they throw std::invalid_argument. Backend option
// `petsc_options` (the CLI's --petsc-options), applied over the defaults (petsc_dist_adapter.h).
// Each split of the body's elements over the processes goes to the config's element_split.
std::unique_ptr<Formulation> MakeDistImplicitFb(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeDistNonsmoothFb(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeDistActiveSet(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeDistPetscRsls(const FormulationConfig& config);
std::unique_ptr<Formulation> MakeDistPetscSsls(const FormulationConfig& config);

}  // namespace cb
