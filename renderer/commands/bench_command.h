// `kappa bench`: Mrays/s per accelerator x ray class x thread count, on the
// same rays, in one run, with statistics off.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

/// Throws InputError for bad input; returns the exit code.
int run_bench(const BenchOptions& options);

}  // namespace kappa
