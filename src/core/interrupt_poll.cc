#include "core/interrupt_poll.h"

#include <atomic>

namespace cb {

namespace {
std::atomic<InterruptPoll> g_poll{nullptr};
}  // namespace

void SetInterruptPoll(InterruptPoll poll) { g_poll.store(poll); }

bool InterruptPolled() {
  const InterruptPoll poll = g_poll.load();
  return poll != nullptr && poll();
}

}  // namespace cb
