#include "renderer/commands/calibrate_command.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <memory>
#include <cstdio>
#include <stdexcept>

#include "accel/factory.h"
#include "accel/grid.h"
#include "accel/grid2.h"
#include "accel/naive.h"
#include "core/error.h"
#include "core/thread_limit.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/output_guard.h"
#include "renderer/render/integrator.h"
#include "renderer/render/statistics_built.h"
#include "renderer/scene/generated_scene.h"
#include "renderer/scene/scene_loader.h"
#include "stats/calibration.h"
#include "stats/machine_probe.h"
#include "stats/query_clock.h"

namespace kappa {
namespace {

/// Generated scenes join the measured ones unless --no-generated: soups (no
/// order in memory, few tests per ray) and dense meshes (numbered along the
/// surface, many tests per occupied cell at low densities), from 3,000 to a
/// million triangles, so that the working set runs from about 0.1 MiB to
/// past the 32 MiB L3 of the project's machines.
struct Generated {
  bool mesh;
  std::size_t triangles;
  std::vector<double> densities;
};
const Generated kGenerated[] = {{false, 3000, {8, 32}},    {false, 30000, {8, 32}},  {false, 300000, {8, 32}},
                                {true, 20000, {2, 8, 32}}, {true, 200000, {2, 8, 32}}, {true, 1000000, {2, 8, 32}}};
/// A class with fewer rays in a calibration frame is not a measurement.
constexpr std::uint64_t kMinRays = 256;
/// The naive model's frames: every measured scene of at most this many
/// triangles (the generated soup of 3,000 among them), and generated soups of
/// these sizes, at a quarter of the
/// samples (a naive query of 3,000 triangles costs about a hundred grid
/// queries), so that T0 and Th are told apart across N while the naive
/// frames add a few seconds.
constexpr std::size_t kNaiveMaxTriangles = 4096;
const std::size_t kNaiveSoups[] = {0, 100, 1000};  // 0: the room alone, 12 triangles, which pins T0
/// grid2's top density for a frame measured at the grid's density `d`: its
/// default at the grid's default, in proportion elsewhere, so that grid2 has
/// as many frames as the grid (enough to determine its model's constants)
/// over top grids from those that refine most cells (deep walks through
/// sub-grids) to those that refine few (walks mostly at the top level).
double grid2_top_density(double d) { return kDefaultGrid2TopDensity * d / kDefaultGridDensity; }

/// One calibration frame: a scene at one density, its grid (or grid2), and
/// what each pass over it measured.
struct Frame {
  const Scene* scene = nullptr;
  std::unique_ptr<Accelerator> grid;
  std::string structure;  ///< the grid's resolution, or grid2's settings, for the labels
  bool grid2 = false;
  double working_set_bytes = 0;
  double list_bytes = 0;  ///< of it, the lists' references and the triangles (QueryLoad::list_bytes)
  std::array<ClassTotals, kRenderClasses> totals{};  ///< the same every pass: frames are deterministic
  std::array<std::vector<double>, kRenderClasses> seconds;
};

/// Renders the frame with statistics on: exactly the queries, in the order
/// and among the shading work, that a render's report times.
void render_pass(Frame& frame, const RenderSettings& settings) {
  Film film(frame.scene->width, frame.scene->height, AovSelection{});
  const RenderResult result = render(*frame.scene, *frame.grid, settings, film);
  if (!result.counters) throw std::logic_error("calibrate: a frame rendered without its counters");
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    frame.totals[k] = result.counters->classes[k].totals;
    frame.seconds[k].push_back(QueryClock::get().seconds(result.counters->ticks[k]));
  }
}

/// One measurement per ray class with enough rays: its counts, and the
/// median of its traversal thread-seconds over the passes.
std::vector<TimedLoad> measurements_of(Frame& frame) {
  std::vector<TimedLoad> out;
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const ClassTotals& t = frame.totals[k];
    if (t.rays < kMinRays) continue;  // too few to time: a frame's classes are not all populated
    std::vector<double>& s = frame.seconds[k];
    std::sort(s.begin(), s.end());
    TimedLoad m;
    m.load = QueryLoad{RenderClass(k),          double(t.rays),          double(t.cells),         double(t.occupied_cells),
                       double(t.tests),     double(t.mailbox_skips), double(t.hits),          frame.working_set_bytes};
    m.load.cold_cells = double(t.cold_cells);
    m.load.cold_tests = double(t.cold_tests);
    m.load.list_bytes = frame.list_bytes;
    m.load.descents = double(t.descents);
    m.seconds = s[s.size() / 2];
    m.label = frame.scene->name + " " + frame.structure + " " + kRenderClassNames[k];
    out.push_back(std::move(m));
  }
  return out;
}

