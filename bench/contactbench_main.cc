// The suite driver: see harness/cli.h.
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "core/abandonable_work.h"
#include "formulations/petsc/petsc.h"
#include "formulations/petsc_dist/parallel_libraries.h"
#include "harness/cli.h"
#include "harness/interrupt.h"
#include "harness/relaunch.h"

namespace {

// Set when the driver returns its status. A library that ends the process from inside the run
// with exit(0) (a Fortran STOP: the sequential MUMPS's stand-in BLACS did, leaving mpirun
// status 0 and no run.json) must not pass for success: the process then exits with 70
// (EX_SOFTWARE). Nothing in the suite calls exit(), so every other exit returns through main.
bool returned = false;

void ExitedFromInsideTheRun() {
  if (!returned) std::_Exit(70);
}

}  // namespace

int main(int argc, char** argv) {
  std::atexit(ExitedFromInsideTheRun);
  // Under mpirun, before MPI starts: the parallel MPI and MUMPS in front of the sequential
  // stand-ins Ipopt and Siconos link (parallel_libraries.h); nothing to do otherwise.
  cb::harness::RelaunchWithLibrariesFirst(cb::ParallelLibrariesPreload(), argv);
  // Before anything else, so that a signal at any time stops the run the same way.
  cb::harness::InstallInterruptHandlers();
  // A file size limit (ulimit -f) then fails the write that exceeds it, which the records
  // report (exit 3), instead of killing the process in the middle of a line.
  std::signal(SIGXFSZ, SIG_IGN);
  int status = 0;
  {
    // PETSc starts on first use, once per process; this scope finalises it (petsc.h).
    const cb::PetscProcessScope petsc;
    status = cb::harness::Main(argc, argv);
  }
  returned = true;
  if (cb::AbandonedWorkRunning()) {
    // A factorisation abandoned on an interrupt is still running: the static destructors would
    // tear down the BLAS under it (core/abandonable_work.h). The records are written already.
    std::fflush(nullptr);
    std::_Exit(status);
  }
  return status;
}
