// PETSc's process lifecycle, apart from the adapter (petsc_adapter.h) and shared with the
// distributed backend (formulations/petsc_dist). PETSc is started on first use with
//   -no_signal_handler   the suite's SIGINT / SIGTERM handling (exit 4, records kept) stays;
//   -skip_petscrc        no ~/.petscrc or ./.petscrc is read (PETSC_OPTIONS still is);
// (starting MPI with it; the serial formulations work on PETSC_COMM_SELF, so a process launched
// without mpirun is one rank), and finalised by a PetscProcessScope (petsc.h) or at exit. Every
// call into PETSc runs under an error handler that records PETSc's message instead of printing
// it; the failed call then throws (std::invalid_argument for a bad option value) or, inside a
// solve, the step fails with the message (PetscErrorCapture). Built only when PETSc is found.
#pragma once

#include <petscsys.h>

#include <string>

namespace cb {

// Starts PETSc unless the process already has (see the top of the file); once per process.
void StartPetsc();

// Whether PETSc has been finalised (at exit): objects left to free are PETSc's no more.
bool PetscGone();

// While it lives, PETSc's errors are recorded (the first report of the one being raised), not
// printed; PetscErrorText then quotes it.
class PetscErrorCapture {
 public:
  PetscErrorCapture();
  ~PetscErrorCapture();
  PetscErrorCapture(const PetscErrorCapture&) = delete;
  PetscErrorCapture& operator=(const PetscErrorCapture&) = delete;
};

// "PETSc <call> failed (error <code>): <the recorded message>".
std::string PetscErrorText(PetscErrorCode code, const char* call);

// Throws std::runtime_error with PetscErrorText when `code` is an error.
void Try(PetscErrorCode code, const char* call);

}  // namespace cb
