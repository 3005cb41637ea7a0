#include "formulations/implicit_fb/implicit_fb_system.h"

namespace cb {

ImplicitFbSystem::ImplicitFbSystem(const StepProblem& step, EtaEquation eta,
                                   std::shared_ptr<PatternCache> cache)
    : StepEquationSystem(step, /*has_rho=*/true, std::move(cache)), eta_(eta) {
  if (layout().nc == 0 && eta_.eta != EtaCase::kNonsmooth) {
    // With no contact pairs (32) has no complementarity term; rho = 0 is its only sensible
    // value, which the nonsmooth row F4 = rho states.
    eta_.eta = EtaCase::kNonsmooth;
  }
  if (step.constraint.kind == ConstraintKind::kKink && eta_.eta == EtaCase::kCase3) {
    // On (53) the kink pair's row no longer holds rho (see StepEquationSystem::Residual), and
    // case 3's row -m - 2 rho^2 has no rho derivative at the kink's rho = 0: the Jacobian's
    // rho column vanishes there, and Newton creeps to rho ~ sqrt(tolerance), leaving the
    // complementarity residual at that size. Case 2's row -m - (rho + rho^3) has the same
    // solution on (53), rho = 0 with every pair complementary, and derivative -1 there.
    eta_.eta = EtaCase::kCase2;
  }
}

ImplicitFbSystem::~ImplicitFbSystem() = default;

double ImplicitFbSystem::Complementarity(double a, double b, double rho) const {
  return SmoothedFischerBurmeister(a, b, rho);  // (31)
}

void ImplicitFbSystem::ComplementarityElement(double a, double b, double rho, double* d_a,
                                              double* d_b, double* d_rho) const {
  // d/da = a/s - 1, d/db = b/s - 1, d/drho = 2 rho / s; at s = 0 (only with rho = 0 at
  // a = b = 0) the element of the nonsmooth FB function (FischerBurmeisterElement).
  FischerBurmeisterElement(a, b, rho, d_a, d_b, d_rho);
}

double ImplicitFbSystem::ExtraRow(const Vec& x) const {
  const StepEquationLayout& l = layout();
  const double m = l.nc > 0 ? x.segment(l.g(), l.nc).dot(x.segment(l.r(), l.nc)) / l.nc : 0.0;
  return eta_.Value(m, x[l.rho()]);  // (32) / nc
}

void ImplicitFbSystem::AppendExtraRowEntries(std::vector<ScatterPattern::Entry>* e) const {
  const StepEquationLayout& l = layout();
  const int row4 = l.extra_row();
  for (int p = 0; p < l.nc; ++p) {
    e->emplace_back(row4, l.g() + p);
    e->emplace_back(row4, l.r() + p);
  }
  e->emplace_back(row4, l.rho());
}

void ImplicitFbSystem::FillExtraRow(const Vec& x, Cursor* cursor) const {
  const StepEquationLayout& l = layout();
  const double rho = x[l.rho()];
  const double dm = l.nc > 0 ? eta_.DerivativeMean(rho) / l.nc : 0.0;
  for (int p = 0; p < l.nc; ++p) {
    cursor->Add(dm * x[l.r() + p]);  // dF4/dg^ = eta'_m r^ / nc
    cursor->Add(dm * x[l.g() + p]);  // dF4/dr^ = eta'_m g^ / nc
  }
  cursor->Add(eta_.DerivativeRho(rho));
}

}  // namespace cb
