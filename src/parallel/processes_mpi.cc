// The processes of a build with MPI (processes.h): MPI_COMM_WORLD while MPI runs (PETSc started
// it and has not finalised it), one process otherwise.
#include <mpi.h>

#include "parallel/processes.h"

namespace cb {

namespace {

bool MpiRunning() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized != 0 && finalized == 0;
}

}  // namespace

int ProcessRank() {
  if (!MpiRunning()) return 0;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int ProcessCount() {
  if (!MpiRunning()) return 1;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

bool Distributed() { return ProcessCount() > 1; }

bool AnyProcess(bool mine) {
  if (!Distributed()) return mine;
  int local = mine ? 1 : 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any != 0;
}

int MinOverProcesses(int mine) {
  if (!Distributed()) return mine;
  int least = mine;
  MPI_Allreduce(&mine, &least, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return least;
}

int BroadcastFromZero(int word) {
  if (!Distributed()) return word;
  MPI_Bcast(&word, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return word;
}

std::string MpiVersion() {
  // Allowed before MPI_Init (MPI 3.1 section 8.7).
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  if (MPI_Get_library_version(text, &length) != MPI_SUCCESS) return "";
  std::string version(text, static_cast<std::size_t>(length));
  const auto end = version.find_first_of(",\n");  // "Open MPI v4.1.4, package: ..."
  return end == std::string::npos ? version : version.substr(0, end);
}

}  // namespace cb
