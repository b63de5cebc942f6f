// The budgets of a progressive render: how many samples per pixel the next
// pass takes, and when to stop, from a time budget (--time-budget), a noise
// target (--target-relmse), a sample cap (--spp) and, under --adaptive, the
// pixels still sampling. The clock is injected: tests advance a fake one.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kappa {

struct Budget {
  std::optional<int> spp_cap;  ///< --spp, when given: the passes' total never exceeds it
  /// Totals a pass must end at, ascending (kappa converge measures the film
  /// at each); the cap still ends the render.
  std::vector<int> checkpoints;
  double time_s = 0;           ///< --time-budget (0: none)
  double target_relmse = 0;    ///< --target-relmse (0: none)
  bool adaptive = false;       ///< pixels below the target stop sampling (needs a target)
  int adaptive_min_spp = 16;
  /// --checkpoint-every: a render saves its completed passes this often, so
  /// without a noise target (whose passes its estimate sizes, the same in
  /// every run) a pass lasts about this long at most (0: no limit).
  double longest_pass_s = 0;

  bool any() const { return time_s > 0 || target_relmse > 0; }
};

/// Where the frame stands after its passes so far.
struct FrameState {
  int spp = 0;                    ///< samples per still-sampling pixel so far
  std::size_t active_pixels = 0;  ///< pixels still sampling
  double relmse_estimate = 0;     ///< the frame's estimate (FrameAccumulator::relmse_estimate)
};

/// A pass is at most this share of the time budget.
inline constexpr double kPassShareOfBudget = 0.05;
/// The estimate is checked from this many samples per pixel on.
inline constexpr int kFirstRelmseCheckSpp = 8;
/// No pixel takes more samples than this (its counts are 32-bit).
inline constexpr int kMaxSpp = 1 << 30;
/// The smallest --target-relmse taken (render_command.cpp says why).
inline constexpr double kMinTargetRelmse = 1e-12;

class PassPlanner {
 public:
  using Clock = std::function<double()>;  ///< seconds, from any origin
  PassPlanner(const Budget& budget, Clock clock);

  /// The samples per pixel of the next pass, or 0 to stop (stop_reason()
  /// says why). Called before every pass; the time budget counts from the
  /// first call.
  int next_pass(const FrameState& state);

  const Budget& budget() const { return m_budget; }
  /// "spp", "time-budget", "target-relmse", "converged" (every pixel
  /// retired), or "" while running.
  const std::string& stop_reason() const { return m_stop_reason; }
  /// Seconds since the first pass began, with a resumed render's time
  /// spent before its checkpoint (resume).
  double elapsed() const;
  /// A render resumed from a checkpoint: `elapsed_s` of its time budget
  /// already spent. Its next pass is sized as a first one where time sizes
  /// passes (one sample: the speed is learnt again), as in a run not
  /// stopped where the estimate alone does.
  void resume(double elapsed_s);

 private:
  int stop(const char* reason);

  Budget m_budget;
  Clock m_clock;
  double m_start = 0;
  double m_pass_start = 0;
  double m_last_pass_work = 0;  ///< pixel-samples of the last pass
  bool m_started = false;
  bool m_learning = false;      ///< a resumed render's first pass: the speed is unknown
  double m_resumed_s = 0;       ///< the time budget spent before a resume
  std::string m_stop_reason;
};

}  // namespace kappa
