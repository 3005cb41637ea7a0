// An elastic body discretised by nodes: the energy part of a contact model. Nodes have
// reference coordinates X and `dim` displacement components each; a component is either a
// free dof (an index into u) or fixed at zero (a support).
#pragma once

#include <memory>
#include <stdexcept>
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
  // The `fixed` flags this map was made from (node * dim + component).
  std::vector<bool> FixedComponents() const;
  int num_dofs() const { return num_dofs_; }
  int dof(int node, int component) const { return map_[node * dim_ + component]; }

 private:
  int dim_ = 0;
  int num_nodes_ = 0;
  int num_dofs_ = 0;
  std::vector<int> map_;
};

// A quantity of the elements at a state, for output: its name (as VTK files and plots label
// it) and `components` values per element (a tensor's 9, row by row), element after element in
// the order of ElasticBody::Cells().
struct CellField {
  std::string name;
  std::vector<double> values;
  int components = 1;
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
  // See ContactModel::InternalForceMagnitudes; the default is |K(u)| |u|.
  virtual void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const;
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

  // The same nodes, dofs and material with only `elements` (indices in the order of Cells()):
  // its energy, internal force and stiffness are those elements' shares, so the bodies of a
  // partition of the element list sum to this one (a distributed evaluation gives each process
  // one). Throws std::invalid_argument for an index out of range.
  virtual std::shared_ptr<const ElasticBody> Restricted(const std::vector<int>& elements) const = 0;

  int num_dofs() const { return dofs().num_dofs(); }
  // Current position X + u of a node; fixed components stay at X.
  Point Position(int node, const Vec& u) const;
};

// The entries `indices` of a body's element list `all` (ElasticBody::Restricted); an index out of
// range throws std::invalid_argument naming `body`.
template <typename Element>
std::vector<Element> SelectElements(const std::vector<Element>& all,
                                    const std::vector<int>& indices, const char* body) {
  std::vector<Element> selected;
  selected.reserve(indices.size());
  for (int k : indices) {
    if (k < 0 || static_cast<std::size_t>(k) >= all.size()) {
      throw std::invalid_argument(std::string(body) + ": element " + std::to_string(k) +
                                  " out of range (" + std::to_string(all.size()) + " elements)");
    }
    selected.push_back(all[static_cast<std::size_t>(k)]);
  }
  return selected;
}

}  // namespace cb
