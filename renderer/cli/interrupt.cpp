#include "renderer/cli/interrupt.h"

#include <signal.h>

namespace kappa {
namespace {

// Only what a signal handler may touch: a lock-free flag and the previous
// action, which sigaction (async-signal-safe) restores.
std::atomic<bool> g_interrupted{false};
struct sigaction g_previous {};
bool g_installed = false;
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void note_interrupt(int) {
  g_interrupted.store(true);
  ::sigaction(SIGINT, &g_previous, nullptr);  // the next SIGINT: the default policy
}

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupted.store(false);
  struct sigaction old {};
  ::sigaction(SIGINT, nullptr, &old);
  if (old.sa_handler == SIG_IGN) return;
  g_previous = old;
  struct sigaction sa {};
  sa.sa_handler = note_interrupt;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  g_installed = true;
}

InterruptGuard::~InterruptGuard() {
  if (!g_installed) return;
  // After a SIGINT the handler already gave SIGINT back; restoring again is harmless.
  ::sigaction(SIGINT, &g_previous, nullptr);
  g_installed = false;
}

const std::atomic<bool>& InterruptGuard::flag() const { return g_interrupted; }

}  // namespace kappa
