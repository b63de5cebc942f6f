#include "renderer/render/frame_accumulator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/byte_size.h"
#include "core/check.h"
#include "core/input_error.h"
#include "core/parallel.h"
#include "core/physical_memory.h"
#include "renderer/render/tile_schedule.h"

namespace kappa {

std::uint64_t frame_bytes(std::size_t pixels, const AovSelection& aov) {
  const std::uint64_t channels = 3 + (aov.albedo ? 3 : 0) + (aov.normal ? 3 : 0) + (aov.depth ? 1 : 0) +
                                 (aov.cost ? 2 : 0) + (aov.variance ? 3 : 0) + (aov.spp ? 1 : 0);
  const bool aov_sums = aov.albedo || aov.normal || aov.depth || aov.cost;
  const std::uint64_t per_pixel = sizeof(PixelSamples) + (aov_sums ? sizeof(PixelAovSums) : 0) +
                                  1 /* adaptive's active flag */ + 2 * channels * sizeof(float);
  return std::uint64_t(pixels) * per_pixel;
}

void refuse_frame_over_memory(int width, int height, const AovSelection& aov) {
  const std::uint64_t need = frame_bytes(std::size_t(width) * std::size_t(height), aov);
  const std::uint64_t have = physical_memory_bytes();
  if (need > have)
    throw InputError("film " + std::to_string(width) + "x" + std::to_string(height) + ": its buffers need " +
                     byte_size(need) + ", more than this machine's " + byte_size(have) +
                     " of memory (a smaller film, or fewer AOVs)");
}

FrameAccumulator::FrameAccumulator(std::size_t pixels, const AovSelection& aov)
    : m_samples(pixels), m_active_count(pixels) {
  if (aov.albedo || aov.normal || aov.depth || aov.cost) m_aovs.resize(pixels);
}

namespace {

/// Runs f(first, last) over fixed blocks of pixels in parallel and returns
/// their results in block order: a sum over them is the same for any thread
/// count.
template <typename T, typename F>
std::vector<T> per_block(std::size_t pixels, F&& f) {
  const std::size_t blocks = (pixels + kBlock - 1) / kBlock;
  std::vector<T> out(blocks);
  kappa::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    out[b] = f(b * kBlock, std::min(pixels, (b + 1) * kBlock));
  });
  return out;
}

}  // namespace

std::size_t FrameAccumulator::retire_converged(double target, std::uint32_t min_spp) {
  if (m_active.empty()) m_active.assign(m_samples.size(), 1);
  // A pixel with fewer than two finite samples has no estimate: it samples on.
  const auto retired = per_block<std::size_t>(m_samples.size(), [&](std::size_t first, std::size_t last) {
    std::size_t n = 0;
    for (std::size_t i = first; i < last; ++i) {
      const PixelSamples& p = m_samples[i];
      if (m_active[i] && p.drawn >= min_spp && p.finite >= 2 && p.relmse_estimate() < target) {
        m_active[i] = 0;
        ++n;
      }
    }
    return n;
  });
  for (std::size_t n : retired) m_active_count -= n;
  return m_active_count;
}

void FrameAccumulator::restore(std::vector<PixelSamples> samples, std::vector<PixelAovSums> aovs,
                               std::vector<std::uint8_t> active) {
  KAPPA_CHECK_EQ(samples.size(), m_samples.size());
  KAPPA_CHECK_EQ(aovs.size(), m_aovs.size());
  KAPPA_CHECK(active.empty() || active.size() == m_samples.size());
  m_samples = std::move(samples);
  m_aovs = std::move(aovs);
  m_active = std::move(active);
  m_active_count = m_active.empty() ? m_samples.size()
                                    : std::size_t(std::count_if(m_active.begin(), m_active.end(),
                                                                [](std::uint8_t a) { return a != 0; }));
}

double FrameAccumulator::relmse_estimate() const {
  const auto sums = per_block<double>(m_samples.size(), [&](std::size_t first, std::size_t last) {
    double sum = 0;
    for (std::size_t i = first; i < last; ++i) sum += m_samples[i].relmse_estimate();
    return sum;
  });
  double sum = 0;
  for (double x : sums) sum += x;
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

void resolve_pixel(Film& film, std::size_t pixel, const PixelSamples& p, const PixelAovSums& a) {
  for (int c = 0; c < 3; ++c) film.rgb[3 * pixel + std::size_t(c)] = float(p.value(c));
  if (!film.variance.empty())
    for (int c = 0; c < 3; ++c) film.variance[3 * pixel + std::size_t(c)] = float(p.variance_of_mean(c));
  if (!film.spp.empty()) film.spp[pixel] = float(p.drawn);
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

void FrameAccumulator::resolve(Film& film) const {
  static const PixelAovSums kNone;
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, m_samples.size(), kBlock), [&](const auto& range) {
    for (std::size_t pixel = range.begin(); pixel != range.end(); ++pixel)
      resolve_pixel(film, pixel, m_samples[pixel], m_aovs.empty() ? kNone : m_aovs[pixel]);
  });
}

void share_pass_state(TileSchedule& schedule, FrameAccumulator& acc, int width, int height) {
  static_assert(std::is_trivially_copyable_v<PixelSamples> && std::is_trivially_copyable_v<PixelAovSums>);
  const std::size_t aov_bytes = acc.has_aovs() ? sizeof(PixelAovSums) : 0;
  schedule.share_pass_state(
      width, height, sizeof(PixelSamples) + aov_bytes,
      [&](std::size_t pixel, std::byte* out) {
        std::memcpy(out, &acc.samples(pixel), sizeof(PixelSamples));
        if (aov_bytes) std::memcpy(out + sizeof(PixelSamples), &acc.aov_sums(pixel), aov_bytes);
      },
      [&](std::size_t pixel, const std::byte* in) {
        std::memcpy(&acc.samples(pixel), in, sizeof(PixelSamples));
        if (aov_bytes) std::memcpy(&acc.aov_sums(pixel), in + sizeof(PixelSamples), aov_bytes);
      });
}

}  // namespace kappa
