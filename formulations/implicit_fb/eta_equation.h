// The smoothing of the implicit formulation (Kanno & Ohsaki, METR 2009-06): the eta equation
// (32) that ties rho to the complementarity residual, its compatible rho (43) and the gamma of
// (37). implicit-fb and nlopt-merit both use it.
#pragma once

#include <string>

namespace cb {

// The eta cases of docs/method.md section 2 (the report's section 5.1).
enum class EtaCase { kCase1 = 1, kCase2 = 2, kCase3 = 3, kNonsmooth = 4 };

// The eta equation (32) divided by nc, in terms of the mean m = g^T r^ / nc (<= 0 at a
// solution) and rho:
//   case 1: -gamma^2 m - (exp(gamma rho) - 1)   eta1(c) = gamma^2 c + 1, eta2(c) = exp(gamma c)
//   case 2: -m - (rho + rho^3)                  eta1(c) = c,             eta2(c) = c + c^3
//   case 3: -m - 2 rho^2                        eta1(c) = c / 2,         eta2(c) = c^2
//   case 4: rho                                 rho fixed at 0 (nonsmooth FB)
struct EtaEquation {
  EtaCase eta = EtaCase::kCase1;
  double gamma = 1.0;  // case 1 only, from (37)

  double Value(double mean_gr, double rho) const;
  double DerivativeMean(double rho) const;  // d/dm
  double DerivativeRho(double rho) const;   // d/drho
  // The rho solving Value(m, rho) = 0: (43) as corrected for case 1, the real root of
  // rho + rho^3 = -m for case 2, sqrt(-m / 2) for case 3 (NaN when m > 0), 0 for case 4.
  double CompatibleRho(double mean_gr) const;
};

// gamma of (37) for a start with mean m0 = g0^T r0 / nc: 1 when m0 < 1 - gamma_tol, else
// sqrt((1 - gamma_tol) / m0), which keeps 1 - gamma^2 m0 >= gamma_tol > 0 so (43) is defined.
double WarmStartGamma(double mean_gr, double gamma_tol);

// Whether `eta` names one of the cases above (1..4); otherwise false with the reason in *why.
// The one check of the range: the formulations' options and the CLI both ask it.
bool IsValidEtaCase(int eta, std::string* why);

// Whether the smoothing settings of a formulation are in range: an eta case 1..4, gamma_tol
// (gamma_ of (37)) in (0, 1) and rho_min (rho_ of (42)) positive; otherwise false with the
// reason in *why. Every formulation with these settings checks them here.
bool IsValidSmoothing(EtaCase eta, double gamma_tol, double rho_min, std::string* why);

}  // namespace cb
