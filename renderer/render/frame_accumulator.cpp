#include "renderer/render/frame_accumulator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace kappa {

FrameAccumulator::FrameAccumulator(std::size_t pixels, const AovSelection& aov)
    : m_samples(pixels), m_active_count(pixels) {
  if (aov.albedo || aov.normal || aov.depth || aov.cost) m_aovs.resize(pixels);
}

std::size_t FrameAccumulator::retire_converged(double target, std::uint32_t min_spp) {
  if (m_active.empty()) m_active.assign(m_samples.size(), 1);
  for (std::size_t i = 0; i < m_samples.size(); ++i)
    if (m_active[i] && m_samples[i].drawn >= min_spp && m_samples[i].relmse_estimate() < target) {
      m_active[i] = 0;
      --m_active_count;
    }
  return m_active_count;
}

double FrameAccumulator::relmse_estimate() const {
  double sum = 0;
  for (const PixelSamples& p : m_samples) sum += p.relmse_estimate();
  return m_samples.empty() ? 0.0 : sum / double(m_samples.size());
}

SppSpread FrameAccumulator::spp_spread() const {
  SppSpread s;
  if (m_samples.empty()) return s;
  s.min = s.max = m_samples[0].drawn;
  double sum = 0;
  for (const PixelSamples& p : m_samples) {
    s.min = std::min(s.min, p.drawn);
    s.max = std::max(s.max, p.drawn);
    sum += p.drawn;
  }
  s.mean = sum / double(m_samples.size());
  return s;
}

void FrameAccumulator::resolve(Film& film) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_samples.size(), 4096), [&](const auto& range) {
    for (std::size_t pixel = range.begin(); pixel != range.end(); ++pixel) resolve_pixel(film, pixel);
  });
}

void FrameAccumulator::resolve_pixel(Film& film, std::size_t pixel) const {
  const PixelSamples& p = m_samples[pixel];
  for (int c = 0; c < 3; ++c) film.rgb[3 * pixel + std::size_t(c)] = float(p.value(c));
  if (!film.variance.empty())
    for (int c = 0; c < 3; ++c) film.variance[3 * pixel + std::size_t(c)] = float(p.variance_of_mean(c));
  if (!film.spp.empty()) film.spp[pixel] = float(p.drawn);
  if (m_aovs.empty()) return;
  const PixelAovSums& a = m_aovs[pixel];
  const double inv_drawn = p.drawn > 0 ? 1.0 / double(p.drawn) : 0.0;
  if (!film.albedo.empty())
    for (int c = 0; c < 3; ++c) film.albedo[3 * pixel + std::size_t(c)] = float(a.albedo[c] * inv_drawn);
  if (!film.normal.empty()) {
    const double len = std::sqrt(a.normal[0] * a.normal[0] + a.normal[1] * a.normal[1] + a.normal[2] * a.normal[2]);
    for (int c = 0; c < 3; ++c) film.normal[3 * pixel + std::size_t(c)] = len > 0 ? float(a.normal[c] / len) : 0.0f;
  }
  if (!film.depth.empty()) film.depth[pixel] = a.depth_hits > 0 ? float(a.depth / a.depth_hits) : INFINITY;
  if (!film.cost_cells.empty()) {
    film.cost_cells[pixel] = float(a.cells);
    film.cost_tests[pixel] = float(a.tests);
  }
}

}  // namespace kappa
