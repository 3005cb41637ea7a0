#include "solvers/interruptible_klu.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <memory>
#include <vector>

#include "core/abandonable_work.h"

namespace cb {

namespace {

// What the worker owns: copies of the matrix's arrays and KLU's settings, the objects handed
// over, and its results.
struct Job {
  std::vector<int> column_pointers, row_indices;
  std::vector<double> values;
  klu_symbolic* symbolic = nullptr;
  klu_common common{};
  klu_numeric* numeric = nullptr;
  int refactored = 0;  // klu_refactor's result
};

klu_numeric* FactorHere(const SpMat& a, klu_symbolic* symbolic, klu_common* common) {
  return klu_factor(const_cast<int*>(a.outerIndexPtr()), const_cast<int*>(a.innerIndexPtr()),
                    const_cast<double*>(a.valuePtr()), symbolic, common);
}

// A job owning copies of a's arrays (`with_values`: its values too) and of KLU's settings.
std::shared_ptr<Job> CopyToJob(const SpMat& a, const klu_common& common, bool with_values) {
  auto job = std::make_shared<Job>();
  job->column_pointers.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1);
  job->row_indices.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  if (with_values) job->values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
  job->common = common;
  return job;
}

// Nobody takes the job's result: free what the worker was given and made.
void FreeJob(Job* job) {
  if (job->numeric != nullptr) klu_free_numeric(&job->numeric, &job->common);
  if (job->symbolic != nullptr) klu_free_symbolic(&job->symbolic, &job->common);
}

}  // namespace

klu_symbolic* AnalyseInterruptibly(const SpMat& a, klu_common* common, bool* interrupted) {
  *interrupted = false;
  const int n = static_cast<int>(a.rows());
  if (a.nonZeros() < kAbandonableMinNonZeros) {
    return klu_analyze(n, const_cast<int*>(a.outerIndexPtr()), const_cast<int*>(a.innerIndexPtr()),
                       common);
  }
  const std::shared_ptr<Job> job = CopyToJob(a, *common, false);
  const WorkEnd end = RunAbandonably(
      kInterruptibleKluAnalysisThreadName,
      [job, n] {
        job->symbolic =
            klu_analyze(n, job->column_pointers.data(), job->row_indices.data(), &job->common);
      },
      [job] { FreeJob(job.get()); });
  if (end != WorkEnd::kFinished) {
    *interrupted = true;
    return nullptr;
  }
  *common = job->common;
  return job->symbolic;
}

bool RefactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_numeric** numeric,
                           klu_common* common, bool* interrupted) {
  *interrupted = false;
  if (a.nonZeros() < kAbandonableMinNonZeros) {
    return klu_refactor(const_cast<int*>(a.outerIndexPtr()), const_cast<int*>(a.innerIndexPtr()),
                        const_cast<double*>(a.valuePtr()), *symbolic, *numeric, common) != 0;
  }
  const std::shared_ptr<Job> job = CopyToJob(a, *common, true);
  job->symbolic = *symbolic;
  job->numeric = *numeric;
  const WorkEnd end = RunAbandonably(
      kInterruptibleKluRefactorThreadName,
      [job] {
        job->refactored =
            klu_refactor(job->column_pointers.data(), job->row_indices.data(), job->values.data(),
                         job->symbolic, job->numeric, &job->common);
      },
      [job] { FreeJob(job.get()); });
  if (end == WorkEnd::kInterruptedBeforeStart) {
    *interrupted = true;
    return false;  // the caller keeps its objects
  }
  *symbolic = nullptr;  // handed back below, or the worker frees them
  *numeric = nullptr;
  if (end == WorkEnd::kAbandoned) {
    *interrupted = true;
    return false;
  }
  *symbolic = job->symbolic;
  *numeric = job->numeric;
  job->symbolic = nullptr;
  job->numeric = nullptr;
  *common = job->common;
  return job->refactored != 0;
}

klu_numeric* FactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_common* common,
                                 bool* interrupted) {
  *interrupted = false;
  if (a.nonZeros() < kAbandonableMinNonZeros) return FactorHere(a, *symbolic, common);
  const std::shared_ptr<Job> job = CopyToJob(a, *common, true);
  job->symbolic = *symbolic;
  const WorkEnd end = RunAbandonably(
      kInterruptibleKluThreadName,
      [job] {
        job->numeric = klu_factor(job->column_pointers.data(), job->row_indices.data(),
                                  job->values.data(), job->symbolic, &job->common);
      },
      [job] { FreeJob(job.get()); });
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
