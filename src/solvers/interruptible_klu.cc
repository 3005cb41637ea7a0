#include "solvers/interruptible_klu.h"

#ifdef CONTACTBENCH_HAVE_SUITESPARSE

#include <pthread.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "core/interrupt_poll.h"

namespace cb {

namespace {

// What the worker owns: the caller shares it until it abandons it.
struct Job {
  std::vector<int> column_pointers, row_indices;
  std::vector<double> values;
  klu_symbolic* symbolic = nullptr;
  klu_common common{};
  klu_numeric* numeric = nullptr;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  bool abandoned = false;
};

void Work(const std::shared_ptr<Job>& job) {
  // Named, so that it can be told apart (/proc/PID/task/*/comm; the interrupt test waits for it).
  pthread_setname_np(pthread_self(), kInterruptibleKluThreadName);
  klu_numeric* numeric = klu_factor(job->column_pointers.data(), job->row_indices.data(),
                                    job->values.data(), job->symbolic, &job->common);
  const std::lock_guard<std::mutex> lock(job->mutex);
  job->numeric = numeric;
  job->done = true;
  if (job->abandoned) {
    // Nobody takes the result: free what the worker was given and made.
    if (job->numeric != nullptr) klu_free_numeric(&job->numeric, &job->common);
    klu_free_symbolic(&job->symbolic, &job->common);
  }
  job->finished.notify_all();
}

klu_numeric* FactorHere(const SpMat& a, klu_symbolic* symbolic, klu_common* common) {
  return klu_factor(const_cast<int*>(a.outerIndexPtr()), const_cast<int*>(a.innerIndexPtr()),
                    const_cast<double*>(a.valuePtr()), symbolic, common);
}

}  // namespace

klu_numeric* FactorInterruptibly(const SpMat& a, klu_symbolic** symbolic, klu_common* common,
                                 bool* interrupted) {
  *interrupted = false;
  if (a.nonZeros() < kInterruptibleKluMinNonZeros) return FactorHere(a, *symbolic, common);
  if (InterruptPolled()) {
    *interrupted = true;
    return nullptr;
  }
  auto job = std::make_shared<Job>();
  job->column_pointers.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1);
  job->row_indices.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  job->values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
  job->symbolic = *symbolic;
  job->common = *common;
  try {
    std::thread([job] { Work(job); }).detach();
  } catch (const std::system_error&) {
    return FactorHere(a, *symbolic, common);  // no thread to be had: uninterruptible, as before
  }
  std::unique_lock<std::mutex> lock(job->mutex);
  while (!job->finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return job->done; })) {
    if (InterruptPolled()) {
      job->abandoned = true;  // the worker frees the symbolic object and its result
      *symbolic = nullptr;
      *interrupted = true;
      return nullptr;
    }
  }
  *common = job->common;
  return job->numeric;
}

}  // namespace cb

#endif
