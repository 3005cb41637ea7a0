// The processes of a run: this process's rank and their count, and the collectives the harness
// and the distributed backend need. The only place outside the distributed backend's own
// adapter (formulations/petsc_dist) that talks to MPI: processes_mpi.cc where the build has MPI
// (with PETSc, formulations/petsc/petsc.cmake), processes_serial.cc otherwise (one process;
// parallel.cmake chooses).
//
// MPI is started by PETSc, on the first PETSc formulation made (formulations/petsc/petsc.h):
// until then, and after it is finalised, the run is one process, rank 0. A collective must be
// called by every process at the same point; with one process each returns its argument.
#pragma once

#include <string>

namespace cb {

// This process's rank in the run (0 .. ProcessCount() - 1) and the number of processes.
int ProcessRank();
int ProcessCount();
// Whether the run has more than one process.
bool Distributed();
// The processes the run was launched with, as its launcher says (OMPI_COMM_WORLD_SIZE,
// PMI_SIZE): known before MPI starts, for what is decided before (the memory estimate, a
// rerun's check). 1 without a launcher or when its value is not a count of 1 to 1e6.
int LaunchedProcessCount();

// Collectives (every process calls them at the same point).
// Whether `mine` holds on any process.
bool AnyProcess(bool mine);
// The least of `mine` over the processes.
int MinOverProcesses(int mine);
// Process 0's `word` on every process (the others' argument is ignored).
int BroadcastFromZero(int word);

// The MPI library this build is linked with ("Open MPI v4.1.4"); "" without MPI.
std::string MpiVersion();

}  // namespace cb
