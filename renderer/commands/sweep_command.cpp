#include "renderer/commands/sweep_command.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "accel/dispatch.h"
#include "accel/factory.h"
#include "accel/grid.h"
#include "accel/triangle.h"
#include "core/error.h"
#include "core/thread_limit.h"
#include "core/warning_log.h"
#include "renderer/io/calibration_file.h"
#include "renderer/cli/progress.h"
#include "renderer/cli/sweep_range.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/output_guard.h"
#include "renderer/io/plot_script.h"
#include "renderer/render/ray_sets.h"
#include "renderer/render/ray_timing.h"
#include "renderer/scene/scene_loader.h"
#include "stats/builtin_calibration.h"
#include "stats/calibration.h"
#include "stats/cast.h"
#include "stats/time_model.h"

namespace kappa {
namespace {

/// The model's ray class for a ray set: bench's bounce rays leave camera
/// hits (the first bounce); uniform lines share no origin or direction, as
/// incoherent as the deepest bounces.
RenderClass model_class(RayClass c) {
  switch (c) {
    case RayClass::camera: return kCamera;
    case RayClass::shadow: return kShadow;
    case RayClass::bounce: return kBounce1;
    case RayClass::lines: return kBounce3Plus;
  }
  return kBounce3Plus;
}

/// One resolution of the sweep: its grid, and per ray set its counts and times.
struct Point {
  GridResolution res;
  std::unique_ptr<UniformGrid> grid;
  struct PerSet {
    CastMeasurement counted;
    std::vector<double> seconds;
  };
  std::vector<PerSet> sets;
};

}  // namespace

int run_sweep(const SweepOptions& options) {
  if (!options.grid_density.empty() && !options.grid_res.empty())
    throw InputError("--grid-density and --grid-res: give one range, not both");
  const SweepRange range = options.grid_res.empty()
                               ? parse_sweep_range(options.grid_density.empty() ? "1:1024" : options.grid_density,
                                                   "--grid-density")
                               : parse_sweep_range(options.grid_res, "--grid-res");
  std::vector<RayClass> classes;
  for (const auto& r : options.rays) classes.push_back(parse_ray_class(r));
  if (!options.plot.empty() && std::filesystem::path(options.plot).extension() != ".png")
    throw InputError("--plot: '" + options.plot + "' must end in .png");

  const ThreadLimit thread_limit(options.threads);
  const bool show_progress = progress_wanted(options.quiet);
  Warnings warnings;
  const Scene scene =
      with_progress(show_progress, [&](TaskProgress* progress) { return load_scene(options.scene, warnings, progress); });
  // Its rays meet the triangles alone: a cut-out's holes are the renderer's (its any-hit filter).
  if (scene.has_cutouts())
    warnings.push_back(located(options.scene, 0, "cut-outs are not applied by kappa sweep: its rays meet the triangles alone (kappa render applies them)"));
  print_warnings(warnings);

  const std::filesystem::path calibration_path =
      options.calibration.empty() ? default_calibration_path() : std::filesystem::path(options.calibration);
  std::vector<std::filesystem::path> inputs = scene.inputs;
  inputs.push_back(calibration_path);
  refuse_outputs_over_inputs({options.json, options.plot}, inputs);
  JsonAndPlot outputs(options.json, options.plot, "sweep_plot.py");  // claimed, and matplotlib checked, now
  std::optional<Calibration> calibration = read_calibration_file(calibration_path, !options.calibration.empty());
  const bool built_in = !calibration;
  if (built_in) calibration = builtin_calibration();

  const std::size_t N = scene.triangles.size();
  const GridBox box = grid_box(scene.triangles);
  const bool by_density = options.grid_res.empty();
  const double from_cells = by_density ? range.from * double(N) : range.from * range.from * range.from;
  const double to_cells = by_density ? range.to * double(N) : range.to * range.to * range.to;
  const std::vector<GridResolution> resolutions =
      sweep_resolutions(box.extent(), from_cells, to_cells, options.steps);

  // The rays, from a grid at the default density and budget (any exact
  // accelerator gives the same hits, so the same rays; the sweep's budget
  // bounds the points, not this).
  const AccelOptions reference_build;
  const auto reference = with_progress(show_progress, [&](TaskProgress* progress) {
    return make_accelerator("grid", scene.triangles, reference_build, progress);
  });
  std::vector<RaySet> sets;
  for (RayClass c : classes) sets.push_back(make_ray_set(c, scene, *reference, options.n, options.seed));

  GridOptions build;
  if (options.grid_max_bytes > 0) build.max_bytes = options.grid_max_bytes;
  std::vector<Point> points;
  std::vector<std::string> skipped;
  for (const GridResolution& res : resolutions) {
    build.resolution = res;
    Point p{res, nullptr, {}};
    try {
      p.grid = with_progress(show_progress, [&](TaskProgress* progress) {
        return std::make_unique<UniformGrid>(scene.triangles, build, progress);
      });
    } catch (const InputError& e) {
      skipped.push_back(res.to_string() + ": " + e.what());
      continue;
    }
    // The counting pass: the same rays, walked with counters (no timing).
    for (const RaySet& set : sets)
      p.sets.push_back({cast_with_counters(*p.grid, set.rays, set.occlusion ? GridWalk::any : GridWalk::closest,
                                           build.max_bytes),
                        {}});
    points.push_back(std::move(p));
  }
  if (points.empty()) throw InputError(options.scene + ": no resolution of the sweep fits --grid-max-bytes");

  // Timed passes, statistics off: per ray set, the resolutions take turns,
  // the first of each round rotating (as in kappa bench), after one
  // untimed pass each.
  tbb::task_arena arena(options.threads);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (sets[s].rays.empty()) continue;
    std::uint64_t hits = 0;
    for (Point& p : points) time_pass(*p.grid, sets[s], arena, hits);
    for (int r = 0; r < options.repeat; ++r)
      for (std::size_t turn = 0; turn < points.size(); ++turn) {
        Point& p = points[(turn + std::size_t(r)) % points.size()];
        p.sets[s].seconds.push_back(time_pass(*p.grid, sets[s], arena, hits));
      }
  }

