// A C++ plug-in (docs/your-own-method.md): formulation `min-newton`, a semismooth Newton on
// min(g^, -r^) for the step system of formulations/external/step_system.h, with a backtracking
// line search on 1/2 ||G||^2, compiled on its own against the installed package and loaded by
// `contactbench run|compare --plugin libmin_newton.so`.
#include <Eigen/SparseLU>
#include <algorithm>
#include <vector>

#include "formulations/external/callback_formulation.h"
#include "formulations/external/plugin.h"

namespace {

// G(x) = (F(x), min(g^_p, -r^_p) per pair); false where not finite.
bool Residual(cb::ExternalStepSystem& s, const cb::Vec& x, cb::Vec* g) {
  cb::Vec f;
  const bool finite = s.Residual(x, &f);
  g->resize(s.size());
  g->head(s.rows()) = f;
  for (std::size_t i = 0; i < s.pair_gaps().size(); ++i) {
    (*g)[s.rows() + static_cast<int>(i)] = std::min(x[s.pair_gaps()[i]], -x[s.pair_reactions()[i]]);
  }
  return finite && g->allFinite();
}

// An element of G's generalised Jacobian: F's rows and, per pair, the row of the smaller side.
cb::SpMat Jacobian(cb::ExternalStepSystem& s, const cb::Vec& x) {
  const cb::SpMat f = s.Jacobian(x);
  std::vector<cb::Triplet> entries;
  for (int j = 0; j < f.outerSize(); ++j) {
    for (cb::SpMat::InnerIterator it(f, j); it; ++it) entries.emplace_back(it.row(), j, it.value());
  }
  for (std::size_t i = 0; i < s.pair_gaps().size(); ++i) {
    const int a = s.pair_gaps()[i], b = s.pair_reactions()[i];
    const bool gap = x[a] <= -x[b];
    entries.emplace_back(s.rows() + static_cast<int>(i), gap ? a : b, gap ? 1.0 : -1.0);
  }
  cb::SpMat j(s.size(), s.size());
  j.setFromTriplets(entries.begin(), entries.end());
  return j;
}

cb::ExternalAnswer MinNewton(cb::ExternalStepSystem& s, const cb::ExternalCall& call) {
  cb::ExternalAnswer out{call.x0, cb::Status::kFailed, "iteration limit", {}, {}};
  cb::Vec g, trial;
  bool finite = Residual(s, out.x, &g);
  for (int it = 0; finite && it < 50; ++it) {
    out.counts.residual_evals++;
    if (g.lpNorm<Eigen::Infinity>() <= 1e-10) {
      out.status = cb::Status::kConverged;
      out.message = "||G||_inf <= 1e-10";
      return out;
    }
    Eigen::SparseLU<cb::SpMat> lu(Jacobian(s, out.x));
    out.counts.jacobian_evals++;
    out.counts.linear_solves++;
    if (lu.info() != Eigen::Success)
      return {out.x, cb::Status::kFailed, "singular", out.counts, {}};
    const cb::Vec dx = lu.solve(-g);
    double t = 1.0;  // Armijo on 1/2 ||G||^2 (the Newton direction's slope is -||G||^2)
    while (!(Residual(s, out.x + t * dx, &trial) &&
             trial.squaredNorm() <= (1.0 - 1e-4 * t) * g.squaredNorm()) &&
           t > 1e-10) {
      t *= 0.5;
    }
    out.x += t * dx;
    finite = Residual(s, out.x, &g);
    out.counts.iterations++;
  }
  return out;
}

}  // namespace

// The entry point (formulations/external/plugin.h).
extern "C" void contactbench_register_formulations(const cb::PluginHost& host) {
  host.register_formulation(cb::ExternalFormulationInfo(
      "min-newton", "semismooth Newton on min(g, -r), a C++ plug-in (examples/plugin)",
      "eigen-sparselu", MinNewton));
}
