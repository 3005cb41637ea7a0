// A structured mesh of nx x ny x nz hexahedra filling the box [0, Lx] x [0, Ly] x [0, Lz],
// graded toward the origin: node i along an axis of n cells sits at L (i / n)^g, g >= 1, so
// that cells are smallest at the face through the origin (and smallest of all at the origin,
// where a contact problem puts its contact point).
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "model/solid_hex8.h"

namespace cb {

struct BoxMeshSpec {
  std::array<int, 3> cells = {1, 1, 1};             // nx, ny, nz
  std::array<double, 3> size = {1.0, 1.0, 1.0};     // Lx, Ly, Lz
  std::array<double, 3> grading = {1.0, 1.0, 1.0};  // the exponents g
};

struct BoxMesh {
  Mat coordinates;                           // num_nodes x 3
  std::vector<SolidHex8::Element> elements;  // VTK order
  std::array<int, 3> cells = {0, 0, 0};
  // Node id of lattice point (i, j, k).
  int node(int i, int j, int k) const { return (k * (cells[1] + 1) + j) * (cells[0] + 1) + i; }
  // The nodes with coordinate index `index` (0 or cells[axis]) along `axis`.
  std::vector<int> FaceNodes(int axis, int index) const;
  // The element faces (4 nodes around) on that side.
  std::vector<SolidHex8::Face> Faces(int axis, int index) const;
};

// Throws std::invalid_argument for a cell count < 1, a size <= 0 or a grading < 1.
BoxMesh MakeBoxMesh(const BoxMeshSpec& spec);

}  // namespace cb
