// PETSc's process lifecycle (petsc_process.h): started once, finalised by its owner or at exit,
// and its errors recorded instead of printed.
#include "formulations/petsc/petsc_process.h"

#include <petscversion.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "formulations/petsc/petsc.h"

namespace cb {

bool PetscAvailable() { return true; }
std::string PetscVersion() {
  return std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
         std::to_string(PETSC_VERSION_SUBMINOR);
}

namespace {

bool started_here = false;  // PetscInitialize was ours, so PetscFinalize is too

void FinalizePetsc() {
  PetscBool initialized = PETSC_FALSE, finalized = PETSC_FALSE;
  PetscInitialized(&initialized);
  PetscFinalized(&finalized);
  if (started_here && initialized && !finalized) PetscFinalize();
}

// The message of the error being raised (its first report), instead of PETSc's printout.
std::string last_error;

PetscErrorCode RecordPetscError(MPI_Comm, int, const char* function, const char*,
                                PetscErrorCode code, PetscErrorType type, const char* message,
                                void*) {
  if (type == PETSC_ERROR_INITIAL || last_error.empty()) {
    const char* text = nullptr;
    if (message == nullptr || *message == '\0') PetscErrorMessage(code, &text, nullptr);
    last_error = std::string(function != nullptr ? function : "PETSc") + "(): " +
                 (text != nullptr      ? text
                  : message != nullptr ? message
                                       : "");
  }
  return code;
}

}  // namespace

bool PetscGone() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  return finalized;
}

PetscErrorCapture::PetscErrorCapture() {
  last_error.clear();
  PetscPushErrorHandler(RecordPetscError, nullptr);
}

PetscErrorCapture::~PetscErrorCapture() { PetscPopErrorHandler(); }

std::string PetscErrorText(PetscErrorCode code, const char* call) {
  std::string text = std::string("PETSc ") + call + " failed (error " + std::to_string(code) + ")";
  return last_error.empty() ? text : text + ": " + last_error;
}

void Try(PetscErrorCode code, const char* call) {
  if (code != 0) throw std::runtime_error(PetscErrorText(code, call));
}

void StartPetsc() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (initialized) return;
  static char name[] = "contactbench", no_signals[] = "-no_signal_handler",
              no_rc[] = "-skip_petscrc";
  static char* arguments[] = {name, no_signals, no_rc, nullptr};
  int argc = 3;
  char** argv = arguments;
  const PetscErrorCode code = PetscInitialize(&argc, &argv, nullptr, nullptr);
  if (code != 0) {
    throw std::runtime_error("PETSc: PetscInitialize failed (error " + std::to_string(code) + ")");
  }
  started_here = true;
  std::atexit(FinalizePetsc);  // a host without a PetscProcessScope
}

PetscProcessScope::~PetscProcessScope() { FinalizePetsc(); }

}  // namespace cb
