// Starting the driver again in the same process (execv of itself) with libraries loaded first,
// before MPI is initialised: how a distributed run gets the parallel MPI and MUMPS in front of
// the sequential stand-ins another backend links (formulations/petsc_dist/parallel_libraries.h).
#pragma once

#include <string>

namespace cb::harness {

// With `preload` (a colon-separated LD_PRELOAD list) non-empty and this process not already
// relaunched: prepends it to LD_PRELOAD and replaces the process by /proc/self/exe with the
// same arguments. Returns only when there is nothing to do or the exec failed (the backend's
// own check then refuses the run with the reason).
void RelaunchWithLibrariesFirst(const std::string& preload, char** argv);

}  // namespace cb::harness
