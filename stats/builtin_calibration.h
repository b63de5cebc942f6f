// The cost models' constants Kappa uses when no calibration file is found:
// those `kappa calibrate` fitted on the project's machines (2-core AMD EPYC,
// 512 KiB L2 per core, 32 MiB shared L3), so that a choice made from the
// model (--grid-res model, --accel auto) works on a fresh clone without a
// calibration run and depends on nothing measured in the run itself. The
// report names them `cost.calibration: "built-in"`.
#pragma once

#include "calibration.h"

namespace kappa {

/// The built-in calibration: eq 10's, the extended and the coherent model's,
/// the build's, naive's and grid2's constants (no machine probe time).
const Calibration& builtin_calibration();

}  // namespace kappa
