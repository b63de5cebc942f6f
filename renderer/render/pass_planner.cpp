#include "renderer/render/pass_planner.h"

#include <algorithm>
#include <cmath>

namespace kappa {

PassPlanner::PassPlanner(const Budget& budget, Clock clock) : m_budget(budget), m_clock(std::move(clock)) {}

double PassPlanner::elapsed() const { return m_started ? m_clock() - m_start : 0.0; }

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
  if (!m_started) {
    // A time budget starts with one sample, to learn the speed; a noise
    // target alone starts with the samples before its first check.
    m_started = true;
    m_start = now;
    count = std::min(count, m_budget.time_s > 0 ? 1.0 : double(kFirstRelmseCheckSpp));
  } else {
    if (relmse) {
      if (state.spp < kFirstRelmseCheckSpp) {
        count = std::min(count, double(kFirstRelmseCheckSpp - state.spp));
      } else {
        // The estimate falls as 1/n: the samples it still needs, at most
        // doubling the total (the estimate is itself noisy).
        const double needed = std::ceil(double(state.spp) * state.relmse_estimate / m_budget.target_relmse) - state.spp;
        count = std::min(count, std::clamp(needed, 1.0, double(state.spp)));
      }
    }
    if (m_budget.time_s > 0) {
      // The last pass's speed (the machine's drifts), per pixel-sample; a
      // pass fills at most 5 % of the budget, and never runs past its end.
      const double per_sample = (now - m_pass_start) / std::max(m_last_pass_work, 1.0);
      const double remaining = m_budget.time_s - (now - m_start);
      const double slot = std::min(kPassShareOfBudget * m_budget.time_s, remaining);
      // A clock too coarse to see the last pass: double the samples. A
      // sample per pixel that takes more than 5 % is the smallest pass
      // there is: it runs while it fits in what is left.
      const double one_spp = per_sample * double(state.active_pixels);
      double fits = per_sample > 0 ? std::floor(slot / one_spp) : std::max(1.0, double(state.spp));
      if (!(fits >= 1) && one_spp <= remaining) fits = 1;
      if (!(fits >= 1)) return stop("time-budget");
      count = std::min(count, fits);
    }
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
