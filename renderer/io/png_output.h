// Writes an 8-bit RGB PNG (libpng): the cell map's picture.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace kappa {

/// Writes width x height RGB pixels, three bytes each, row 0 at the top, to
/// `path` directly. Throws OutputError naming `shown` (or `path`) on failure.
void write_png(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb,
               const std::filesystem::path& shown = {});

}  // namespace kappa
