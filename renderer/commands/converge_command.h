// `kappa converge`: error against render time, one curve per setting, against
// a reference image: the JSON, a table ranking the settings at equal time,
// and a log-log plot.
#pragma once

#include "renderer/cli/options.h"

namespace kappa {

/// Throws InputError for bad input; returns the process exit code otherwise.
int run_converge(const ConvergeOptions& options);

}  // namespace kappa
