// Every setting that changes a rendered image, in one record that both the
// EXR header (as kappa:KEY attributes) and the report ("render.settings")
// serialise, so a flag added here appears in both. Natural types: an int
// below 2^31 is an int, counts and the seed are doubles (exact below 2^53),
// names are strings, switches are booleans.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/cli/options.h"
#include "renderer/render/pass_planner.h"
#include "renderer/scene/scene.h"

namespace kappa {

using SettingValue = std::variant<int, double, std::string, bool>;
using RenderRecord = std::vector<std::pair<std::string, SettingValue>>;

/// The settings of a render of `scene` as `options` asked for it, with a hash
/// of the input files' bytes (`input_hash`, 16 hex digits).
/// `grid_res` is the resolution the grid was built at ("64x32x16", which
/// --grid-res takes back), or "none" for an accelerator without cells.
/// `spp` is the samples per pixel the render took (a budget decides them),
/// and the budgets appear when they were set.
RenderRecord render_record(const RenderOptions& options, const Scene& scene, const std::string& grid_res, int spp,
                           const Budget& budget = {});

/// FNV-1a 64 over the hashes of every input file's bytes as they were read
/// (input_read(), core/input_file.h), in the scene's order, as 16 hex digits.
std::string input_hash(const Scene& scene);
/// 16 lower-case hex digits of h.
std::string hex16(std::uint64_t h);

/// The record as a JSON object of the same keys.
nlohmann::ordered_json to_json(const RenderRecord& record);

}  // namespace kappa
