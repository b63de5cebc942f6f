// `kappa sweep`: the grid's cost against its resolution on one scene, the
// rays of `kappa bench` timed at every resolution (statistics off, the
// resolutions taking turns) beside their counts (a counting pass on the
// same rays) and the cost models' predictions from those counts.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

int run_sweep(const SweepOptions& options);

}  // namespace kappa
