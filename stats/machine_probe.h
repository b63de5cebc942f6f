// The machine's speed at a moment: a fixed workload, timed on one thread.
// A render's report times it just before and just after its frame, and
// `kappa calibrate` when it measures the model's constants, so a reader can
// tell a model error from a slow minute (these machines drift by up to 1.5x
// within a minute): a prediction off by 20 % while the probe ran 20 % slower
// than at calibration is the machine, not the model.
#pragma once

#include <cstdint>

namespace kappa {

struct ProbeResult {
  double seconds = 0;      ///< the median of the timed passes, each the same queries
  std::uint64_t hits = 0;  ///< of a pass's queries, those that hit: the same in every call
};

/// Builds a uniform grid over a fixed soup of triangles and times closest-hit
/// queries of fixed rays through it, on the calling thread: about 2 ms a pass
/// on the project's machines, 5 passes. Its data fit the L2 cache, so it measures the core's speed
/// (clock, a sibling's contention), not the memory's.
ProbeResult machine_probe();

}  // namespace kappa
