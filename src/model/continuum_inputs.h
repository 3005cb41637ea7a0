// The checks the continuum elements (PlaneStressQ4, SolidHex8) make of their inputs alike: the
// node coordinates, the isotropic material and the supports. Each throws std::invalid_argument
// naming the body ("BODY: ...").
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/types.h"

namespace cb {

// Coordinates n x `dim`, every one finite.
inline void CheckNodeCoordinates(const char* body, const Mat& coordinates, int dim) {
  if (coordinates.cols() != dim) {
    throw std::invalid_argument(std::string(body) + ": coordinates have " +
                                std::to_string(coordinates.cols()) + " columns, expected " +
                                std::to_string(dim));
  }
  for (Eigen::Index n = 0; n < coordinates.rows(); ++n) {
    if (!coordinates.row(n).allFinite()) {
      throw std::invalid_argument(std::string(body) + ": node " + std::to_string(n) +
                                  " has non-finite coordinates");
    }
  }
}

// E > 0 and finite.
inline void CheckYoungsModulus(const char* body, double youngs_modulus) {
  if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus)) {
    throw std::invalid_argument(std::string(body) + ": Young's modulus must be positive, got " +
                                std::to_string(youngs_modulus));
  }
}

// nu in (-1, 0.5): the isotropic elasticity tensor is positive definite only there.
inline void CheckPoissonRatio(const char* body, double poisson_ratio) {
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5)) {
    throw std::invalid_argument(std::string(body) +
                                ": Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(poisson_ratio));
  }
}

// `fixed` empty (no supports) or one entry per degree of freedom, num_nodes * dim.
inline void CheckFixedSize(const char* body, const std::vector<bool>& fixed, int nodes, int dim) {
  if (!fixed.empty() && fixed.size() != static_cast<std::size_t>(nodes) * dim) {
    throw std::invalid_argument(std::string(body) + ": `fixed` has " +
                                std::to_string(fixed.size()) + " entries, expected num_nodes * " +
                                std::to_string(dim) + " = " + std::to_string(dim * nodes) +
                                " (or none)");
  }
}

}  // namespace cb
