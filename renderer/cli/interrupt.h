// Ctrl-C during a budgeted render (docs/command-line.md, exit codes): the first SIGINT
// sets a flag that makes the render abandon its pass, so that the image of
// the completed passes is written and kappa exits 130; a second SIGINT, or
// one outside a budgeted render, keeps the default policy of atomic_file.h
// (the temporaries are removed and the process ends by the signal).
#pragma once

#include <atomic>

namespace kappa {

/// Exit code of a render ended by SIGINT after writing what it had (the
/// shell's 128 + SIGINT).
inline constexpr int kInterruptedExitCode = 130;

class InterruptGuard {
 public:
  /// Catches the next SIGINT, unless SIGINT is ignored (a background job):
  /// then nothing changes. Create it after the outputs' AtomicOutput, whose
  /// handler a second SIGINT then reaches.
  InterruptGuard();
  /// Gives SIGINT back to the handler it had before.
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// Set once a SIGINT arrived; the render polls it.
  const std::atomic<bool>& flag() const;
  bool interrupted() const { return flag().load(); }
};

}  // namespace kappa
