// libFuzzer target: naive against every other exact accelerator (today the
// grid, at a fuzzed resolution) on fuzzed triangles and rays. For rays in the
// domain docs/accelerators.md guarantees (finite, non-zero direction, origin within a
// few bounding-box diagonals of the scene, 0 <= tmin < tmax) the closest hit
// must be bitwise the same (triangle, t, barycentrics) and any_hit must agree
// with it. Outside that domain: no crash, no hang, and no hit outside
// (tmin, tmax] or on a triangle that does not exist.
//
// Half the inputs snap coordinates to a small lattice, so rays run through
// vertices, along edges and in cell planes, axis-parallel and coplanar, where
// a grid is easiest to get wrong; the other half take raw float bits.
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "accel/factory.h"
#include "accel/naive.h"
#include "core/check.h"
#include "core/input_error.h"
#include "renderer/scene/obj/obj_limits.h"

namespace {

using namespace kappa;

/// Reads the input front to back; zeros once it runs out.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
  bool empty() const { return m_pos >= m_size; }
  std::uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }
  std::uint32_t word() {
    std::uint32_t w = 0;
    for (int i = 0; i < 4; ++i) w = (w << 8) | byte();
    return w;
  }

 private:
  const std::uint8_t* m_data;
  std::size_t m_size;
  std::size_t m_pos = 0;
};

struct Coordinates {
  bool snapped;
  double scale;   ///< lattice step (snapped) or fold range (raw)
  double offset;  ///< translation of the whole scene

  float next(ByteReader& in, int lattice_half_steps) const {
    if (snapped) {
      const int k = int(in.byte() % (2 * lattice_half_steps + 1)) - lattice_half_steps;
      return float(offset + 0.5 * k * scale);
    }
    const float raw = std::bit_cast<float>(in.word());
    if (std::isfinite(raw) && std::fabs(double(raw)) <= kMaxCoordinate) return raw;
    return float(offset + scale * (double(in.byte()) - 128.0) / 16.0);  // fold non-finite and huge values
  }
};

int axis_cells(std::uint8_t b) {
  static const int kChoices[] = {1, 2, 3, 4, 5, 7, 8, 64, 1024, kMaxGridAxis};
  return kChoices[b % std::size(kChoices)];
}

bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

bool finite3(const Vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const std::uint8_t mode = in.byte();
  static const double kScales[] = {1e-6, 1e-3, 1, 1e3, 1e6};
  static const double kOffsets[] = {0, 1, -3.5, 1e3, 1e6};
  const Coordinates coords{(mode & 1) != 0, kScales[(mode >> 1) % 5], kOffsets[(mode >> 4) % 5]};

  AccelOptions options;
  // A fuzzed resolution such as 16384x16384x2 (5e8 cells, 4 GiB while
  // building) fits the default budget, a quarter of RAM, and takes seconds: a
  // user may ask for it, a fuzz run cannot afford it. This budget refuses it
  // as --grid-max-bytes would (the first finding, a 15 s "hang"). 64 MiB was
  // still too much: a 154-byte input's grid took 23.7 s to build and walk
  // under the fuzzer's instrumentation (0.07 s in a release build).
  options.grid_max_bytes = std::uint64_t(8) << 20;
  const std::uint8_t res = in.byte();
  if (res % 4 != 0) {  // else "auto"
    options.grid_res = std::to_string(axis_cells(in.byte())) + "x" + std::to_string(axis_cells(in.byte())) + "x" +
                       std::to_string(axis_cells(in.byte()));
  }

  std::vector<Triangle> triangles(1 + in.byte() % 24);
  for (Triangle& t : triangles)
    for (Vec3f* v : {&t.v0, &t.v1, &t.v2}) *v = {coords.next(in, 4), coords.next(in, 4), coords.next(in, 4)};

  const NaiveAccelerator naive(triangles);
  std::unique_ptr<Accelerator> grid;
  try {
    grid = make_accelerator("grid", triangles, options);
  } catch (const InputError&) {
    return 0;  // a resolution over the memory limit is refused, as on the command line
  }

  Bounds3f box;
  for (const Triangle& t : triangles)
    for (const Vec3f& v : {t.v0, t.v1, t.v2}) box.extend(v);
  const Vec3d lo(box.lo), hi(box.hi);
  const Vec3d centre = (lo + hi) * 0.5;
  const double diagonal = length(hi - lo);

  while (!in.empty()) {
    Ray ray;
    ray.o = {coords.next(in, 12), coords.next(in, 12), coords.next(in, 12)};
    if (coords.snapped) {
      ray.d = {float(int(in.byte() % 5) - 2), float(int(in.byte() % 5) - 2), float(int(in.byte() % 5) - 2)};
    } else {
      ray.d = {std::bit_cast<float>(in.word()), std::bit_cast<float>(in.word()), std::bit_cast<float>(in.word())};
    }
    const std::uint8_t range = in.byte();
    if (range & 1) ray.tmin = std::bit_cast<float>(in.word());
    if (range & 2) ray.tmax = std::bit_cast<float>(in.word());

    const auto expected = naive.closest_hit(ray);
    const auto got = grid->closest_hit(ray);
    const bool in_domain = finite3(ray.o) && finite3(ray.d) && (ray.d.x != 0 || ray.d.y != 0 || ray.d.z != 0) &&
                           std::isfinite(ray.tmin) && ray.tmin >= 0 && ray.tmin < ray.tmax &&
                           length(Vec3d(ray.o) - centre) <= 4 * diagonal;
    if (in_domain) {
      KAPPA_CHECK_EQ(expected.has_value(), got.has_value());
      if (expected) {
        KAPPA_CHECK_EQ(expected->triangle, got->triangle);
        KAPPA_CHECK(same_bits(expected->t, got->t));
        KAPPA_CHECK(same_bits(expected->b0, got->b0) && same_bits(expected->b1, got->b1) &&
                    same_bits(expected->b2, got->b2));
      }
      KAPPA_CHECK_EQ(naive.any_hit(ray), expected.has_value());
      KAPPA_CHECK_EQ(grid->any_hit(ray), expected.has_value());
    } else {
      for (const auto& hit : {expected, got}) {
        if (!hit) continue;
        KAPPA_CHECK_LT(hit->triangle, triangles.size());
        KAPPA_CHECK(hit->t > ray.tmin && hit->t <= ray.tmax);
      }
      (void)grid->any_hit(ray);
    }
  }
  return 0;
}
