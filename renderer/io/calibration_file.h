// The calibration a command predicts with, read as every command reads it.
#pragma once

#include <filesystem>
#include <optional>

#include "stats/calibration.h"

namespace kappa {

/// The calibration at `path`, or nullopt where there is none: one left beside
/// the binary by an older Kappa (`named` false) is set aside with a warning
/// (a rebuild must not stop every command); one named with --calibration
/// (`named`) that is missing or of another format is refused (InputError).
/// The caller falls back to the built-in constants on nullopt.
std::optional<Calibration> read_calibration_file(const std::filesystem::path& path, bool named);

}  // namespace kappa
