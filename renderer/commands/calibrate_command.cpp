#include "renderer/commands/calibrate_command.h"

#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>

#include "accel/factory.h"
#include "accel/grid.h"
#include "accel/grid_traverse.h"
#include "accel/thread_limit.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/output_guard.h"
#include "renderer/render/ray_sets.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/util/error.h"
#include "stats/calibration.h"
#include "stats/cast.h"
#include "stats/synthetic_rays.h"

namespace kappa {
namespace {

/// Median thread-seconds per ray of walking every ray once with `threads`
/// threads at once, nothing recorded: the render report's measured time is
/// thread-seconds of walks running on every core, which share caches and
/// memory bandwidth, so the constants are measured the same way.
double seconds_per_ray(const UniformGrid& grid, const std::vector<Ray>& rays, GridWalk walk, int repeat, int threads) {
  std::vector<double> times;
  std::atomic<std::uint64_t> sink{0};
  for (int r = 0; r <= repeat; ++r) {  // pass 0 warms the caches and is not kept
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
      NoRecorder none;
      std::uint64_t hits = 0;
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        switch (walk) {
          case GridWalk::closest: hits += grid.closest_hit(rays[i], none).has_value(); break;
          case GridWalk::any: hits += grid.any_hit(rays[i], none); break;
          case GridWalk::whole: hits += grid.walk_whole(rays[i], none).has_value(); break;
        }
      }
      sink.fetch_add(hits, std::memory_order_relaxed);  // keeps the walks from being optimized away
    });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Thread-seconds: every thread busy, unless there are fewer chunks of rays than threads.
    const std::size_t busy = std::min<std::size_t>(std::size_t(threads), (rays.size() + 1023) / 1024);
    if (r > 0) times.push_back(s * double(std::max<std::size_t>(busy, 1)) / double(std::max<std::size_t>(rays.size(), 1)));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

std::string machine_name() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return std::string(host) + ", " + std::to_string(::sysconf(_SC_NPROCESSORS_ONLN)) + " cores";
}

}  // namespace

int run_calibrate(const CalibrateOptions& options) {
  const std::filesystem::path out_path = options.out.empty() ? default_calibration_path() : std::filesystem::path(options.out);
  std::vector<std::string> files = options.scenes;
  if (files.empty()) {
    const auto assets = default_calibration_path().parent_path().parent_path() / "assets";
    files = {(assets / "cornell-box" / "scene.json").string(), (assets / "bunny-lowres" / "scene_lowres.json").string()};
  }
  // Every scene first: the calibration file must not replace one of their files.
  std::vector<Scene> scenes;
  std::vector<std::filesystem::path> inputs;
  for (const auto& file : files) {
    Warnings warnings;
    scenes.push_back(load_scene(file, warnings));
    inputs.insert(inputs.end(), scenes.back().inputs.begin(), scenes.back().inputs.end());
  }
  refuse_outputs_over_inputs({out_path}, inputs);
  AtomicOutput out(out_path);

  const ThreadLimit thread_limit(options.threads);
  const int threads = active_threads();
  std::vector<CostSample> samples;
  for (const Scene& scene : scenes) {
    for (double density : options.densities) {
      AccelOptions build = options.build;
      build.grid_density = density;
      const UniformGrid grid(scene.triangles, grid_options(build));
      for (RayClass cls : {RayClass::camera, RayClass::bounce, RayClass::shadow, RayClass::lines}) {
        std::vector<Ray> rays;
        GridWalk walk = GridWalk::closest;
        if (cls == RayClass::lines) {
          rays = uniform_lines(grid.info().lo, grid.info().hi, options.n, 1);
        } else {
          const RaySet set = make_ray_set(cls, scene, grid, options.n, 1);
          rays = set.rays;
          if (set.occlusion) walk = GridWalk::any;
        }
        if (rays.empty()) continue;
        const CastMeasurement m = cast_with_counters(grid, rays, walk);
        CostSample s;
        s.seconds_per_ray = seconds_per_ray(grid, rays, walk, options.repeat, threads);
        s.cells_per_ray = double(m.counters.totals.cells) / double(rays.size());
        s.refs_per_ray = double(m.counters.totals.refs) / double(rays.size());
        s.label = scene.name + " " + grid.info().resolution.to_string() + " " + ray_class_name(cls);
        std::printf("  %-40s %8.1f ns/ray %8.2f cells %8.2f refs\n", s.label.c_str(), s.seconds_per_ray * 1e9,
                    s.cells_per_ray, s.refs_per_ray);
        samples.push_back(s);
      }
    }
  }
  Calibration cal = fit_calibration(samples);
  cal.machine = machine_name() + ", " + std::to_string(threads) + " walking";
  std::printf("T0 %.2f ns, Ts %.2f ns, Th %.2f ns (%zu measurements, rms relative error %.1f %%) -> %s\n", cal.T0_ns,
              cal.Ts_ns, cal.Th_ns, cal.samples, 100 * cal.rms_relative_error, out_path.c_str());
  write_and_commit(out, to_json(cal, samples).dump(2) + "\n");
  return 0;
}

}  // namespace kappa
