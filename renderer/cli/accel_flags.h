// The flags that choose and size an accelerator, added the same way to every
// subcommand that builds one: one --grid-res validator, one --grid-max-bytes.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "accel/factory.h"

namespace kappa {

/// --accel NAME, one of accelerator_names(); with `auto_allowed` (kappa
/// render) also `auto` (renderer/render/accel_choice.h).
void add_accel_flag(CLI::App& app, std::string& accel, const std::string& help, bool auto_allowed = false);
/// --accel A,B,..., each one of accelerator_names().
void add_accel_list_flag(CLI::App& app, std::vector<std::string>& accels, const std::string& help);

/// --grid-res, --grid-density and --grid-max-bytes into `build`; with
/// `model_allowed` (kappa render) --grid-res also takes `model`.
void add_grid_flags(CLI::App& app, AccelOptions& build, bool model_allowed = false);
/// --grid-max-bytes alone, for commands that set the resolution otherwise.
void add_grid_max_bytes_flag(CLI::App& app, AccelOptions& build);

/// A number that is finite and within [lo, hi]: NaN and infinities pass
/// CLI11's own Range (every comparison with NaN is false), so they are
/// refused here, naming the flag.
CLI::Validator finite_number(double lo, double hi);
/// A whole number written with digits only, within [lo, hi]: "-1" would
/// otherwise wrap to 2^64 - 1 in an unsigned option.
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi);

/// --seed: 0 ... 2^53 - 1, the integers a double holds exactly (the EXR and
/// the report store it as a number).
inline constexpr std::uint64_t kMaxSeed = (std::uint64_t(1) << 53) - 1;

}  // namespace kappa
