#include "core/library_versions.h"

#include <Eigen/Core>

#ifdef CONTACTBENCH_HAVE_SUITESPARSE
#include <cholmod.h>
#endif

namespace cb {

std::string EigenVersion() {
  return std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION);
}

std::string SuiteSparseVersion() {
#ifdef CONTACTBENCH_HAVE_SUITESPARSE
  return std::to_string(SUITESPARSE_MAIN_VERSION) + "." + std::to_string(SUITESPARSE_SUB_VERSION) +
         "." + std::to_string(SUITESPARSE_SUBSUB_VERSION) + " (CHOLMOD " +
         std::to_string(CHOLMOD_MAIN_VERSION) + "." + std::to_string(CHOLMOD_SUB_VERSION) + "." +
         std::to_string(CHOLMOD_SUBSUB_VERSION) + ")";
#else
  return "";
#endif
}

}  // namespace cb
