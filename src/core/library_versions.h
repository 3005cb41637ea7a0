// The versions of the libraries the core is built on, from their headers at build time (Eigen,
// SuiteSparse); run.json records them with the backends' (formulations/registry.h).
#pragma once

#include <string>

namespace cb {

std::string EigenVersion();
// SuiteSparse's version with CHOLMOD's ("5.12.0 (CHOLMOD 3.0.14)"); "" when built without it.
std::string SuiteSparseVersion();

}  // namespace cb
