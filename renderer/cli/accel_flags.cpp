#include "renderer/cli/accel_flags.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "accel/factory.h"
#include "accel/grid_resolution.h"
#include "core/input_error.h"

namespace kappa {
namespace {

/// --grid-res checked while parsing, with parse_grid_resolution's reason.
CLI::Validator grid_resolution_validator(bool model_allowed) {
  return CLI::Validator(
      [model_allowed](std::string& value) {
        if (model_allowed && value == "model") return std::string();
        try {
          parse_grid_resolution(value);
          return std::string();
        } catch (const InputError& e) {
          std::string reason = e.what();  // drop the "--grid-res: " prefix CLI11 adds again
          return reason.substr(reason.find(": ") + 2);
        }
      },
      model_allowed ? "model|auto|N|NxNxN" : "auto|N|NxNxN");
}

}  // namespace

CLI::Validator finite_number(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& value) {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size()) return "'" + value + "' is not a number";
        if (!std::isfinite(v) || errno == ERANGE) return "'" + value + "' is not a finite number";
        if (v < lo || v > hi) {
          std::ostringstream s;
          s << "'" << value << "' is outside [" << lo << ", " << hi << "]";
          return s.str();
        }
        return std::string();
      },
      "finite number");
}

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& value) {
        std::uint64_t v = 0;
        const char* first = value.data();
        const char* last = first + value.size();
        const auto [end, ec] = std::from_chars(first, last, v);
        if (value.empty() || end != last || ec != std::errc() || v < lo || v > hi)
          return "'" + value + "' is not a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
        return std::string();
      },
      "whole number");
}

void add_accel_flag(CLI::App& app, std::string& accel, const std::string& help, bool auto_allowed) {
  std::vector<std::string> names = accelerator_names();
  if (auto_allowed) names.insert(names.begin(), "auto");
  app.add_option("--accel", accel, help)->check(CLI::IsMember(names))->capture_default_str();
}

void add_accel_list_flag(CLI::App& app, std::vector<std::string>& accels, const std::string& help) {
  app.add_option("--accel", accels, help)
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(CLI::IsMember(accelerator_names()))
      ->capture_default_str();
}

void add_grid_flags(CLI::App& app, AccelOptions& build, bool model_allowed) {
  app.add_option("--grid-res", build.grid_res,
                 model_allowed ? "grid resolution: model (the cost model's choice from a pilot of the frame), auto, "
                                 "N (cubic) or NxNxN"
                               : "grid resolution: auto, N (cubic) or NxNxN")
      ->check(grid_resolution_validator(model_allowed))
      ->capture_default_str();
  app.add_option("--grid-density", build.grid_density, "cells per triangle for --grid-res auto (default 32)")
      ->check(finite_number(1e-6, 1e6));
  app.add_option("--grid2-top-density", build.grid2_top_density, "grid2's top cells per triangle (default 1/2)")
      ->check(finite_number(1e-6, 1e6));
  app.add_option("--grid2-leaf-density", build.grid2_leaf_density,
                 "grid2's sub-grid cells per triangle of the cell it refines (default 2)")
      ->check(finite_number(1e-6, 1e6));
  add_grid_max_bytes_flag(app, build);
}

void add_grid_max_bytes_flag(CLI::App& app, AccelOptions& build) {
  app.add_option("--grid-max-bytes", build.grid_max_bytes,
                 "refuse larger grids; with statistics, per-cell counters beyond it are refused and totals kept "
                 "(default: a quarter of RAM)")
      ->check(whole_number(1, std::numeric_limits<std::uint64_t>::max()));
}

}  // namespace kappa
