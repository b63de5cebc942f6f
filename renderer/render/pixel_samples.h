// What one pixel keeps across the passes of a progressive render: the sum of
// its finite samples in sample order (so the image after any passes is
// bitwise the image of one pass of the same total), Welford's running mean
// and sum of squared deviations (the variance of the pixel mean, for the
// error estimate and the adaptive stop), and its counts.
#pragma once

#include <cstdint>

#include "core/vec3.h"

namespace kappa {

/// The error estimate's guard against dark pixels: a relative error over
/// x̄² + 0.01 (as pbrt-v4 and Mitsuba measure relMSE), not over x̄² alone.
inline constexpr double kRelmseEpsilon = 0.01;

struct PixelSamples {
  double sum[3] = {0, 0, 0};
  double mean[3] = {0, 0, 0};
  double m2[3] = {0, 0, 0};
  std::uint32_t finite = 0;  ///< samples averaged in
  std::uint32_t drawn = 0;   ///< samples taken, finite or not: the next sample's index

  /// Adds one finite sample (the caller drops non-finite ones).
  void add(const Vec3f& L) {
    const double x[3] = {L.x, L.y, L.z};
    const double inv = 1.0 / double(++finite);
    for (int c = 0; c < 3; ++c) {
      sum[c] += x[c];
      const double d = x[c] - mean[c];
      mean[c] += d * inv;
      m2[c] += d * (x[c] - mean[c]);
    }
  }
  /// The pixel's value: its finite samples' mean (0 without one).
  double value(int c) const { return finite > 0 ? sum[c] / double(finite) : 0.0; }
  /// s²/n, the variance of the pixel mean (0 below two samples: unknown).
  double variance_of_mean(int c) const {
    return finite > 1 ? m2[c] / (double(finite - 1) * double(finite)) : 0.0;
  }
  /// The pixel's own relMSE estimate: (s²/n)/(x̄² + 0.01), averaged over R, G, B.
  double relmse_estimate() const {
    double e = 0;
    for (int c = 0; c < 3; ++c) e += variance_of_mean(c) / (mean[c] * mean[c] + kRelmseEpsilon);
    return e / 3;
  }
};

}  // namespace kappa
