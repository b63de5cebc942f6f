// `kappa render`: load, build the accelerator, render, write the EXR atomically.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

/// Throws InputError for bad input; returns the process exit code otherwise.
int run_render(const RenderOptions& options);

}  // namespace kappa
