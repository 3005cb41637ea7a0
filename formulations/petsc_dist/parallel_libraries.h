// Which libraries serve MPI and MUMPS in this process. Debian's Ipopt and Siconos link the
// sequential MUMPS (libdmumps_seq), which exports stand-ins of MPI (MPI_Comm_rank always 0, the
// Fortran mpi_* too) and its own dmumps_c; loaded before Open MPI and the parallel MUMPS, they
// serve PETSc as well, and every process of an mpirun believes it is process 0. Loading the
// parallel libraries first (LD_PRELOAD) puts the real ones in front for every caller; the
// sequential backends are not used in a distributed run.
#pragma once

#include <string>

namespace cb {

// The sequential stand-in that serves MPI or MUMPS in this process, "" when the real ones do.
std::string SequentialStandIn();

// Under an MPI launcher, of one process or several (OMPI_COMM_WORLD_SIZE, PMI_SIZE), with a
// stand-in serving: the parallel libraries, already loaded, to put first (a colon-separated
// LD_PRELOAD list); "" otherwise, and always without PETSc.
std::string ParallelLibrariesPreload();

}  // namespace cb
