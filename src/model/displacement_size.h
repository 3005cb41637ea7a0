// The size check every elastic body makes of the displacements it is given.
#pragma once

#include <stdexcept>
#include <string>

#include "core/types.h"

namespace cb {

// Throws std::invalid_argument ("BODY::WHAT: u has size .., expected ..") unless u has
// num_dofs entries.
inline void CheckDisplacementSize(const Vec& u, int num_dofs, const char* body, const char* what) {
  if (u.size() != num_dofs) {
    throw std::invalid_argument(std::string(body) + "::" + what + ": u has size " +
                                std::to_string(u.size()) + ", expected " +
                                std::to_string(num_dofs));
  }
}

}  // namespace cb
