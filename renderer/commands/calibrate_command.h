// `kappa calibrate`: measures T0, Ts, Th (eq 10) on this machine.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

/// Writes the calibration file (stats/calibration.h); returns the exit code.
int run_calibrate(const CalibrateOptions& options);

}  // namespace kappa
