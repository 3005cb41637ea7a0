#include "harness/interrupt.h"

#include <atomic>
#include <csignal>
#include <string>

#include "core/interrupt_poll.h"

namespace cb::harness {

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void OnSignal(int) { g_interrupted.store(true); }

}  // namespace

void InstallInterruptHandlers() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  // And for the library's long factorisations (core/interrupt_poll.h).
  SetInterruptPoll(InterruptRequested);
}

InterruptScope::InterruptScope() {
  g_interrupted.store(false);
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &previous_, nullptr);
  g_interrupted.store(false);
}

bool InterruptRequested() { return g_interrupted.load(); }

void AcknowledgeInterrupt() { g_interrupted.store(false); }

void StopIfInterrupted(const char* doing) {
  if (InterruptRequested()) throw Interrupted(std::string("interrupted while ") + doing);
}

}  // namespace cb::harness
