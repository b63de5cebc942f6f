// Runs the one subcommand a parsed command line names: what build/kappa's
// and kappa-mpi's mains share.
#pragma once

#include "renderer/cli/command_line.h"

namespace kappa {

/// The command's exit code (its failures are thrown, as each command's are).
int run_command(const Command& command);

}  // namespace kappa
