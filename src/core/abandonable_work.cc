#include "core/abandonable_work.h"

#include <pthread.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>

#include "core/interrupt_poll.h"

namespace cb {

namespace {

// Shared by the caller and the worker until the caller abandons it; then the worker's alone.
struct Shared {
  std::function<void()> work, release;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  bool abandoned = false;
};

std::atomic<WorkerStartHook> g_start_hook{nullptr};
std::atomic<int> g_abandoned_running{0};

void Work(const std::shared_ptr<Shared>& shared, const char* thread_name) {
  pthread_setname_np(pthread_self(), thread_name);
  if (const WorkerStartHook hook = g_start_hook.load()) hook(thread_name);
  shared->work();
  const std::lock_guard<std::mutex> lock(shared->mutex);
  shared->done = true;
  if (shared->abandoned) {
    shared->release();  // nobody takes the result
    --g_abandoned_running;
  }
  shared->finished.notify_all();
}

}  // namespace

void SetWorkerStartHookForTesting(WorkerStartHook hook) { g_start_hook.store(hook); }

bool AbandonedWorkRunning() { return g_abandoned_running.load() > 0; }

WorkEnd RunAbandonably(const char* thread_name, std::function<void()> work,
                       std::function<void()> release) {
  if (InterruptPolled()) return WorkEnd::kInterruptedBeforeStart;
  auto shared = std::make_shared<Shared>();
  shared->work = std::move(work);
  shared->release = std::move(release);
  try {
    std::thread([shared, thread_name] { Work(shared, thread_name); }).detach();
  } catch (const std::system_error&) {
    shared->work();  // no thread to be had: uninterruptible, on this thread
    return WorkEnd::kFinished;
  }
  std::unique_lock<std::mutex> lock(shared->mutex);
  while (!shared->finished.wait_for(lock, std::chrono::milliseconds(100),
                                    [&] { return shared->done; })) {
    if (InterruptPolled()) {
      shared->abandoned = true;  // under the lock: the worker counts it down when it ends
      ++g_abandoned_running;
      return WorkEnd::kAbandoned;
    }
  }
  return WorkEnd::kFinished;
}

}  // namespace cb
