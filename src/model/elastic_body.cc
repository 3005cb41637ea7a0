#include "model/elastic_body.h"

#include <stdexcept>
#include <string>

namespace cb {
namespace {

void CheckShape(int num_nodes, int dim) {
  if (num_nodes < 0) {
    throw std::invalid_argument("DofMap: negative number of nodes " + std::to_string(num_nodes));
  }
  if (dim < 1) {
    throw std::invalid_argument("DofMap: dimension must be positive, got " + std::to_string(dim));
  }
}

}  // namespace

DofMap::DofMap(int num_nodes, int dim) : DofMap(num_nodes, dim, std::vector<bool>{}) {}

DofMap::DofMap(int num_nodes, int dim, const std::vector<bool>& fixed)
    : dim_(dim), num_nodes_(num_nodes) {
  CheckShape(num_nodes, dim);
  const std::size_t size = static_cast<std::size_t>(num_nodes) * static_cast<std::size_t>(dim);
  // An empty `fixed` means "no supports", the common case of a body held by contact alone.
  if (!fixed.empty() && fixed.size() != size) {
    throw std::invalid_argument("DofMap: `fixed` has " + std::to_string(fixed.size()) +
                                " entries, expected num_nodes * dim = " + std::to_string(size) +
                                " (or none)");
  }
  map_.resize(size);
  int next = 0;
  for (std::size_t k = 0; k < size; ++k) {
    map_[k] = (!fixed.empty() && fixed[k]) ? -1 : next++;
  }
  num_dofs_ = next;
}

std::vector<bool> DofMap::FixedComponents() const {
  std::vector<bool> fixed(map_.size());
  for (std::size_t k = 0; k < map_.size(); ++k) fixed[k] = map_[k] < 0;
  return fixed;
}

void ElasticBody::InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const {
  SpMat stiffness;
  Stiffness(u, &stiffness);
  *magnitudes = stiffness.cwiseAbs() * u.cwiseAbs();
}

Point ElasticBody::Position(int node, const Vec& u) const {
  Point x = reference(node);
  const DofMap& map = dofs();
  for (int c = 0; c < map.dim(); ++c) {
    const int dof = map.dof(node, c);
    if (dof >= 0) x[c] += u[dof];
  }
  return x;
}

}  // namespace cb
