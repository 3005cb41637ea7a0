// Newton's stall guard (SolverOptions::nonmonotone_window): once two iterations in a row had
// their full step rejected, the Armijo test is measured from the largest merit of the last
// nonmonotone_window iterates instead of the current one, for the rest of the solve (Grippo,
// Lampariello & Lucidi, SIAM J. Numer. Anal. 23, 1986). Shared by the serial Newton and the
// distributed one's line search (formulations/petsc_dist/dist_line_search.h), so that both
// globalise alike.
#pragma once

#include <vector>

namespace cb {

class NonmonotoneReference {
 public:
  // `window` >= 1 (1: monotone); `merit` at the start.
  NonmonotoneReference(int window, double merit);

  // The merit the next Armijo test is measured from, at an iterate of merit `merit`.
  double Reference(double merit) const;
  // After an accepted step of factor `step` to an iterate of merit `merit`.
  void Accept(double merit, double step);
  // The last accepted step was the full one (or none was taken yet).
  bool last_step_full() const { return damped_in_a_row_ == 0; }

 private:
  static constexpr int kStallIterations = 2;

  int window_;
  std::vector<double> recent_;
  int damped_in_a_row_ = 0;
  bool nonmonotone_ = false;
};

}  // namespace cb
