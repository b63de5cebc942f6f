// Whether this executable has the statistics' counting path. kappa has it;
// kappa-nostats, the baseline tools/stats_overhead.sh times `--stats off`
// against, is linked from the same objects but for integrator.cpp, compiled
// without it (renderer/CMakeLists.txt), so none of the render's counting
// frames (render_counting*) is in it. (Cast, sweep and the pilot count cells
// with the stats module's own walks, which both have.)
#pragma once

namespace kappa {

/// Defined in integrator.cpp, whose frame dispatch is the one place that differs.
bool statistics_built();

}  // namespace kappa
