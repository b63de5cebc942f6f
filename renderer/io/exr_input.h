// Reads a reference image for kappa converge: its R, G, B channels and, when
// Kappa rendered it with --aov variance, its variance of the mean.
#pragma once

#include <filesystem>
#include <vector>

namespace kappa {

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<float> rgb;       ///< 3 per pixel, row 0 at the top, as Film
  std::vector<float> variance;  ///< 3 per pixel, or empty without variance.R/G/B
};

/// Throws InputError naming the file for a file OpenImageIO cannot read, one
/// without R, G and B channels, or one with a non-finite or negative value.
ReferenceImage read_reference(const std::filesystem::path& path);

}  // namespace kappa
