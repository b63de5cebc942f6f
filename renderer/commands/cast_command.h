// `kappa cast`: one of the paper's ray distributions (or the renderer's own)
// cast through the accelerator with statistics on, and its report.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

/// Throws InputError for bad input; returns the process exit code otherwise.
int run_cast(const CastOptions& options);

}  // namespace kappa
