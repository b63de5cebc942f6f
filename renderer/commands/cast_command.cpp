#include "renderer/commands/cast_command.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>

#include "accel/factory.h"
#include "accel/grid.h"
#include "accel/thread_limit.h"
#include "renderer/io/atomic_file.h"
#include "renderer/render/bench_rays.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/util/error.h"
#include "renderer/version.h"
#include "stats/cast.h"
#include "stats/cost_model.h"
#include "stats/report.h"
#include "stats/synthetic_rays.h"

namespace kappa {
namespace {

std::string format_or_dash(const nlohmann::ordered_json& v, const char* fmt) {
  if (!v.is_number()) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v.get<double>());
  return buf;
}

void print_table(const std::string& cls, const nlohmann::ordered_json& grid, const nlohmann::ordered_json& rays) {
  std::printf("grid %s x %s x %s: N_c %s, N %s, theta_tot %s (eq19 %s, eq21 %s), empty %s\n",
              grid["res"][0].dump().c_str(), grid["res"][1].dump().c_str(), grid["res"][2].dump().c_str(),
              grid["N_c"].dump().c_str(), grid["N"].dump().c_str(), grid["theta_tot"].dump().c_str(),
              format_or_dash(grid["theta_tot_eq19"], "%.0f").c_str(), format_or_dash(grid["theta_tot_eq21"], "%.0f").c_str(),
              format_or_dash(grid["empty_fraction"], "%.3f").c_str());
  std::printf("%-9s %10s %9s %9s %9s %9s %9s %8s %8s %8s\n", "rays", "count", "cells", "predicted", "tests", "refs",
              "p_tot", "r", "kappa", "eq25");
  std::printf("%-9s %10s %9s %9s %9s %9s %9s %8s %8s %8s\n", cls.c_str(), rays["count"].dump().c_str(),
              format_or_dash(rays["cells_per_ray"], "%.3f").c_str(),
              format_or_dash(rays.value("p_tot_predicted", rays["cells_per_ray_predicted"]), "%.3f").c_str(),
              format_or_dash(rays["tests_per_ray"], "%.3f").c_str(), format_or_dash(rays["refs_per_ray"], "%.3f").c_str(),
              format_or_dash(rays["p_tot"], "%.3f").c_str(), format_or_dash(rays["r"], "%.3f").c_str(),
              format_or_dash(rays["kappa"], "%.3f").c_str(), format_or_dash(rays["kappa_eq25"], "%.3f").c_str());
}

}  // namespace

int run_cast(const CastOptions& options) {
  std::unique_ptr<AtomicOutput> report_out;
  if (!options.report.empty()) report_out = std::make_unique<AtomicOutput>(options.report);
  const ThreadLimit thread_limit(options.threads);

  Warnings warnings;
  const Scene scene = load_scene(options.scene, warnings);
  for (const auto& w : warnings) std::fprintf(stderr, "kappa: warning: %s\n", printable_line(w).c_str());

  const auto accel = make_accelerator(options.accel, scene.triangles, options.build);
  const auto* grid = dynamic_cast<const UniformGrid*>(accel.get());

  // The rays: the paper's synthetic distributions through the grid's box,
  // or the renderer's own from the camera.
  std::vector<Ray> rays;
  GridWalk walk = GridWalk::whole;
  std::optional<double> p_tot_predicted;
  double length = options.length;
  Vec3d lo(scene.bounds().lo), hi(scene.bounds().hi);
  if (grid) lo = grid->info().lo, hi = grid->info().hi;
  if (options.length > 0 && options.rays != "segments")
    std::fprintf(stderr, "kappa: warning: --length applies to --rays segments only; ignored\n");
  if (options.rays == "lines") {
    rays = uniform_lines(lo, hi, options.n, options.seed);
  } else if (options.rays == "segments") {
    if (!(length > 0)) {
      const Vec3d l = grid ? grid->info().cell_size : (hi - lo) / 16.0;
      length = 2.0 * (l.x + l.y + l.z) / 3.0;  // two mean cell widths
    }
    if (length >= max_component(hi - lo))
      throw InputError("--length " + std::to_string(length) + " does not fit in the scene box");
    rays = uniform_segments(lo, hi, length, options.n, options.seed);
  } else {
    const RaySet set = make_ray_set(parse_ray_class(options.rays), scene, *accel, options.n, options.seed);
    rays = set.rays;
    walk = set.occlusion ? GridWalk::any : GridWalk::closest;
  }

  if (rays.size() < options.n)
    std::fprintf(stderr, "kappa: warning: %zu of the %zu rays asked for could be made (the report counts those)\n",
                 rays.size(), options.n);

  nlohmann::ordered_json report;
  report["schema_version"] = kReportSchemaVersion;
  report["kappa_version"] = version_string();
  report["scene"] = scene.source.string();
  report["accel"] = std::string(accel->name());
  report["render"] = nullptr;  // a cast renders nothing
  report["cast"] = {{"rays", options.rays}, {"n", rays.size()}, {"seed", options.seed},
                    {"threads", active_threads()}};
  if (options.rays == "segments") report["cast"]["length"] = length;

  nlohmann::ordered_json ray_section;
  if (grid) {
    const CastMeasurement m = cast_with_counters(*grid, rays, walk, options.build.max_bytes());
    report["stats"] = {{"per_cell", m.counters.per_cell()}};
    if (!m.stats_note.empty()) {
      report["stats_note"] = m.stats_note;
      std::fprintf(stderr, "kappa: warning: %s\n", m.stats_note.c_str());
    }
    if (options.rays == "lines")
      p_tot_predicted = p_tot_lines_eq22(hi - lo, grid->info().cell_size, double(grid->info().resolution.cells()));
    report["grid"] = grid_section(*grid, scene.triangles);
    ray_section = ray_class_section(m, p_tot_predicted);
  } else {
    // Other accelerators: only what applies (counts, hits, time).
    std::atomic<std::uint64_t> hits{0};
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
      const bool hit = walk == GridWalk::any ? accel->any_hit(rays[i]) : accel->closest_hit(rays[i]).has_value();
      hits.fetch_add(hit, std::memory_order_relaxed);
    });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ray_section = {{"count", rays.size()},
                   {"hit_fraction", rays.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(double(hits) / double(rays.size()))},
                   {"time_s", s}};
  }
  report["rays"] = {{options.rays, ray_section}};
  report["cost"] = nullptr;  // no calibration yet (T0, Ts, Th)

  if (!options.quiet) {
    if (grid) print_table(options.rays, report["grid"], ray_section);
    else std::printf("%s: %s rays, hit fraction %s\n", options.rays.c_str(), ray_section["count"].dump().c_str(),
                     ray_section["hit_fraction"].dump().c_str());
  }
  if (report_out) {
    write_and_commit(*report_out, report.dump(2) + "\n");
  }
  return 0;
}

}  // namespace kappa
