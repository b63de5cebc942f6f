// `kappa render`: load, build the accelerator, render, write the EXR atomically.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

class FrameSplit;

/// Throws InputError for bad input; returns the process exit code otherwise.
/// With a `split` of more than one process (kappa-mpi), this process renders
/// the tiles it is given and only the writer writes (frame_split.h).
int run_render(const RenderOptions& options, FrameSplit* split = nullptr);

}  // namespace kappa
