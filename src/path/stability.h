// The stiffness of the path at an equilibrium state, bordered by the closed contacts:
//
//   A = [K_t  -G_c^T]     K_t = hess pi - sum_p r_p hess phi_p,
//       [G_c     0  ],    G_c = the gap-Jacobian rows of the pairs closed at the state.
//
// It gives the tangent of the path (docs/method.md section 5: A [du; dr] = [f; 0]) and the
// stability of the state. With Z a basis of the null space of G_c (the motions that keep the closed
// contacts closed), the state is stable when Z^T K_t Z is positive definite; its number of
// negative eigenvalues (the "unstable modes") changes where an eigenvalue crosses zero: at a
// limit point (the null vector phi has phi^T f != 0 and the load parameter turns) or at a
// bifurcation point (phi^T f = 0: the path crosses another branch, tangent to phi). The sign of
// det A alone misses two eigenvalues crossing between two steps (P2 has its limit point and its
// bifurcation point that close), so the modes are counted: by Sylvester's law of inertia, as
// the negative pivots of an LDL^T factorisation of K_t + rho G_c^T G_c, whose eigenvalues on
// Z tend to those of Z^T K_t Z while the m others grow with rho (rho = 1e6 max|diag K_t|,
// the rows of G_c being unit normals).
// Eigen's SparseLU (not the configurable solver) factorises A: the path's sizes are small and
// the tangent and null vector need nothing else. On a 3-D body both factorisations take minutes
// (the LDL^T of plate-3d at 32 x 32 x 32: over 90 s, issue 30), so a large A is factorised on a
// worker thread an interrupt abandons (core/abandonable_work.h); the factors are then missing.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <memory>
#include <string>
#include <vector>

#include "model/contact_model.h"
#include "step/step_problem.h"

namespace cb {

// The worker thread's name (at most 15 characters).
constexpr const char* kInterruptibleStiffnessThreadName = "stiffness-fact";

class BorderedStiffness {
 public:
  // kModes counts the unstable modes only (one LDL^T: what the driver needs at every accepted
  // state); kModesAndSolves also factorises A for the tangent and the null vector.
  enum class Use { kModes, kModesAndSolves };

  // Assembles A at `state`, counts its unstable modes and, for kModesAndSolves, factorises it.
  BorderedStiffness(const ContactModel& model, const ContactScales& scales, const State& state,
                    Use use = Use::kModesAndSolves);
  // The same with the closed pairs given (one flag per pair) instead of read off the state: the
  // two pieces of the path at a kink, where the state itself is on both.
  BorderedStiffness(const ContactModel& model, const ContactScales& scales, const State& state,
                    const std::vector<bool>& closed);

  // False when A is numerically singular, not finite or not factorised (kModes, or abandoned
  // on an interrupt: interrupted()); message() says why.
  bool ok() const { return ok_; }
  bool interrupted() const { return interrupted_; }
  const std::string& message() const { return message_; }
  // The number of negative eigenvalues of Z^T K_t Z (0: stable); -1 when not computed.
  int unstable_modes() const { return unstable_modes_; }
  int num_closed() const { return static_cast<int>(closed_pairs_.size()); }

  // The displacement part du of the solution of A [du; dr] = [rhs; 0].
  bool SolveDisplacement(const Vec& rhs, Vec* du) const;
  // Both parts: du, and dr for every pair (0 for the open ones).
  bool Solve(const Vec& rhs, Vec* du, Vec* dr) const;

  // An orthonormal basis (d x k) of the displacement parts of the k-dimensional near-null
  // space of A at a point where k eigenvalues are near zero, by block inverse iteration (A is
  // nearly singular there, so a few solves from any start converge).
  bool NullSpace(int k, int iterations, Mat* basis) const;

 private:
  void Build(const ContactModel& model, const State& state, Use use);
  // The inertia of *penalised and, for kModesAndSolves, the LU of *bordered (both taken over).
  void Factorize(SpMat* penalised, SpMat* bordered, Use use);

  int dofs_ = 0;
  int pairs_ = 0;
  std::vector<int> closed_pairs_;
  using Lu = Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>>;
  std::shared_ptr<Lu> lu_;  // made by the worker when there is one
  bool ok_ = false;
  bool interrupted_ = false;
  int unstable_modes_ = -1;
  std::string message_;
};

// The number of unstable modes at `state` (BorderedStiffness::unstable_modes, which factorises
// for them alone).
int UnstableModes(const ContactModel& model, const ContactScales& scales, const State& state);

// The gaps g = -phi(u) of the model at u.
Vec GapsAt(const ContactModel& model, const Vec& u);

// Contact status of each pair at (g, r): closed when min(g/L, -r/R) picks the gap.
std::vector<bool> ClosedPairs(const ContactScales& scales, const Vec& g, const Vec& r);

}  // namespace cb
