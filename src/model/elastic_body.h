// An elastic body discretised by nodes: the energy part of a contact model. Nodes have
// reference coordinates X and `dim` displacement components each; a component is either a
// free dof (an index into u) or fixed at zero (a support).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace cb {

// Node/component -> dof index, -1 for a fixed (supported) component.
class DofMap {
 public:
  DofMap() = default;
  // All components free, numbered node by node.
  DofMap(int num_nodes, int dim);
  // `fixed[n * dim + c]` true for supported components; free ones are numbered in order.
  DofMap(int num_nodes, int dim, const std::vector<bool>& fixed);

  int dim() const { return dim_; }
  int num_nodes() const { return num_nodes_; }
  int num_dofs() const { return num_dofs_; }
  int dof(int node, int component) const { return map_[node * dim_ + component]; }

 private:
  int dim_ = 0;
  int num_nodes_ = 0;
  int num_dofs_ = 0;
  std::vector<int> map_;
};

// A quantity of the elements at a state, for output: its name (as VTK files and plots label
// it) and one value per element, in the order of ElasticBody::Cells().
struct CellField {
  std::string name;
  std::vector<double> values;
};

class ElasticBody {
 public:
  virtual ~ElasticBody() = default;
  virtual int dim() const = 0;
  virtual int num_nodes() const = 0;
  virtual const DofMap& dofs() const = 0;
  // Reference position of a node (size dim()).
  virtual Point reference(int node) const = 0;
  virtual bool is_linear() const = 0;
  virtual double Energy(const Vec& u) const = 0;
  virtual void InternalForce(const Vec& u, Vec* force) const = 0;
  // Pattern fixed at construction.
  virtual void Stiffness(const Vec& u, SpMat* stiffness) const = 0;
  // The stiffness as a stream of contributions (see ContactModel::StiffnessEntries).
  virtual std::vector<std::pair<int, int>> StiffnessEntries() const = 0;
  virtual void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const = 0;
  // InternalForce and AddStiffness at the same u in one call, for a Newton iteration that needs
  // both (see ContactModel::InternalForceAndStiffness). Element-by-element bodies override it to
  // compute each element's kinematics once; the results equal the two separate calls bit for bit.
  virtual void InternalForceAndStiffness(const Vec& u, Vec* force, double scale, const int* slots,
                                         double* values) const {
    InternalForce(u, force);
    AddStiffness(u, scale, slots, values);
  }

  // The elements as node lists, for output (2 nodes: a line, 4: a quadrilateral, 8: a
  // hexahedron; VTK cells).
  virtual std::vector<std::vector<int>> Cells() const = 0;
  // The element quantities at displacement u (a truss's member forces, a continuum's stress);
  // none by default.
  virtual std::vector<CellField> CellFields(const Vec& /*u*/) const { return {}; }

  int num_dofs() const { return dofs().num_dofs(); }
  // Current position X + u of a node; fixed components stay at X.
  Point Position(int node, const Vec& u) const;
};

}  // namespace cb
