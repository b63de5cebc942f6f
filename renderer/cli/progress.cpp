#include "renderer/cli/progress.h"

#include <chrono>
#include <cstdio>

namespace kappa {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

ProgressBar::ProgressBar(bool enabled) : m_enabled(enabled), m_start(now_seconds()) {
  if (!m_enabled) return;
  m_thread = std::thread([this] {
    std::unique_lock lock(m_mutex);
    while (!m_wake.wait_for(lock, std::chrono::milliseconds(250), [this] { return m_stop; })) draw(false);
  });
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::finish() {
  if (!m_enabled) return;
  {
    std::lock_guard lock(m_mutex);
    m_stop = true;
  }
  m_wake.notify_all();
  if (m_thread.joinable()) m_thread.join();
  draw(true);
  m_enabled = false;
}

void ProgressBar::draw(bool final_line) const {
  const std::size_t total = m_total.load(std::memory_order_relaxed);
  const std::size_t done = m_done.load(std::memory_order_relaxed);
  const double fraction = total > 0 ? double(done) / double(total) : 0.0;
  const double elapsed = now_seconds() - m_start;
  constexpr int kWidth = 40;
  char bar[kWidth + 1];
  const int filled = int(fraction * kWidth);
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '=' : (i == filled ? '>' : ' ');
  bar[kWidth] = '\0';
  if (fraction > 0 && fraction < 1) {
    std::fprintf(stderr, "\r[%s] %5.1f%%  %6.1fs  ETA %6.1fs ", bar, 100 * fraction, elapsed,
                 elapsed * (1 - fraction) / fraction);
  } else {
    std::fprintf(stderr, "\r[%s] %5.1f%%  %6.1fs              ", bar, 100 * fraction, elapsed);
  }
  if (final_line) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace kappa
