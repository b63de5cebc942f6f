#include "renderer/cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace kappa {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

constexpr auto kRedraw = std::chrono::milliseconds(250);

}  // namespace

bool progress_wanted(bool quiet) { return !quiet && ::isatty(STDERR_FILENO); }

ProgressBar::ProgressBar(bool enabled) : m_enabled(enabled) {
  if (!m_enabled) return;
  m_task.set_observer([this](const TaskProgress::Snapshot& state) {
    std::lock_guard lock(m_mutex);
    draw(state, false);
  });
  m_thread = std::thread([this] {
    std::unique_lock lock(m_mutex);
    while (!m_wake.wait_for(lock, kRedraw, [this] { return m_stop; })) {
      const TaskProgress::Snapshot state = m_task.snapshot();
      if (state.generation != 0) draw(state, false);  // 0: no phase yet
    }
  });
}

void ProgressBar::stop() {
  {
    std::lock_guard lock(m_mutex);
    m_stop = true;
  }
  m_wake.notify_all();
  if (m_thread.joinable()) m_thread.join();
}

ProgressBar::~ProgressBar() {
  if (!m_enabled) return;
  stop();
  if (m_drawn_generation != ~std::uint64_t(0)) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

void ProgressBar::finish() {
  if (!m_enabled) return;
  stop();
  draw(m_task.snapshot(), true);
  m_enabled = false;
}

void ProgressBar::draw(const TaskProgress::Snapshot& state, bool final_line) {
  const double now = now_seconds();
  if (state.generation != m_drawn_generation) {
    m_drawn_generation = state.generation;
    m_phase_start = now;
  }
  const double elapsed = now - m_phase_start;
  // A file name with a control character (a newline, an escape) must not
  // break the line or reach the terminal as a command.
  std::string line = "\r";
  for (char c : state.phase) line += (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) ? '?' : c;
  char text[128];
  if (state.total > 0) {
    const double fraction = std::min(1.0, double(state.done) / double(state.total));
    constexpr int kWidth = 40;
    std::string bar(kWidth, ' ');
    const int filled = int(fraction * kWidth);
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '=' : (i == filled ? '>' : ' ');
    if (fraction > 0 && fraction < 1)
      std::snprintf(text, sizeof text, " [%s] %5.1f%%  %6.1fs  ETA %6.1fs", bar.c_str(), 100 * fraction, elapsed,
                    elapsed * (1 - fraction) / fraction);
    else
      std::snprintf(text, sizeof text, " [%s] %5.1f%%  %6.1fs", bar.c_str(), 100 * fraction, elapsed);
  } else {
    std::snprintf(text, sizeof text, " ...  %6.1fs", elapsed);
  }
  line += text;
  line += "\033[K";  // erase what a longer earlier phase left
  if (final_line) line += '\n';
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace kappa
