#include "solvers/interruptible_cholmod.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <memory>
#include <vector>

#include "core/abandonable_work.h"

namespace cb {

namespace {

// What the worker owns: CHOLMOD's state (declared first: it outlives the factor), copies of the
// matrix's arrays, the factor handed over, and whether it factorised.
struct Job {
  Cholmod cholmod;
  SpMat lower;
  CholmodFactor factor;
  bool factorized = false;
};

// What an analysis's worker owns: its CHOLMOD state, a copy of the pattern (and of the order
// given), and the symbolic factor it makes.
struct AnalysisJob {
  Cholmod cholmod;
  SpMat lower;
  std::vector<int> permutation;
  CholmodFactor factor;
};

CholmodFactor AnalyseHere(Cholmod* cholmod, SpMat* lower, int* permutation) {
  cholmod_sparse view = LowerTriangleView(*lower);
  return permutation != nullptr ? cholmod->AnalyseInOrder(&view, permutation)
                                : cholmod->Analyse(&view);
}

}  // namespace

CholmodFactor AnalyseInterruptibly(Cholmod* cholmod, SpMat* lower, const int* permutation,
                                   bool* interrupted) {
  *interrupted = false;
  if (lower->nonZeros() < kAbandonableMinNonZeros) {
    std::vector<int> order;
    if (permutation != nullptr) order.assign(permutation, permutation + lower->rows());
    return AnalyseHere(cholmod, lower, permutation != nullptr ? order.data() : nullptr);
  }
  auto job = std::make_shared<AnalysisJob>();
  job->lower = *lower;
  if (permutation != nullptr) job->permutation.assign(permutation, permutation + lower->rows());
  const WorkEnd end = RunAbandonably(
      kInterruptibleCholmodAnalysisThreadName,
      [job] {
        job->factor = AnalyseHere(&job->cholmod, &job->lower,
                                  job->permutation.empty() ? nullptr : job->permutation.data());
      },
      [job] { job->factor.reset(); });  // nobody takes it
  if (end != WorkEnd::kFinished) {
    *interrupted = true;
    return {};
  }
  return CholmodFactor(job->factor.release(), cholmod->common());
}

bool FactorizeInterruptibly(Cholmod* cholmod, SpMat* lower, CholmodFactor* factor,
                            bool* interrupted) {
  *interrupted = false;
  if (lower->nonZeros() < kAbandonableMinNonZeros) {
    cholmod_sparse view = LowerTriangleView(*lower);
    return cholmod->Factorize(&view, *factor);
  }
  auto job = std::make_shared<Job>();
  job->lower = *lower;
  job->factor = CholmodFactor(factor->release(), job->cholmod.common());
  const WorkEnd end = RunAbandonably(
      kInterruptibleCholmodThreadName,
      [job] {
        cholmod_sparse view = LowerTriangleView(job->lower);
        job->factorized = job->cholmod.Factorize(&view, job->factor);
      },
      [job] { job->factor.reset(); });  // nobody takes it
  if (end == WorkEnd::kInterruptedBeforeStart) {
    *factor = CholmodFactor(job->factor.release(), cholmod->common());
  }
  if (end != WorkEnd::kFinished) {
    *interrupted = true;
    return false;
  }
  *factor = CholmodFactor(job->factor.release(), cholmod->common());
  return job->factorized;
}

}  // namespace cb

#endif  // CONTACTBENCH_HAVE_SUITESPARSE
