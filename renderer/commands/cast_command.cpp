#include "renderer/commands/cast_command.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <optional>
#include <type_traits>

#include "accel/cell_layout.h"
#include "accel/dispatch.h"
#include "accel/factory.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/thread_limit.h"
#include "core/warning_log.h"
#include "renderer/cli/progress.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/output_guard.h"
#include "renderer/render/ray_sets.h"
#include "renderer/report/report_sections.h"
#include "renderer/report/stats_table.h"
#include "renderer/scene/scene_loader.h"
#include "stats/cast.h"
#include "stats/cost_model.h"
#include "stats/report.h"
#include "stats/synthetic_rays.h"

namespace kappa {

int run_cast(const CastOptions& options) {
  const ThreadLimit thread_limit(options.threads);

  const bool show_progress = progress_wanted(options.quiet);
  Warnings warnings;
  const Scene scene =
      with_progress(show_progress, [&](TaskProgress* progress) { return load_scene(options.scene, warnings, progress); });
  // Its rays meet the triangles alone: a cut-out's holes are the renderer's (its any-hit filter).
  if (scene.has_cutouts())
    warnings.push_back(located(options.scene, 0, "cut-outs are not applied by kappa cast: its rays meet the triangles alone (kappa render applies them)"));
  print_warnings(warnings);
  refuse_outputs_over_inputs({options.report}, scene.inputs);
  const auto report_out = optional_output(options.report);

  const auto accel = with_progress(show_progress, [&](TaskProgress* progress) {
    return make_accelerator(options.accel, scene.triangles, options.build, progress);
  });
  const CellLayout* cells = accel->cells();
  const std::optional<Vec3d> cell_size = cells ? cells->uniform_cell_size() : std::nullopt;

  // The rays: the paper's synthetic distributions through the cells' box,
  // or the renderer's own from the camera.
  std::vector<Ray> rays;
  GridWalk walk = GridWalk::whole;
  std::optional<double> p_tot_predicted;
  double length = options.length;
  Vec3d lo(scene.bounds().lo), hi(scene.bounds().hi);
  if (cells) lo = cells->bounds().lo, hi = cells->bounds().hi;
  if (options.length > 0 && options.rays != "segments")
    warning_log().add("--length applies to --rays segments only; ignored");
  if (options.rays == "lines") {
    rays = uniform_lines(lo, hi, options.n, options.seed);
  } else if (options.rays == "segments") {
    if (!(length > 0)) {
      const Vec3d l = cell_size.value_or((hi - lo) / 16.0);
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
    warning_log().add(std::to_string(rays.size()) + " of the " + std::to_string(options.n) +
                      " rays asked for could be made (the report counts those)");

  nlohmann::ordered_json report = report_header(scene, *accel);
  report["render"] = nullptr;  // a cast renders nothing
  report["cast"] = {{"rays", options.rays}, {"n", rays.size()}, {"seed", options.seed},
                    {"threads", active_threads()}};
  if (options.rays == "segments") report["cast"]["length"] = length;

  nlohmann::ordered_json ray_section = visit_accelerator(*accel, [&](const auto& a) {
    using A = std::decay_t<decltype(a)>;
    if constexpr (CellWalker<A>) {
      const CastMeasurement m = cast_with_counters(a, rays, walk, options.build.max_bytes());
      add_stats_block(report, m.counters.per_cell(), m.cell_sample, m.stats_note);
      if (!m.stats_note.empty()) warning_log().add(m.stats_note);
      if (options.rays == "lines" && cell_size)
        p_tot_predicted = p_tot_lines_eq22(hi - lo, *cell_size, double(cells->cell_count()));
      report[std::string(a.name())] = accel_section(a, scene.triangles);
      nlohmann::ordered_json section = ray_class_section(m, p_tot_predicted);
      add_level_figures(section, m.counters.totals, cells->levels());
      return section;
    } else {
      // Accelerators without cells: only what applies (counts, hits, time).
      std::atomic<std::uint64_t> hits{0};
      const auto start = std::chrono::steady_clock::now();
      kappa::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
        const bool hit = walk == GridWalk::any ? a.any_hit(rays[i]) : a.closest_hit(rays[i]).has_value();
        hits.fetch_add(hit, std::memory_order_relaxed);
      });
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return any_accel_class_section(rays.size(), hits, s);
    }
  });
  report["rays"] = {{options.rays, ray_section}};
  report["cost"] = nullptr;  // no calibration yet (T0, Ts, Th)

  if (!options.quiet) {
    if (cells) std::fputs(grid_occupancy_line(report[std::string(accel->name())]).c_str(), stdout);
    std::fputs(stats_table(report).c_str(), stdout);
  }
  if (report_out) {
    report["warnings"] = warnings_section(warning_log().kinds());
    write_and_commit(*report_out, report.dump(2) + "\n");
  }
  return 0;
}

}  // namespace kappa
