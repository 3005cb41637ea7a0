// The adapter between the Siconos formulations (siconos_lcp_formulation.cc) and Siconos
// numerics: the dense LCP of siconos_lcp.h as Siconos's LinearComplementarityProblem, its
// SolverOptions, one run of linearComplementarity_driver, and the info code mapped onto
// StepResult. Built only when Siconos is found (siconos.cmake; siconos_stub.cc otherwise).
//
// Siconos options set, and why (also written into settings() and the records):
//   solver id          SICONOS_LCP_LEMKE (lexicographic Lemke, lcp_lexicolemke),
//                      SICONOS_LCP_NEWTON_FB_FBLSA (semismooth Newton on the Fischer-Burmeister
//                      function with a line search on its merit, lcp_newton_FB) or
//                      SICONOS_LCP_NEWTON_MIN_FBLSA (Newton on min(z, w) with the same line
//                      search, lcp_newton_minFB).
//   dparam[TOL] = 1e-12 (option `tol`): Siconos's error, ||z - proj(z - w)|| / (1 + ||q||) of
//                      the scaled LCP, must sit well below the verdict's 1e-8 on the rows of
//                      the step, which it meets only up to the conditioning of the reduction.
//   iparam[MAX_ITER] = 100 for the Newton solvers (option `max_iter`; Siconos's default 1000):
//                      the fixtures and P1 take at most 15 when they converge, and an
//                      iteration is a dense LU of the LCP, which the time limit cannot
//                      interrupt. Lemke's limit is its own default, a multiple of the size,
//                      left as it is: every pivot is needed.
//   verbosity 0        nothing in the library prints.
// Status: the driver's info 0 is Status::kConverged; 1 is the iteration limit
// (Status::kLimitReached), except Lemke's below its pivot limit, a ray termination
// (Status::kFailed): Siconos 4.4's lcp_lexicolemke ends without an info of its own both when z0
// leaves the basis and when the entering column has no positive entry (a ray), and the driver's
// check of the answer turns an end whose error exceeds tol into 1, the code of the limit too.
// An end at z0's exit has only the pivots' rounding in its error, so below the limit it is the
// ray (P1's solves up to n = 400 end at errors of 1e-14 or less); the message gives the error.
// Any other info is a failure (Lemke: a pivoting failure; Newton: LAPACK's solve of the
// direction).
// Counts: `iterations` is iparam[ITER_DONE] (Newton iterations, or Lemke's pivots),
// residual_evals = jacobian_evals = linear_solves = the same count for the Newton solvers (one
// each per iteration) and, for Lemke, residual_evals = 1 (the pivots are the linear algebra).
// The factorisation of K and the nc solves of the reduction are not counted as iterations.
#pragma once

#include <string>

#include "core/types.h"
#include "formulations/common/config.h"
#include "step/formulation.h"

namespace cb {

enum class SiconosLcpSolver { kLemke, kNewtonFb, kNewtonMin };

// Siconos's id and name of each solver.
int SiconosLcpSolverId(SiconosLcpSolver solver);
const char* SiconosLcpSolverName(SiconosLcpSolver solver);

// The options of the Siconos formulations (defaults and reasons at the top of this file).
struct SiconosLcpOptions {
  double tol = 1e-12;
  int max_iter = 100;
  // The largest LCP (number of contact pairs) accepted: M is dense, n^2 doubles, and Lemke's
  // pivots cost O(n^2) each, so 2000 means 32 MB and seconds per solve.
  int max_size = 2000;

  void Read(OptionReader* reader);
  // Throws std::invalid_argument naming the bad option of formulation `name`.
  void Check(const std::string& name) const;
  std::string Settings(SiconosLcpSolver solver) const;
};

// The outcome of one run of the LCP driver.
struct SiconosLcpOutcome {
  int info = -1;           // the driver's return code (0: converged)
  int iterations = 0;      // iparam[SICONOS_IPARAM_ITER_DONE]
  int max_iterations = 0;  // iparam[SICONOS_IPARAM_MAX_ITER], the limit it ran with
  double error = 0.0;      // dparam[SICONOS_DPARAM_RESIDU]
  Vec z, w;
  std::string library_output;  // what Siconos wrote to stderr during the run
};

// Solves w = M z + q, z >= 0, w >= 0, z^T w = 0 from z0 (used by the Newton solvers as their
// start; Lemke pivots from its own basis and ignores it).
SiconosLcpOutcome RunSiconosLcp(SiconosLcpSolver solver, const SiconosLcpOptions& options,
                                const Mat& m, const Vec& q, const Vec& z0);

// status, message, details["siconos_info"], ["siconos_error"] and the counts of `result`.
void RecordSiconosOutcome(SiconosLcpSolver solver, const SiconosLcpOutcome& outcome,
                          StepResult* result);

}  // namespace cb
