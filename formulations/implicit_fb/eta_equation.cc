#include "formulations/implicit_fb/eta_equation.h"

#include <cmath>
#include <limits>

namespace cb {

double EtaEquation::Value(double m, double rho) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * gamma * m - std::expm1(gamma * rho);
    case EtaCase::kCase2:
      return -m - (rho + rho * rho * rho);
    case EtaCase::kCase3:
      return -m - 2.0 * rho * rho;
    case EtaCase::kNonsmooth:
      return rho;
  }
  return 0.0;
}

double EtaEquation::DerivativeMean(double /*rho*/) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * gamma;
    case EtaCase::kCase2:
    case EtaCase::kCase3:
      return -1.0;
    case EtaCase::kNonsmooth:
      return 0.0;
  }
  return 0.0;
}

double EtaEquation::DerivativeRho(double rho) const {
  switch (eta) {
    case EtaCase::kCase1:
      return -gamma * std::exp(gamma * rho);
    case EtaCase::kCase2:
      return -(1.0 + 3.0 * rho * rho);
    case EtaCase::kCase3:
      return -4.0 * rho;
    case EtaCase::kNonsmooth:
      return 1.0;
  }
  return 0.0;
}

double EtaEquation::CompatibleRho(double m) const {
  switch (eta) {
    case EtaCase::kCase1: {
      // (43) with gamma^2, consistent with (32): exp(gamma rho) = 1 - gamma^2 m.
      const double argument = 1.0 - gamma * gamma * m;
      if (!(argument > 0.0)) return std::numeric_limits<double>::quiet_NaN();
      return std::log1p(-gamma * gamma * m) / gamma;
    }
    case EtaCase::kCase2: {
      // rho^3 + rho - q = 0 has exactly one real root (the left side is increasing): Cardano,
      // polished by Newton steps against cancellation.
      const double q = -m;
      const double s = std::sqrt(0.25 * q * q + 1.0 / 27.0);
      double rho = std::cbrt(0.5 * q + s) + std::cbrt(0.5 * q - s);
      for (int i = 0; i < 3; ++i) rho -= (rho * rho * rho + rho - q) / (3.0 * rho * rho + 1.0);
      return rho;
    }
    case EtaCase::kCase3:
      if (m > 0.0) return std::numeric_limits<double>::quiet_NaN();
      return std::sqrt(-0.5 * m);
    case EtaCase::kNonsmooth:
      return 0.0;
  }
  return 0.0;
}

double WarmStartGamma(double m, double gamma_tol) {
  // (37): g0^T r0 < nc (1 - gamma_), divided by nc.
  if (m < 1.0 - gamma_tol) return 1.0;
  return std::sqrt((1.0 - gamma_tol) / m);
}

bool IsValidEtaCase(int eta, std::string* why) {
  if (eta >= 1 && eta <= 4) return true;
  *why = "eta must be 1, 2, 3 or 4 (got " + std::to_string(eta) + ")";
  return false;
}

bool IsValidSmoothing(EtaCase eta, double gamma_tol, double rho_min, std::string* why) {
  if (!IsValidEtaCase(static_cast<int>(eta), why)) {
    return false;
  } else if (!(gamma_tol > 0.0 && gamma_tol < 1.0)) {
    *why = "gamma_tol must be in (0, 1)";
  } else if (!(rho_min > 0.0) || !std::isfinite(rho_min)) {
    *why = "rho_min must be positive";
  } else {
    return true;
  }
  return false;
}

}  // namespace cb
