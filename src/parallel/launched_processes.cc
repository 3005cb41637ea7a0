// The processes a launcher started (processes.h), read from its environment: the same in builds
// with and without MPI, since the launcher may start a serial build too.
#include <cstdlib>

#include "parallel/processes.h"

namespace cb {

int LaunchedProcessCount() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name)) {
      char* end = nullptr;
      const long count = std::strtol(value, &end, 10);
      if (end != value && *end == '\0' && count >= 1 && count <= 1000000) {
        return static_cast<int>(count);
      }
    }
  }
  return 1;
}

}  // namespace cb
