// The flags that choose and size an accelerator, added the same way to every
// subcommand that builds one: one --grid-res validator, one --grid-max-bytes.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "accel/factory.h"

namespace kappa {

/// --accel NAME, one of accelerator_names().
void add_accel_flag(CLI::App& app, std::string& accel, const std::string& help);
/// --accel A,B,..., each one of accelerator_names().
void add_accel_list_flag(CLI::App& app, std::vector<std::string>& accels, const std::string& help);

/// --grid-res, --grid-density and --grid-max-bytes into `build`.
void add_grid_flags(CLI::App& app, AccelOptions& build);
/// --grid-max-bytes alone, for commands that set the resolution otherwise.
void add_grid_max_bytes_flag(CLI::App& app, AccelOptions& build);

}  // namespace kappa
