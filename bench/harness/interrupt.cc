#include "harness/interrupt.h"

#include <atomic>
#include <csignal>

namespace cb::harness {

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void OnSignal(int) { g_interrupted.store(true); }

}  // namespace

void InstallInterruptHandlers() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

bool InterruptRequested() { return g_interrupted.load(); }

}  // namespace cb::harness
