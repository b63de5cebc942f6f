// Reads a reference image for kappa converge: its R, G, B channels and, when
// Kappa rendered it with --aov variance, its variance of the mean.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace kappa {

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<float> rgb;       ///< 3 per pixel, row 0 at the top, as Film
  std::vector<float> variance;  ///< 3 per pixel, or empty without variance.R/G/B
};

/// The size a reference must have: the film it is compared with.
struct FilmSize {
  int width = 0, height = 0;
};

/// Throws InputError naming the file for a file OpenEXR cannot read, one
/// without R, G and B channels, one with a non-finite or negative value, and,
/// from its header before any pixel is read, one whose size is not `film`'s
/// (when given) or whose reading would need more than `max_bytes` (default:
/// the machine's physical memory): a few bytes of header can declare a window
/// of 2^31 x 2^31.
ReferenceImage read_reference(const std::filesystem::path& path, std::optional<FilmSize> film = std::nullopt,
                              std::optional<std::uint64_t> max_bytes = std::nullopt);

}  // namespace kappa
