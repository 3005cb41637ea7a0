// The smoothed Fischer-Burmeister function (12) and its generalised Jacobian
// (step_equations.h).
#include <cmath>

#include "formulations/common/step_equations.h"

namespace cb {

double SmoothedFischerBurmeister(double a, double b, double rho) {
  return std::sqrt(a * a + b * b + 2.0 * rho * rho) - (a + b);
}

void FischerBurmeisterElement(double a, double b, double rho, double* d_a, double* d_b,
                              double* d_rho) {
  const double s = std::sqrt(a * a + b * b + 2.0 * rho * rho);
  if (s > 0.0) {
    *d_a = a / s - 1.0;
    *d_b = b / s - 1.0;
    *d_rho = 2.0 * rho / s;
  } else {
    // The limit along (a, b) = t (1, 1), t -> 0+ (see the header).
    *d_a = M_SQRT1_2 - 1.0;
    *d_b = M_SQRT1_2 - 1.0;
    *d_rho = 0.0;
  }
}

}  // namespace cb
