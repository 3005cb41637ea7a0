#include "solvers/interruptible_klu.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <memory>
#include <vector>

#include "core/abandonable_work.h"

namespace cb {

namespace {

// What the worker owns: copies of the matrix's arrays and KLU's settings, the symbolic object
// handed over, and its result.
struct Job {
  std::vector<int> column_pointers, row_indices;
  std::vector<double> values;
  klu_symbolic* symbolic = nullptr;
  klu_common common{};
  klu_numeric* numeric = nullptr;
};

klu_numeric* FactorHere(const SpMat& a, klu_symbolic* symbolic, klu_common* common) {
  return klu_factor(const_cast<int*>(a.outerIndexPtr()), const_cast<int*>(a.innerIndexPtr()),
                    const_cast<double*>(a.valuePtr()), symbolic, common);
}

}  // namespace

klu_numeric* FactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_common* common,
                                 bool* interrupted) {
  *interrupted = false;
  if (a.nonZeros() < kInterruptibleKluMinNonZeros) return FactorHere(a, *symbolic, common);
  auto job = std::make_shared<Job>();
  job->column_pointers.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1);
  job->row_indices.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  job->values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
  job->symbolic = *symbolic;
  job->common = *common;
  const WorkEnd end = RunAbandonably(
      kInterruptibleKluThreadName,
      [job] {
        job->numeric = klu_factor(job->column_pointers.data(), job->row_indices.data(),
                                  job->values.data(), job->symbolic, &job->common);
      },
      [job] {
        // Nobody takes the result: free what the worker was given and made.
        if (job->numeric != nullptr) klu_free_numeric(&job->numeric, &job->common);
        klu_free_symbolic(&job->symbolic, &job->common);
      });
  if (end == WorkEnd::kAbandoned) *symbolic = nullptr;  // the worker frees it
  if (end != WorkEnd::kFinished) {
    *interrupted = true;
    return nullptr;
  }
  *common = job->common;
  return job->numeric;
}

}  // namespace cb

#endif
