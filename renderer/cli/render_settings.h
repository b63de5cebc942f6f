// A frame's settings from render's options, shared by kappa render and kappa
// converge so that a setting means the same in both.
#pragma once

#include <cstdint>
#include <string>

#include "renderer/cli/options.h"
#include "renderer/render/frame.h"

namespace kappa {

/// --cell-sample: "auto" (0) or a whole number from 1 to 2^20; throws InputError.
std::uint64_t parse_cell_sample(const std::string& text);

/// Every RenderSettings field an option sets (not `passes`, which the command
/// owns); throws InputError for a bad value.
RenderSettings render_settings_of(const RenderOptions& options, const AovSelection& aov);

}  // namespace kappa
