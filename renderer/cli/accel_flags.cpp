#include "renderer/cli/accel_flags.h"

#include <cstdint>
#include <limits>
#include <stdexcept>

#include "accel/factory.h"
#include "accel/grid_resolution.h"
#include "accel/input_error.h"

namespace kappa {
namespace {

/// --grid-res checked while parsing, with parse_grid_resolution's reason.
CLI::Validator grid_resolution_validator() {
  return CLI::Validator(
      [](std::string& value) {
        try {
          parse_grid_resolution(value);
          return std::string();
        } catch (const InputError& e) {
          std::string reason = e.what();  // drop the "--grid-res: " prefix CLI11 adds again
          return reason.substr(reason.find(": ") + 2);
        }
      },
      "auto|N|NxNxN");
}

}  // namespace

void add_accel_flag(CLI::App& app, std::string& accel, const std::string& help) {
  app.add_option("--accel", accel, help)->check(CLI::IsMember(accelerator_names()))->capture_default_str();
}

void add_accel_list_flag(CLI::App& app, std::vector<std::string>& accels, const std::string& help) {
  app.add_option("--accel", accels, help)
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(CLI::IsMember(accelerator_names()))
      ->capture_default_str();
}

void add_grid_flags(CLI::App& app, AccelOptions& build) {
  app.add_option("--grid-res", build.grid_res, "grid resolution: auto, N (cubic) or NxNxN")
      ->check(grid_resolution_validator())
      ->capture_default_str();
  app.add_option("--grid-density", build.grid_density, "cells per triangle for --grid-res auto (default 32)")
      ->check(CLI::Range(1e-6, 1e6));
  add_grid_max_bytes_flag(app, build);
}

void add_grid_max_bytes_flag(CLI::App& app, AccelOptions& build) {
  app.add_option("--grid-max-bytes", build.grid_max_bytes,
                 "refuse larger grids; with statistics, per-cell counters beyond it are refused and totals kept "
                 "(default: a quarter of RAM)")
      ->check(CLI::Range(std::uint64_t(1), std::numeric_limits<std::uint64_t>::max()));
}

}  // namespace kappa
