#include "renderer/commands/bench_command.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "accel/dispatch.h"
#include "accel/factory.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/warning_log.h"
#include "renderer/cli/progress.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/output_guard.h"
#include "renderer/render/ray_sets.h"
#include "renderer/render/ray_timing.h"
#include "renderer/scene/scene_loader.h"

namespace kappa {
namespace {

/// Naive's rough speed on this hardware (triangle tests per second per
/// thread), only to decide whether running it would take minutes.
constexpr double kNaiveTestsPerSecond = 1.5e8;

struct Built {
  std::string name;
  std::unique_ptr<Accelerator> accel;
  double build_s = 0;
  std::uint64_t bytes = 0;
};

struct Result {
  std::string accel, rays;
  int threads = 1;
  double median = 0, min = 0, max = 0;  ///< Mrays/s
  std::uint64_t hits = 0;
};

}  // namespace

int run_bench(const BenchOptions& options) {
  std::vector<RayClass> classes;
  for (const auto& r : options.rays) classes.push_back(parse_ray_class(r));
  const bool show_progress = progress_wanted(false);
  Warnings warnings;
  const Scene scene =
      with_progress(show_progress, [&](TaskProgress* progress) { return load_scene(options.scene, warnings, progress); });
  // Its rays meet the triangles alone: a cut-out's holes are the renderer's (its any-hit filter).
  if (scene.has_cutouts())
    warnings.push_back(located(options.scene, 0, "cut-outs are not applied by kappa bench: its rays meet the triangles alone (kappa render applies them)"));
  print_warnings(warnings);
  refuse_outputs_over_inputs({options.json}, scene.inputs);
  const auto json_out = optional_output(options.json);
  const std::size_t N = scene.triangles.size();

  // Ray sets first, from the grid (any exact accelerator gives the same rays).
  const auto reference = with_progress(show_progress, [&](TaskProgress* progress) {
    return make_accelerator("grid", scene.triangles, options.build, progress);
  });
  std::vector<RaySet> sets;
  for (RayClass c : classes) sets.push_back(make_ray_set(c, scene, *reference, options.n, options.seed));

  std::printf("kappa bench: %s, %zu triangles, %zu rays per class, %d repeats (median of the repeats, after one warm-up pass)\n",
              scene.name.c_str(), N, options.n, options.repeat);
  for (const RaySet& s : sets)
    std::printf("  %-7s %9zu rays: %s\n", ray_class_name(s.kind), s.rays.size(), s.note.c_str());

  std::vector<Built> built;
  for (const auto& name : options.accels) {
    if (name == "naive") {
      double thread_seconds = 0;
      for (int t : options.threads) thread_seconds += 1.0 / t;
      const double estimate = double(N) * double(options.n) * double(sets.size()) * double(options.repeat + 1) *
                              thread_seconds / kNaiveTestsPerSecond;
      if (estimate > options.naive_budget_s) {
        std::printf("  note: naive skipped: %zu triangles x %zu rays would take about %.0f s (budget %.0f s)\n", N,
                    options.n, estimate, options.naive_budget_s);
        continue;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    Built b{name, with_progress(show_progress, [&](TaskProgress* progress) {
              return make_accelerator(name, scene.triangles, options.build, progress);
            })};
    b.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    b.bytes = b.accel->bytes();
    built.push_back(std::move(b));
  }

  // Accelerators take turns on each ray set, one pass each per round, the
  // first of the round rotating: the machine's speed drifts (other tenants,
  // clocks) over seconds, and turns put every accelerator through the same
  // drift, so a ratio compares like with like.
  std::vector<std::vector<Result>> per_accel(built.size());
  for (const RaySet& set : sets) {
    if (set.rays.empty()) continue;
    for (int threads : options.threads) {
      tbb::task_arena arena(threads);
      std::vector<std::vector<double>> rates(built.size());
      std::vector<std::uint64_t> hits(built.size(), 0);
      for (std::size_t k = 0; k < built.size(); ++k)
        visit_accelerator(*built[k].accel, [&](const auto& a) { return time_pass(a, set, arena, hits[k]); });  // warm-up: caches, page faults, thread start
      for (int r = 0; r < options.repeat; ++r) {
        for (std::size_t turn = 0; turn < built.size(); ++turn) {
          const std::size_t k = (turn + std::size_t(r)) % built.size();
          const double s = visit_accelerator(*built[k].accel, [&](const auto& a) { return time_pass(a, set, arena, hits[k]); });
          rates[k].push_back(double(set.rays.size()) / s * 1e-6);
        }
      }
      for (std::size_t k = 0; k < built.size(); ++k)
        per_accel[k].push_back({built[k].name, ray_class_name(set.kind), threads, median_of(rates[k]),
                                 *std::min_element(rates[k].begin(), rates[k].end()),
                                 *std::max_element(rates[k].begin(), rates[k].end()), hits[k]});
    }
  }
  // Listed accelerator by accelerator, as given.
  std::vector<Result> results;
  for (const auto& rows : per_accel) results.insert(results.end(), rows.begin(), rows.end());

  // The peers: robust Embree (watertight, as exact as Embree gets) and
  // Embree without the robust flag at high build quality (accel/embree.h).
  auto peer_rate = [&](const char* peer, const Result& r) -> double {
    for (const Result& e : results)
      if (e.accel == peer && e.rays == r.rays && e.threads == r.threads) return e.median;
    return 0;
  };
  const auto ratio_text = [](double rate, double peer) {
    char text[32];
    if (peer > 0) std::snprintf(text, sizeof text, "%.3f", rate / peer);
    else std::snprintf(text, sizeof text, "-");
    return std::string(text);
  };

  std::printf("\n%-11s %9s %12s\n", "accel", "build_s", "bytes");
  for (const Built& b : built) std::printf("%-11s %9.3f %12llu\n", b.name.c_str(), b.build_s, (unsigned long long)b.bytes);
  std::printf("\n%-11s %-7s %7s %26s %10s %14s %10s\n", "accel", "rays", "threads", "Mrays/s median (min-max)",
              "vs embree", "vs embree-fast", "hits");
  for (const Result& r : results) {
    char range[64];
    std::snprintf(range, sizeof range, "%.3f (%.3f-%.3f)", r.median, r.min, r.max);
    std::printf("%-11s %-7s %7d %26s %10s %14s %10llu\n", r.accel.c_str(), r.rays.c_str(), r.threads, range,
                ratio_text(r.median, peer_rate("embree", r)).c_str(),
                ratio_text(r.median, peer_rate("embree-fast", r)).c_str(), (unsigned long long)r.hits);
  }

  if (json_out) {
    nlohmann::ordered_json j;
    j["scene"] = scene.source.string();
    j["n"] = options.n;
    j["repeat"] = options.repeat;
    j["accels"] = nlohmann::ordered_json::object();
    for (const Built& b : built) j["accels"][b.name] = {{"build_s", b.build_s}, {"bytes", b.bytes}};
    j["results"] = nlohmann::ordered_json::array();
    const auto ratio_json = [](double rate, double peer) {
      return peer > 0 ? nlohmann::ordered_json(rate / peer) : nlohmann::ordered_json();
    };
    for (const Result& r : results) {
      j["results"].push_back({{"accel", r.accel},
                              {"rays", r.rays},
                              {"threads", r.threads},
                              {"mrays_per_s_median", r.median},
                              {"mrays_per_s_min", r.min},
                              {"mrays_per_s_max", r.max},
                              {"ratio_to_embree", ratio_json(r.median, peer_rate("embree", r))},
                              {"ratio_to_embree_fast", ratio_json(r.median, peer_rate("embree-fast", r))},
                              {"hits", r.hits}});
    }
    write_and_commit(*json_out, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace kappa
