#include "formulations/siconos/siconos_adapter.h"

#include <LCP_Solvers.h>
#include <LinearComplementarityProblem.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <NumericsVerbose.h>
#include <SolverOptions.h>
#include <lcp_cst.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "formulations/common/captured_stderr.h"
#include "formulations/siconos/siconos.h"

namespace cb {

bool SiconosAvailable() { return true; }
// Siconos's headers carry no version: siconos.cmake names the library file linked and the
// Debian package that holds it (its config-version file says 4.5.0 of the 4.4.0 package).
std::string SiconosVersion() { return CONTACTBENCH_SICONOS_VERSION; }

int SiconosLcpSolverId(SiconosLcpSolver solver) {
  switch (solver) {
    case SiconosLcpSolver::kLemke:
      return SICONOS_LCP_LEMKE;
    case SiconosLcpSolver::kNewtonFb:
      return SICONOS_LCP_NEWTON_FB_FBLSA;
    case SiconosLcpSolver::kNewtonMin:
      return SICONOS_LCP_NEWTON_MIN_FBLSA;
  }
  return SICONOS_LCP_LEMKE;
}

const char* SiconosLcpSolverName(SiconosLcpSolver solver) {
  switch (solver) {
    case SiconosLcpSolver::kLemke:
      return "SICONOS_LCP_LEMKE";
    case SiconosLcpSolver::kNewtonFb:
      return "SICONOS_LCP_NEWTON_FB_FBLSA";
    case SiconosLcpSolver::kNewtonMin:
      return "SICONOS_LCP_NEWTON_MIN_FBLSA";
  }
  return "?";
}

void SiconosLcpOptions::Read(OptionReader* reader) {
  tol = reader->GetReal("tol", tol);
  max_iter = reader->GetInteger("max_iter", max_iter);
  max_size = reader->GetInteger("max_size", max_size);
}

void SiconosLcpOptions::Check(const std::string& name) const {
  if (!(tol > 0.0)) throw std::invalid_argument(name + ": option tol must be > 0");
  if (max_iter < 1) throw std::invalid_argument(name + ": option max_iter must be >= 1");
  if (max_size < 1) throw std::invalid_argument(name + ": option max_size must be >= 1");
}

std::string SiconosLcpOptions::Settings(SiconosLcpSolver solver) const {
  std::ostringstream s;
  s << "solver=" << SiconosLcpSolverName(solver) << " tol=" << tol;
  if (solver != SiconosLcpSolver::kLemke) s << " max_iter=" << max_iter;
  s << " max_size=" << max_size;
  if (solver == SiconosLcpSolver::kLemke) s << " iterations=pivots";
  return s.str();
}

namespace {

// Siconos's SolverOptions (the global one, not cb::SolverOptions of the equation solvers).
struct OptionsDeleter {
  void operator()(::SolverOptions* o) const { solver_options_delete(o); }
};

// Siconos's C structures of the problem, owning their memory for the duration of one run.
class LcpProblem {
 public:
  LcpProblem(const Mat& m, const Vec& q) : q_(q) {
    const int n = static_cast<int>(q.size());
    matrix_ = NM_create(NM_DENSE, n, n);
    std::copy_n(m.data(), static_cast<std::size_t>(n) * n, matrix_->matrix0);
    problem_.size = n;
    problem_.M = matrix_;
    problem_.q = q_.data();
  }
  ~LcpProblem() {
    NM_clear(matrix_);
    std::free(matrix_);
  }
  LcpProblem(const LcpProblem&) = delete;
  LcpProblem& operator=(const LcpProblem&) = delete;
  LinearComplementarityProblem* get() { return &problem_; }

 private:
  Vec q_;
  NumericsMatrix* matrix_ = nullptr;
  LinearComplementarityProblem problem_{};
};

}  // namespace

SiconosLcpOutcome RunSiconosLcp(SiconosLcpSolver solver, const SiconosLcpOptions& options,
                                const Mat& m, const Vec& q, const Vec& z0) {
  numerics_set_verbose(0);
  LcpProblem problem(m, q);
  std::unique_ptr<::SolverOptions, OptionsDeleter> o(
      solver_options_create(SiconosLcpSolverId(solver)));
  if (o == nullptr) throw std::runtime_error("Siconos: solver_options_create failed");
  o->dparam[SICONOS_DPARAM_TOL] = options.tol;
  if (solver != SiconosLcpSolver::kLemke) o->iparam[SICONOS_IPARAM_MAX_ITER] = options.max_iter;
  SiconosLcpOutcome outcome;
  outcome.z = z0;
  outcome.w = Vec::Zero(q.size());
  CapturedStderr library_output;
  outcome.info =
      linearComplementarity_driver(problem.get(), outcome.z.data(), outcome.w.data(), o.get());
  outcome.library_output = library_output.Release();
  outcome.iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  outcome.max_iterations = o->iparam[SICONOS_IPARAM_MAX_ITER];
  outcome.error = o->dparam[SICONOS_DPARAM_RESIDU];
  return outcome;
}

void RecordSiconosOutcome(SiconosLcpSolver solver, const SiconosLcpOutcome& outcome,
                          StepResult* result) {
  result->counts.iterations = outcome.iterations;
  if (solver == SiconosLcpSolver::kLemke) {
    result->counts.residual_evals = 1;
  } else {
    result->counts.residual_evals = outcome.iterations + 1;
    result->counts.jacobian_evals = outcome.iterations;
    result->counts.linear_solves = outcome.iterations;
  }
  // The drivers' codes (LCP_Solvers.h): 0 converged, 1 iteration limit or, for Lemke below
  // its limit, a ray (siconos_adapter.h), otherwise a failure (Lemke: a negative diagonal term;
  // Newton: LAPACK's solve of the direction).
  std::string meaning;
  switch (outcome.info) {
    case 0:
      result->status = Status::kConverged;
      meaning = "converged";
      break;
    case 1:
      if (solver == SiconosLcpSolver::kLemke && outcome.iterations < outcome.max_iterations) {
        result->status = Status::kFailed;
        meaning = "ray termination (no positive entry in the entering column) after " +
                  std::to_string(outcome.iterations) + " pivots, below the limit of " +
                  std::to_string(outcome.max_iterations);
      } else {
        result->status = Status::kLimitReached;
        meaning = "iteration limit reached";
      }
      break;
    default:
      result->status = Status::kFailed;
      meaning =
          solver == SiconosLcpSolver::kLemke ? "pivoting failed" : "no descent direction (LAPACK)";
      break;
  }
  result->details["siconos_info"] = std::to_string(outcome.info) + " " + meaning;
  std::ostringstream error;
  error << outcome.error;
  result->details["siconos_error"] = error.str();
  if (!outcome.library_output.empty()) {
    result->details["siconos_output"] = AbbreviateOutput(outcome.library_output);
  }
  result->message = std::string("Siconos ") + SiconosLcpSolverName(solver) + ": " + meaning +
                    " (error " + error.str() + ")";
}

}  // namespace cb