  nlohmann::ordered_json j;
  j["scene"] = scene.source.string();
  j["N"] = N;
  j["rays"] = options.rays;
  j["n"] = options.n;
  j["threads"] = options.threads;
  j["repeat"] = options.repeat;
  j["calibration"] = built_in ? std::string("built-in") : calibration_path.string();
  j["skipped"] = skipped;
  j["points"] = nlohmann::ordered_json::array();
  if (!options.quiet) {
    std::printf("kappa sweep: %s, %zu triangles, %zu rays per class, %d threads, median of %d passes; cost model: %s\n",
                scene.name.c_str(), N, options.n, options.threads, options.repeat,
                built_in ? "built-in constants" : calibration_path.c_str());
    for (const RaySet& s : sets)
      std::printf("  %-7s %9zu rays: %s\n", ray_class_name(s.kind), s.rays.size(), s.note.c_str());
    for (const std::string& s : skipped) std::printf("  skipped %s\n", s.c_str());
    std::printf("\n%-7s %-14s %11s %11s %18s %8s %8s %7s %9s %9s %10s %8s\n", "rays", "res", "N_c", "theta_tot",
                "ns/ray (min-max)", "cells", "tests", "kappa", "eq10 ns", "ext ns", "MiB", "build_s");
  }
  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (sets[s].rays.empty()) continue;
    double best = 0;
    for (const Point& p : points) {
      const double m = median_of(p.sets[s].seconds);
      if (best == 0 || m < best) best = m;
    }
    for (const Point& p : points) {
      const CastMeasurement& c = p.sets[s].counted;
      const ClassTotals& t = c.counters.totals;
      const double rays = double(sets[s].rays.size());
      const double working_set = double(p.grid->bytes()) + double(N * sizeof(Triangle));
      QueryLoad load{model_class(sets[s].kind), double(t.rays),          double(t.cells), double(t.occupied_cells),
                     double(t.tests),           double(t.mailbox_skips), double(t.hits),  working_set};
      load.list_bytes = double(p.grid->reference_bytes()) + double(N * sizeof(Triangle));
      const double measured = median_of(p.sets[s].seconds);
      const double eq10 = calibration->eq10.seconds(load) / rays, ext = calibration->extended.seconds(load) / rays;
      const auto& times = p.sets[s].seconds;
      j["points"].push_back({{"res", p.res.to_string()},
                             {"N_c", p.res.cells()},
                             {"class", ray_class_name(sets[s].kind)},
                             {"seconds_per_ray", measured / rays},
                             {"seconds_per_ray_min", *std::min_element(times.begin(), times.end()) / rays},
                             {"seconds_per_ray_max", *std::max_element(times.begin(), times.end()) / rays},
                             {"cells_per_ray", double(t.cells) / rays},
                             {"tests_per_ray", double(t.tests) / rays},
                             {"theta_tot", p.grid->info().theta_tot},
                             {"p_tot", c.collusion.p_tot},
                             {"kappa", c.collusion.kappa ? nlohmann::ordered_json(*c.collusion.kappa) : nullptr},
                             {"bytes", p.grid->bytes()},
                             {"build_s", p.grid->build_s()},
                             {"eq10_s_per_ray", eq10},
                             {"extended_s_per_ray", ext}});
      if (!options.quiet) {
        char spread[48];
        std::snprintf(spread, sizeof spread, "%.1f (%.1f-%.1f)%s", measured / rays * 1e9,
                      *std::min_element(times.begin(), times.end()) / rays * 1e9,
                      *std::max_element(times.begin(), times.end()) / rays * 1e9, measured == best ? "*" : " ");
        std::printf("%-7s %-14s %11llu %11llu %18s %8.2f %8.2f %7.3f %9.1f %9.1f %10.1f %8.3f\n",
                    ray_class_name(sets[s].kind), p.res.to_string().c_str(), (unsigned long long)p.res.cells(),
                    (unsigned long long)p.grid->info().theta_tot, spread, double(t.cells) / rays,
                    double(t.tests) / rays, c.collusion.kappa.value_or(0.0), eq10 * 1e9, ext * 1e9,
                    double(p.grid->bytes()) / double(1 << 20), p.grid->build_s());
      }
    }
  }
  if (!options.quiet) std::printf("(* the fastest resolution for that class)\n");

  outputs.finish(j.dump(2) + "\n");
  return 0;
}

}  // namespace kappa
