// Pin-jointed truss in 2-D or 3-D with linear elastic members and Biot (engineering) strain:
// member force N = E A (l - L) / L, energy E A L ((l - L) / L)^2 / 2. The energy, gradient and
// Hessian are geometrically exact (large displacements).
#pragma once

#include <memory>
#include <vector>

#include "core/sparse.h"
#include "model/elastic_body.h"

namespace cb {

struct TrussMember {
  int node_i = 0;
  int node_j = 0;
  double youngs_modulus = 0.0;  // E
  double area = 0.0;            // A
};

class Truss final : public ElasticBody {
 public:
  // `coordinates`: one row per node, dim() = 2 or 3 columns. `fixed[n * dim + c]` marks
  // supported components (size num_nodes * dim, or empty for none). Throws
  // std::invalid_argument for unknown nodes, zero-length members, E <= 0 or A <= 0.
  Truss(Mat coordinates, std::vector<TrussMember> members, const std::vector<bool>& fixed = {});

  int dim() const override { return static_cast<int>(coordinates_.cols()); }
  int num_nodes() const override { return static_cast<int>(coordinates_.rows()); }
  const DofMap& dofs() const override { return dofs_; }
  Point reference(int node) const override { return coordinates_.row(node).transpose(); }
  bool is_linear() const override { return false; }
  double Energy(const Vec& u) const override;
  void InternalForce(const Vec& u, Vec* force) const override;
  // Sum over members of |N e| per row (a member's force along it, at both ends).
  void InternalForceMagnitudes(const Vec& u, Vec* magnitudes) const override;
  void Stiffness(const Vec& u, SpMat* stiffness) const override;
  std::vector<std::pair<int, int>> StiffnessEntries() const override { return stiffness_entries_; }
  void AddStiffness(const Vec& u, double scale, const int* slots, double* values) const override;
  void InternalForceAndStiffness(const Vec& u, Vec* force, double scale, const int* slots,
                                 double* values) const override;

  std::vector<std::vector<int>> Cells() const override;
  std::shared_ptr<const ElasticBody> Restricted(const std::vector<int>& elements) const override;
  // axial_force N and axial_stress N / A (Biot stress on the reference area) of each member.
  std::vector<CellField> CellFields(const Vec& u) const override;
  const std::vector<TrussMember>& members() const { return members_; }
  // The dofs of a member's end nodes, [node_i components, node_j components], -1 if fixed.
  struct MemberDofs {
    int dof[6];
  };
  double ReferenceLength(int member) const { return lengths_[member]; }
  // Axial force N = E A (l - L) / L of a member (tension positive).
  double MemberForce(int member, const Vec& u) const;

 private:
  struct Kinematics {
    double delta[3];    // x_j - x_i (dim() entries used)
    double length;      // l = |x_j - x_i|
    double elongation;  // l - L, computed without cancellation
  };

  Kinematics MemberKinematics(std::size_t member, const Vec& u) const;
  // grad pi_m of one member added into *force; with `magnitudes`, its entries' absolute values.
  void AddMemberForce(std::size_t member, const Kinematics& kin, Vec* force,
                      bool magnitudes = false) const;
  // The stiffness blocks and, when force is not null, the internal force, member by member.
  template <int D>
  void AddStiffnessOf(const Vec& u, double scale, const int* slots, double* values,
                      Vec* force) const;

  Mat coordinates_;
  std::vector<TrussMember> members_;
  std::vector<double> lengths_;
  std::vector<Point> reference_deltas_;  // X_j - X_i
  std::vector<MemberDofs> member_dofs_;
  DofMap dofs_;
  std::vector<std::pair<int, int>> stiffness_entries_;  // in AddStiffness's order
  ScatterPattern stiffness_pattern_;
};

}  // namespace cb