/// One naive frame: every class with enough rays, its median thread-seconds
/// over `repeat` timed passes (each after an untimed one, as the grid's).
std::vector<TimedNaiveLoad> measure_naive(const Scene& scene, const RenderSettings& settings, int repeat) {
  const NaiveAccelerator naive(scene.triangles);
  std::array<std::vector<double>, kRenderClasses> seconds;
  std::array<ClassTotals, kRenderClasses> totals{};
  for (int pass = 0; pass < 2 * repeat; ++pass) {
    Film film(scene.width, scene.height, AovSelection{});
    const RenderResult result = render(scene, naive, settings, film);
    if (pass % 2 == 0) continue;  // warms the caches; its times are dropped
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      totals[k] = result.counters->classes[k].totals;
      seconds[k].push_back(QueryClock::get().seconds(result.counters->ticks[k]));
    }
  }
  std::vector<TimedNaiveLoad> out;
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    if (totals[k].rays < kMinRays) continue;
    std::sort(seconds[k].begin(), seconds[k].end());
    out.push_back({NaiveLoad{RenderClass(k), double(totals[k].rays), double(totals[k].hits), double(scene.triangles.size())},
                   seconds[k][seconds[k].size() / 2], scene.name + " naive " + kRenderClassNames[k]});
  }
  return out;
}

/// The structure built from `options`, the fastest of three builds when it
/// builds in under 0.2 s: a millisecond build's single time is mostly noise.
template <class Structure, class Options>
std::unique_ptr<Structure> fastest_build(std::span<const Triangle> triangles, const Options& options) {
  auto best = std::make_unique<Structure>(triangles, options);
  for (int again = 0; again < 2 && best->build_s() < 0.2; ++again) {
    auto next = std::make_unique<Structure>(triangles, options);
    if (next->build_s() < best->build_s()) best = std::move(next);
  }
  return best;
}

std::string machine_name() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return std::string(host) + ", " + std::to_string(::sysconf(_SC_NPROCESSORS_ONLN)) + " cores";
}

}  // namespace

