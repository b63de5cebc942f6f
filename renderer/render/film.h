// The image being rendered: RGB radiance and the optional AOVs (geometric,
// cost, variance, samples), one box-filtered value per pixel (no splatting
// across pixels).
#pragma once

#include <cstddef>
#include <vector>

namespace kappa {

/// Which auxiliary outputs to keep, chosen once per frame.
struct AovSelection {
  bool albedo = false;  ///< Kd of the first hit (0 where the camera ray escapes)
  bool normal = false;  ///< geometric normal of the first hit, facing the camera
  bool depth = false;   ///< mean eye distance of the samples that hit (+inf if none did)
  bool cost = false;    ///< grid cells visited and triangle tests made, summed over the pixel's rays (stats on)
  bool variance = false;  ///< the variance of the pixel mean, s²/n, per channel
  bool spp = false;       ///< the samples the pixel took (--adaptive makes them differ)
};

struct Film {
  int width = 0, height = 0;
  std::vector<float> rgb;     ///< 3 per pixel, row 0 at the top
  std::vector<float> albedo;  ///< 3 per pixel, when selected
  std::vector<float> normal;  ///< 3 per pixel, when selected
  std::vector<float> depth;   ///< 1 per pixel, when selected
  std::vector<float> cost_cells;  ///< 1 per pixel, when cost is selected
  std::vector<float> cost_tests;  ///< 1 per pixel, when cost is selected
  std::vector<float> variance;    ///< 3 per pixel, when selected
  std::vector<float> spp;         ///< 1 per pixel, when selected

  Film(int w, int h, const AovSelection& aov)
      : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3) {
    const std::size_t n = std::size_t(w) * std::size_t(h);
    if (aov.albedo) albedo.resize(3 * n);
    if (aov.normal) normal.resize(3 * n);
    if (aov.depth) depth.resize(n);
    if (aov.cost) {
      cost_cells.resize(n);
      cost_tests.resize(n);
    }
    if (aov.variance) variance.resize(3 * n);
    if (aov.spp) spp.resize(n);
  }
  std::size_t pixels() const { return std::size_t(width) * std::size_t(height); }
};

}  // namespace kappa
