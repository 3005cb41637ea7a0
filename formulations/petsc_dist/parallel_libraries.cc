#include "formulations/petsc_dist/parallel_libraries.h"

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace cb {

namespace {

// The file of the shared library that defines `symbol` for this process ("" if none).
std::string DefiningLibrary(const char* symbol) {
  void* address = dlsym(RTLD_DEFAULT, symbol);
  Dl_info info;
  if (address == nullptr || dladdr(address, &info) == 0 || info.dli_fname == nullptr) return "";
  return info.dli_fname;
}

bool IsSequential(const std::string& library) {
  return library.find("_seq") != std::string::npos || library.find("mpiseq") != std::string::npos;
}

// Started by an MPI launcher (one process or several), before MPI is initialised. One process
// under mpirun needs the parallel libraries first too: PETSc's MPI_Init then reaches Open MPI
// while the stand-in's MPI_Finalize would take the finalisation, and mpirun reports the
// process as ended without finalising (status 1 after verified records).
bool LaunchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && std::atoi(value) >= 1) return true;
  }
  return false;
}

// The loaded libraries whose file name starts with one of the parallel libraries' names (and
// is not a sequential one): Open MPI's C and Fortran bindings, the parallel MUMPS and ScaLAPACK
// (its BLACS: the sequential MUMPS and its libmpiseq define stand-ins of blacs_gridinit_ that
// stop the process, "BLACS_GRIDINIT should not be called", when MUMPS on several processes
// calls them for its root's dense ScaLAPACK factorisation).
std::vector<std::string> LoadedParallelLibraries() {
  std::vector<std::string> found;
  auto visit = [](dl_phdr_info* info, std::size_t, void* data) {
    const std::string path = info->dlpi_name != nullptr ? info->dlpi_name : "";
    const std::string file = path.substr(path.find_last_of('/') + 1);
    for (const char* prefix :
         {"libmpi_mpifh.so", "libmpi.so", "libmumps_common-", "libdmumps-", "libscalapack-"}) {
      if (file.rfind(prefix, 0) == 0 && !IsSequential(file)) {
        static_cast<std::vector<std::string>*>(data)->push_back(path);
      }
    }
    return 0;
  };
  dl_iterate_phdr(visit, &found);
  return found;
}

}  // namespace

std::string SequentialStandIn() {
  for (const char* symbol : {"MPI_Comm_rank", "mpi_comm_rank_", "dmumps_c"}) {
    const std::string library = DefiningLibrary(symbol);
    if (IsSequential(library)) return library;
  }
  return "";
}

std::string ParallelLibrariesPreload() {
  if (!LaunchedByMpi() || SequentialStandIn().empty()) return "";
  std::string list;
  for (const std::string& path : LoadedParallelLibraries())
    list += (list.empty() ? "" : ":") + path;
  return list;
}

}  // namespace cb