int run_calibrate(const CalibrateOptions& options) {
  // Its measurements are the counting frames' counts and times.
  if (!statistics_built())
    throw InputError("calibrate: this is kappa-nostats, built without statistics (the overhead baseline); use kappa");
  const std::filesystem::path out_path = options.out.empty() ? default_calibration_path() : std::filesystem::path(options.out);
  std::vector<std::string> files = options.scenes;
  if (files.empty()) {
    const auto assets = default_calibration_path().parent_path().parent_path() / "assets";
    files = {(assets / "cornell-box" / "scene.json").string(), (assets / "bunny-lowres" / "scene_lowres.json").string()};
  }
  // Every scene first: the calibration file must not replace one of their files.
  struct Measured {
    Scene scene;
    std::vector<double> densities;
  };
  std::vector<Measured> scenes;
  std::vector<std::filesystem::path> inputs;
  for (const auto& file : files) {
    Warnings warnings;
    scenes.push_back({load_scene(file, warnings), options.densities});
    inputs.insert(inputs.end(), scenes.back().scene.inputs.begin(), scenes.back().scene.inputs.end());
  }
  if (!options.no_generated)
    for (const Generated& g : kGenerated)
      scenes.push_back({g.mesh ? generated_blob_scene(g.triangles) : generated_soup_scene(g.triangles, 1), g.densities});
  refuse_outputs_over_inputs({out_path}, inputs);
  AtomicOutput out(out_path);

  const ThreadLimit thread_limit(options.threads);
  const int threads = active_threads();
  std::vector<Frame> frames;
  std::vector<TimedBuild> builds;  // each frame's grid, for the build model
  std::vector<TimedBuild> grid2_builds;
  const std::uint64_t options_max_bytes = options.build.max_bytes();
  for (Measured& s : scenes) {
    // The calibration frame is the centre --size x --size window of the
    // scene's own film: a narrower field of view at the film's pixel density,
    // so that neighbouring paths are as close, and their walks share as much
    // of the caches, as in a render of the whole film (a small frame of the
    // whole view reads 10-20 % slower per query for the same counts).
    Scene& scene = s.scene;
    const double crop = std::min(1.0, double(options.size) / double(scene.height));
    scene.camera.vfov_deg = float(2 * std::atan(std::tan(scene.camera.vfov_deg * std::numbers::pi / 360) * crop) * 360 /
                                  std::numbers::pi);
    scene.width = scene.height = options.size;
    for (double density : s.densities) {
      AccelOptions build = options.build;
      build.grid_density = density;
      Frame f;
      f.scene = &scene;
      auto grid = fastest_build<UniformGrid>(scene.triangles, grid_options(build));
      const GridInfo& info = grid->info();
      f.structure = info.resolution.to_string();
      builds.push_back({double(info.N), double(info.theta_tot), double(info.resolution.cells()), grid->build_s(),
                        scene.name + " " + f.structure});
      f.working_set_bytes = double(grid->bytes()) + double(scene.triangles.size() * sizeof(Triangle));
      f.list_bytes = double(grid->reference_bytes()) + double(scene.triangles.size() * sizeof(Triangle));
      f.grid = std::move(grid);
      frames.push_back(std::move(f));
    }
    for (double density : s.densities) {
      Grid2Options options;
      options.top_density = grid2_top_density(density);
      options.max_bytes = options_max_bytes;
      Frame f;
      f.scene = &scene;
      f.grid2 = true;
      char structure[64];
      std::snprintf(structure, sizeof structure, "grid2 top %g", options.top_density);
      f.structure = structure;
      // A fine top grid of a large scene can need more than a grid of its
      // density (a leaf record beside each top cell): over the budget, that
      // frame is left out and said so; the others still fit grid2's constants.
      std::unique_ptr<NestedGrid> grid2;
      try {
        grid2 = fastest_build<NestedGrid>(scene.triangles, options);
      } catch (const InputError& e) {
        std::printf("  %-36s not measured: %s\n", (scene.name + " " + f.structure).c_str(), e.what());
        continue;
      }
      const Grid2Info& info = grid2->info();
      grid2_builds.push_back({double(info.N), double(info.theta_tot), double(info.leaves), grid2->build_s(),
                              scene.name + " " + f.structure});
      f.working_set_bytes = double(grid2->bytes()) + double(scene.triangles.size() * sizeof(Triangle));
      f.list_bytes = double(grid2->reference_bytes()) + double(scene.triangles.size() * sizeof(Triangle));
      f.grid = std::move(grid2);
      frames.push_back(std::move(f));
    }
  }
  // The passes take turns over the frames, so that the machine's drift in
  // speed (up to 1.5x within a minute on shared machines) spreads over every
  // frame instead of falling on a few. Each timed pass follows an untimed one
  // of the same frame: a short frame that starts with another scene's data in
  // the caches reads 10-20 % slower than the same rays in a long render.
  RenderSettings settings;  // the render's defaults, but for the samples
  settings.spp = options.spp;
  settings.stats = true;
  settings.stats_max_bytes = options.build.max_bytes();
  // The machine probe before and after the grid's passes: a render's report
  // sets its own probes against their mean.
  const double probe_before = machine_probe().seconds;
  for (int pass = 0; pass < options.repeat; ++pass)
    for (Frame& f : frames) {
      render_pass(f, settings);  // warms the caches; its times are dropped
      for (auto& s : f.seconds) s.pop_back();
      render_pass(f, settings);
    }
  const double probe_after = machine_probe().seconds;
  std::vector<TimedLoad> measurements, grid2_measurements;
  for (Frame& f : frames)
    for (TimedLoad& m : measurements_of(f)) {
      const double r = m.load.rays;
      std::printf("  %-36s %9.0f rays %8.1f ns/ray %8.2f cells %8.2f tests %6.2f skips %6.1f MiB\n", m.label.c_str(), r,
                  m.seconds / r * 1e9, m.load.cells / r, m.load.tests / r, m.load.skips / r,
                  m.load.working_set_bytes / double(1 << 20));
      (f.grid2 ? grid2_measurements : measurements).push_back(std::move(m));
    }
  // The naive model's frames, after the grid's (their order does not matter:
  // one scene at a time, each pass warmed).
  RenderSettings naive_settings = settings;
  naive_settings.spp = std::max(1, options.spp / 4);
  std::vector<TimedNaiveLoad> naive;
  const auto measure = [&](const Scene& scene) {
    for (TimedNaiveLoad& m : measure_naive(scene, naive_settings, options.repeat)) {
      std::printf("  %-36s %9.0f rays %8.1f ns/ray %8.0f triangles\n", m.label.c_str(), m.load.rays,
                  m.seconds / m.load.rays * 1e9, m.load.triangles);
      naive.push_back(std::move(m));
    }
  };
  for (const Measured& s : scenes)
    if (s.scene.triangles.size() <= kNaiveMaxTriangles) measure(s.scene);
  // The soups even with --no-generated: the given scenes alone may all be
  // of one size, which cannot tell T0 from Th.
  for (const std::size_t n : kNaiveSoups) {
    Scene soup = generated_soup_scene(n, 1);
    soup.width = soup.height = options.size;
    measure(soup);
  }
  Calibration cal = fit_calibration(measurements);
  fit(cal.build, builds, threads);
  fit(cal.naive, naive);
  fit(cal.grid2.traversal, grid2_measurements);
  cal.grid2_coherent = fit_coherent(grid2_measurements, /*nested=*/true);
  fit(cal.grid2.build, grid2_builds, threads);
  cal.machine = machine_name() + ", " + std::to_string(threads) + " walking";
  cal.clock = QueryClock::get().source();
  cal.probe_s = 0.5 * (probe_before + probe_after);
  std::printf("eq 10: T0 %.2f ns, Ts %.2f ns, Th %.2f ns (rms relative error %.1f %%)\n", cal.eq10.ns[0], cal.eq10.ns[1],
              cal.eq10.ns[2], 100 * cal.eq10.rms_relative_error);
  std::printf("extended:");
  for (std::size_t i = 0; i < cal.extended.terms.size(); ++i)
    std::printf(" %s %.2f ns%s", cal.extended.terms[i].c_str(), cal.extended.ns[i],
                i + 1 < cal.extended.terms.size() ? "," : "");
  std::printf(" (rms relative error %.1f %%)\n", 100 * cal.extended.rms_relative_error);
  for (const auto& [name, model] : {std::pair{"grid", &cal.coherent}, std::pair{"grid2", &cal.grid2_coherent}}) {
    if (!*model) {
      std::printf("coherent (%s): not determined by these measurements\n", name);
      continue;
    }
    // Its terms beyond the extended model's: the cold ones, and grid2's per descent.
    const TimeModel& m = **model;
    std::printf("coherent (%s):", name);
    const std::size_t first = extended_model(m.cache_bytes).terms.size();
    for (std::size_t i = first; i < m.terms.size(); ++i)
      std::printf("%s %s %.2f ns", i == first ? "" : ",", m.terms[i].c_str(), m.ns[i]);
    std::printf(" (rms relative error %.1f %%)\n", 100 * m.rms_relative_error);
  }
  std::printf("grid build (%d threads): %.2f ns per triangle, %.2f ns per reference, %.3f ns per cell (rms relative "
              "error %.1f %% over %zu builds)\n",
              threads, cal.build.ns[0], cal.build.ns[1], cal.build.ns[2], 100 * cal.build.rms_relative_error,
              builds.size());
  std::printf("naive: T0 %.2f ns, Th %.3f ns, Th_occluded %.3f ns per triangle (rms relative error %.1f %% over %zu "
              "measurements)\n",
              cal.naive.ns[0], cal.naive.ns[1], cal.naive.ns[2], 100 * cal.naive.rms_relative_error, naive.size());
  std::printf("grid2: traversal T_descend %.2f ns per sub-grid entered (rms relative error %.1f %% over %zu "
              "measurements), build %.2f ns per triangle, %.2f ns per reference, %.3f ns per leaf (rms relative error "
              "%.1f %% over %zu builds)\n",
              cal.grid2.traversal.ns.back(), 100 * cal.grid2.traversal.rms_relative_error, grid2_measurements.size(), cal.grid2.build.ns[0],
              cal.grid2.build.ns[1], cal.grid2.build.ns[2], 100 * cal.grid2.build.rms_relative_error,
              grid2_builds.size());
  std::printf("machine probe: %.2f ms before the grids' passes, %.2f ms after\n", 1e3 * probe_before, 1e3 * probe_after);
  std::printf("%zu measurements -> %s\n", cal.samples, out_path.c_str());
  write_and_commit(out, to_json(cal, {measurements, builds, naive, grid2_measurements, grid2_builds}).dump(2) + "\n");
  return 0;
}

}  // namespace kappa
