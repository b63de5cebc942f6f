// Rendering in-memory scenes for the renderer tests.
#pragma once

#include <cmath>
#include <vector>

#include "accel/factory.h"
#include "renderer/render/film.h"
#include "renderer/render/integrator.h"
#include "renderer/scene/scene.h"

namespace kappa::test {

inline Film render_scene(const Scene& scene, const RenderSettings& settings, const std::string& accel = "naive") {
  AccelOptions options;
  options.filtered = scene.has_cutouts();
  const auto a = make_accelerator(accel, scene.triangles, options);
  Film film(scene.width, scene.height, settings.aov);
  render(scene, *a, settings, film);
  return film;
}

struct ChannelStats {
  double mean = 0;
  double standard_error = 0;  ///< of the mean, treating pixels as independent estimates
};

/// Mean and standard error of channel c over the pixels where `use` is true.
template <typename Predicate>
ChannelStats channel_stats(const Film& film, int c, Predicate use) {
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    if (!use(i)) continue;
    const double v = film.rgb[3 * i + std::size_t(c)];
    sum += v;
    sum2 += v * v;
    ++n;
  }
  ChannelStats s;
  if (n == 0) return s;
  s.mean = sum / double(n);
  const double var = std::max(0.0, sum2 / double(n) - s.mean * s.mean);
  s.standard_error = std::sqrt(var / double(n));
  return s;
}

inline ChannelStats channel_stats(const Film& film, int c) {
  return channel_stats(film, c, [](std::size_t) { return true; });
}

}  // namespace kappa::test
