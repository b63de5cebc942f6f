// Writes a film to OpenEXR (the OpenEXR library): float RGB, the selected AOVs
// as named channels, and the render's metadata as "kappa:*" attributes.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "renderer/render/film.h"

namespace kappa {

using MetadataValue = std::variant<std::string, int, float, double>;
using Metadata = std::vector<std::pair<std::string, MetadataValue>>;

/// Channel names in file order: R, G, B, then albedo.{R,G,B}, normal.{X,Y,Z},
/// depth.Z, cost.cells, cost.tests, variance.{R,G,B} and spp for the AOVs
/// present in the film.
std::vector<std::string> exr_channel_names(const Film& film);

/// Writes width x height pixels of `names.size()` float channels, interleaved
/// in `names`' order, ZIP-compressed, with `metadata` and the time of writing
/// (capDate) as attributes, to `path` directly. Throws OutputError naming
/// `shown` (or `path`) on failure, with the system's reason.
void write_float_exr(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& names,
                     const std::vector<float>& pixels, const Metadata& metadata,
                     const std::filesystem::path& shown = {});

/// Writes `film` to `path` directly (callers wanting atomicity pass the
/// temporary of an AtomicOutput, and its target as `shown`, the name errors
/// give). Throws OutputError on failure, with the system's reason.
void write_exr(const std::filesystem::path& path, const Film& film, const Metadata& metadata,
               const std::filesystem::path& shown = {});

}  // namespace kappa
