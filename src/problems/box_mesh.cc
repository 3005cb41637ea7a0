#include "problems/box_mesh.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cb {
namespace {

const char* kAxisName[3] = {"x", "y", "z"};

void CheckSpec(const BoxMeshSpec& spec) {
  for (int axis = 0; axis < 3; ++axis) {
    const std::string name = kAxisName[axis];
    if (spec.cells[axis] < 1) {
      throw std::invalid_argument("box mesh: cells along " + name + " must be >= 1, got " +
                                  std::to_string(spec.cells[axis]));
    }
    if (!(spec.size[axis] > 0.0) || !std::isfinite(spec.size[axis])) {
      throw std::invalid_argument("box mesh: size along " + name + " must be positive, got " +
                                  std::to_string(spec.size[axis]));
    }
    if (!(spec.grading[axis] >= 1.0) || !std::isfinite(spec.grading[axis])) {
      throw std::invalid_argument("box mesh: grading along " + name + " must be >= 1, got " +
                                  std::to_string(spec.grading[axis]));
    }
  }
}

// Lattice point (a, b) of the side `index` along `axis`, a and b running over the other two
// axes in cyclic order.
int SideNode(const BoxMesh& mesh, int axis, int index, int a, int b) {
  int ijk[3];
  ijk[axis] = index;
  ijk[(axis + 1) % 3] = a;
  ijk[(axis + 2) % 3] = b;
  return mesh.node(ijk[0], ijk[1], ijk[2]);
}

void CheckSide(const BoxMesh& mesh, int axis, int index) {
  if (axis < 0 || axis > 2 || (index != 0 && index != mesh.cells[axis])) {
    throw std::invalid_argument("box mesh: no side " + std::to_string(index) + " along axis " +
                                std::to_string(axis));
  }
}
}  // namespace

BoxMesh MakeBoxMesh(const BoxMeshSpec& spec) {
  CheckSpec(spec);
  BoxMesh mesh;
  mesh.cells = spec.cells;
  const auto [nx, ny, nz] = spec.cells;
  std::array<std::vector<double>, 3> lattice;
  for (int axis = 0; axis < 3; ++axis) {
    const int n = spec.cells[axis];
    for (int i = 0; i <= n; ++i) {
      lattice[axis].push_back(spec.size[axis] *
                              std::pow(static_cast<double>(i) / n, spec.grading[axis]));
    }
  }
  mesh.coordinates.resize(static_cast<Eigen::Index>(nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.coordinates.row(mesh.node(i, j, k)) << lattice[0][i], lattice[1][j], lattice[2][k];
      }
    }
  }
  mesh.elements.reserve(static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        mesh.elements.push_back({mesh.node(i, j, k), mesh.node(i + 1, j, k),
                                 mesh.node(i + 1, j + 1, k), mesh.node(i, j + 1, k),
                                 mesh.node(i, j, k + 1), mesh.node(i + 1, j, k + 1),
                                 mesh.node(i + 1, j + 1, k + 1), mesh.node(i, j + 1, k + 1)});
      }
    }
  }
  return mesh;
}

std::vector<int> BoxMesh::FaceNodes(int axis, int index) const {
  CheckSide(*this, axis, index);
  std::vector<int> nodes;
  const int na = cells[(axis + 1) % 3], nb = cells[(axis + 2) % 3];
  for (int b = 0; b <= nb; ++b) {
    for (int a = 0; a <= na; ++a) nodes.push_back(SideNode(*this, axis, index, a, b));
  }
  return nodes;
}

std::vector<SolidHex8::Face> BoxMesh::Faces(int axis, int index) const {
  CheckSide(*this, axis, index);
  std::vector<SolidHex8::Face> faces;
  const int na = cells[(axis + 1) % 3], nb = cells[(axis + 2) % 3];
  for (int b = 0; b < nb; ++b) {
    for (int a = 0; a < na; ++a) {
      faces.push_back({SideNode(*this, axis, index, a, b), SideNode(*this, axis, index, a + 1, b),
                       SideNode(*this, axis, index, a + 1, b + 1),
                       SideNode(*this, axis, index, a, b + 1)});
    }
  }
  return faces;
}

}  // namespace cb
