#include "renderer/render/pass_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kappa {

PassPlanner::PassPlanner(const Budget& budget, Clock clock) : m_budget(budget), m_clock(std::move(clock)) {}

double PassPlanner::elapsed() const { return m_started ? m_clock() - m_start + m_resumed_s : m_resumed_s; }

void PassPlanner::resume(double elapsed_s) {
  m_resumed_s = elapsed_s;
  m_started = true;
  m_start = m_clock();
  m_learning = true;
}

int PassPlanner::stop(const char* reason) {
  m_stop_reason = reason;
  return 0;
}

int PassPlanner::next_pass(const FrameState& state) {
  const double now = m_clock();
  const double cap = double(std::min(m_budget.spp_cap.value_or(kMaxSpp), kMaxSpp));
  if (state.spp >= cap) return stop("spp");
  if (state.active_pixels == 0) return stop("converged");
  const bool relmse = m_budget.target_relmse > 0;
  if (relmse && state.spp >= kFirstRelmseCheckSpp && state.relmse_estimate < m_budget.target_relmse)
    return stop("target-relmse");

  double count = cap - state.spp;
  if (relmse) {
    // A noise target starts with the samples before its first check; then
    // the estimate falls as 1/n: the samples it still needs, at most
    // doubling the total (the estimate is itself noisy).
    if (state.spp < kFirstRelmseCheckSpp) {
      count = std::min(count, double(kFirstRelmseCheckSpp - state.spp));
    } else {
      const double needed = std::ceil(double(state.spp) * state.relmse_estimate / m_budget.target_relmse) - state.spp;
      count = std::min(count, std::clamp(needed, 1.0, double(state.spp)));
    }
  }
  // Time sizes the passes under a time budget, and under --checkpoint-every
  // without a noise target (with one, the estimate alone: the same passes,
  // and so the same retirements, in every run).
  const bool timed = m_budget.time_s > 0 || (m_budget.longest_pass_s > 0 && !relmse);
  const bool learning = !m_started || m_learning;
  if (!m_started) {
    // A first pass without a time to size it: the samples before a noise
    // target's first check.
    if (!timed) count = std::min(count, double(kFirstRelmseCheckSpp));
    m_started = true;
    m_start = now;
  }
  m_learning = false;
  if (timed && learning) {
    count = std::min(count, 1.0);  // one sample, to learn the speed
  } else if (timed) {
    // The last pass's speed (the machine's drifts), per pixel-sample; a
    // pass fills at most 5 % of the budget and the longest pass, and never
    // runs past the budget's end.
    const double per_sample = (now - m_pass_start) / std::max(m_last_pass_work, 1.0);
    const double remaining =
        m_budget.time_s > 0 ? m_budget.time_s - (now - m_start + m_resumed_s) : std::numeric_limits<double>::infinity();
    double slot = m_budget.time_s > 0 ? std::min(kPassShareOfBudget * m_budget.time_s, remaining) : remaining;
    if (m_budget.longest_pass_s > 0) slot = std::min(slot, m_budget.longest_pass_s);
    // A clock too coarse to see the last pass: double the samples. A
    // sample per pixel that takes more than the slot is the smallest pass
    // there is: it runs while it fits in what is left.
    const double one_spp = per_sample * double(state.active_pixels);
    double fits = per_sample > 0 ? std::floor(slot / one_spp) : std::max(1.0, double(state.spp));
    if (!(fits >= 1) && one_spp <= remaining) fits = 1;
    if (!(fits >= 1)) return stop("time-budget");
    count = std::min(count, fits);
  }
  for (int c : m_budget.checkpoints)
    if (c > state.spp) {
      count = std::min(count, double(c - state.spp));
      break;
    }
  m_pass_start = now;
  m_last_pass_work = count * double(state.active_pixels);
  return int(count);
}

}  // namespace kappa
