#include "machine_probe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <random>
#include <vector>

#include "accel/grid.h"
#include "synthetic_rays.h"

namespace kappa {
namespace {

constexpr std::size_t kTriangles = 2048;
constexpr std::size_t kRays = 4096;
constexpr int kPasses = 5;  // odd: the median is one pass's time
constexpr std::uint64_t kSeed = 0x70726f6265ull;  // "probe"

/// Small triangles spread through the unit cube: every cell a ray crosses
/// may hold some, so the walk and the tests both take part.
std::vector<Triangle> probe_soup() {
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), e(-0.05f, 0.05f);
  std::vector<Triangle> soup(kTriangles);
  for (Triangle& t : soup) {
    const Vec3f c{u(rng), u(rng), u(rng)};
    t = {c + Vec3f{e(rng), e(rng), e(rng)}, c + Vec3f{e(rng), e(rng), e(rng)}, c + Vec3f{e(rng), e(rng), e(rng)}};
  }
  return soup;
}

}  // namespace

ProbeResult machine_probe() {
  const std::vector<Triangle> soup = probe_soup();
  const UniformGrid grid(soup, GridOptions{});
  const std::vector<Ray> rays = uniform_lines({0, 0, 0}, {1, 1, 1}, kRays, kSeed);
  std::array<double, kPasses> seconds{};
  std::uint64_t hits = 0;
  for (double& s : seconds) {
    hits = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const Ray& ray : rays) hits += grid.closest_hit(ray).has_value();
    s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::nth_element(seconds.begin(), seconds.begin() + kPasses / 2, seconds.end());
  return {seconds[kPasses / 2], hits};
}

}  // namespace kappa
