#include "core/slow_work.h"

#include <atomic>

namespace cb {

namespace {
std::atomic<SlowWorkListener> g_listener{nullptr};
}  // namespace

void SetSlowWorkListener(SlowWorkListener listener) { g_listener.store(listener); }

void ReportSlowWork(const SlowWork& work) {
  const SlowWorkListener listener = g_listener.load();
  if (listener != nullptr) listener(work);
}

}  // namespace cb
