#include "machine_probe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <vector>

#include "accel/grid.h"

namespace kappa {
namespace {

// The workload is fixed by these numbers and by the generator below alone (no
// standard-library distribution, whose output differs between libraries, and
// no default resolution, which may change): a calibration file's probe time
// and a later render's time the same queries.
constexpr std::size_t kTriangles = 2048;
constexpr std::size_t kRays = 4096;
constexpr GridResolution kResolution{16, 16, 16};
constexpr int kPasses = 5;  // odd: the median is one pass's time

/// SplitMix64's floats in [0, 1), 24 bits each.
class ProbeRandom {
 public:
  float next() {
    m_state += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = m_state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return float((z ^ (z >> 31)) >> 40) * 0x1p-24f;
  }
  Vec3f point() {  // in order x, y, z
    const float x = next(), y = next();
    return {x, y, next()};
  }

 private:
  std::uint64_t m_state = 0x70726f6265ull;  // "probe"
};

/// Small triangles spread through the unit cube: every cell a ray crosses
/// may hold some, so the walk and the tests both take part.
std::vector<Triangle> probe_soup(ProbeRandom& random) {
  std::vector<Triangle> soup(kTriangles);
  const Vec3f half{0.05f, 0.05f, 0.05f};
  for (Triangle& t : soup) {
    const Vec3f c = random.point();
    const Vec3f a = c + random.point() * 0.1f - half, b = c + random.point() * 0.1f - half;
    t = {c, a, b};
  }
  return soup;
}

/// Rays from points of a cube four times the soup's, about it, toward points
/// inside the soup's.
std::vector<Ray> probe_rays(ProbeRandom& random) {
  std::vector<Ray> rays(kRays);
  const Vec3f centre{0.5f, 0.5f, 0.5f};
  for (Ray& r : rays) {
    const Vec3f from = centre + (random.point() - centre) * 4.0f;
    r.o = from;
    r.d = normalize(random.point() - from);
  }
  return rays;
}

}  // namespace

ProbeResult machine_probe() {
  ProbeRandom random;
  const std::vector<Triangle> soup = probe_soup(random);
  const std::vector<Ray> rays = probe_rays(random);
  GridOptions options;
  options.resolution = kResolution;
  const UniformGrid grid(soup, options);
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
