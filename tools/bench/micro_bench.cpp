// Google Benchmark micro-benchmarks of the two inner loops of the grid: the
// watertight triangle test and one 3D-DDA step. Built with the project, not
// run by tools/test.sh:  build/kappa_micro_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "accel/grid.h"
#include "accel/triangle.h"

namespace kappa {
namespace {

struct RayTriangle {
  Ray ray;
  Triangle tri;
};

/// Pairs where the ray hits (hit = true) or misses the triangle.
std::vector<RayTriangle> pairs(bool hit, std::size_t n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<RayTriangle> out;
  while (out.size() < n) {
    const Triangle tri{{u(rng), u(rng), 2 + u(rng)}, {u(rng), u(rng), 2 + u(rng)}, {u(rng), u(rng), 2 + u(rng)}};
    const Ray ray{{u(rng) * 0.5f, u(rng) * 0.5f, 0}, {u(rng) * 0.3f, u(rng) * 0.3f, 1}};
    float t, b0, b1, b2;
    if (intersect_triangle(PreparedRay(ray), tri, 0, INFINITY, t, b0, b1, b2) == hit) out.push_back({ray, tri});
  }
  return out;
}

template <bool Hit>
void BM_TriangleTest(benchmark::State& state) {
  const auto set = pairs(Hit, 4096);
  std::vector<PreparedRay> prepared;
  for (const auto& p : set) prepared.emplace_back(p.ray);
  std::size_t i = 0, found = 0;
  for (auto _ : state) {
    float t, b0, b1, b2;
    found += intersect_triangle(prepared[i], set[i].tri, 0, INFINITY, t, b0, b1, b2);
    i = (i + 1) & 4095;
  }
  benchmark::DoNotOptimize(found);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TriangleTest<true>)->Name("triangle_test/hit");
BENCHMARK(BM_TriangleTest<false>)->Name("triangle_test/miss");

/// One DDA step: rays cross a 256^3 grid whose only triangle sits in a
/// corner they never reach, so every cell they visit is empty.
void BM_DdaStep(benchmark::State& state) {
  const int res = int(state.range(0));
  const std::vector<Triangle> tris = {{{0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}}, {{1, 1, 1}, {1, 1, 1 - 1e-3f}, {1, 1 - 1e-3f, 1}}};
  GridOptions options;
  options.resolution = GridResolution{res, res, res};
  const UniformGrid grid(tris, options);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.3f, 0.7f);
  std::vector<Ray> rays;
  for (int i = 0; i < 1024; ++i) rays.push_back(Ray{{u(rng), u(rng), -0.5f}, {u(rng) - 0.5f, u(rng) - 0.5f, 1}});
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    hits += grid.closest_hit(rays[i]).has_value();
    i = (i + 1) & 1023;
  }
  benchmark::DoNotOptimize(hits);
  // A ray along +z crossing the grid visits about res + |dx|/l + |dy|/l cells.
  state.counters["cells_per_s"] = benchmark::Counter(double(state.iterations()) * res * 1.2, benchmark::Counter::kIsRate);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DdaStep)->Name("dda_walk")->Arg(64)->Arg(256);

}  // namespace
}  // namespace kappa

BENCHMARK_MAIN();
