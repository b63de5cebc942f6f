#include "renderer/cli/command_line.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <limits>
#include <new>
#include <stdexcept>

#include "core/error.h"
#include "core/memory_need.h"
#include "core/warning_log.h"
#include "renderer/cli/accel_flags.h"
#include "renderer/render/statistics_built.h"
#include "renderer/version.h"

namespace kappa {
namespace {

/// The flags of `kappa render` that set up a frame, bound to `o`; with
/// `converge` only those kappa converge takes (the film's outputs, the budgets
/// and --spp are its own).
void add_render_flags(CLI::App& render, RenderOptions& o, bool converge) {
  if (converge)
    add_accel_flag(render, o.accel, "accelerator");
  else
    add_accel_flag(render, o.accel,
                   "accelerator (default grid2, the fastest exact one; grid, the paper's uniform grid, when "
                   "--grid-res or --grid-density is given); auto: the exact one the cost model predicts fastest "
                   "for the frame (the grid when the render counts cells)",
                   true);
  add_grid_flags(render, o.build, !converge);
  // The default accelerator is grid2, the fastest exact one on whole frames
  // (the README gives the figures); --grid-res and --grid-density set the uniform grid's
  // cells, so given without --accel they mean the uniform grid, as before.
  render.parse_complete_callback([&render, &o] {
    if (render.count("--accel") == 0 && (render.count("--grid-res") > 0 || render.count("--grid-density") > 0))
      o.accel = "grid";
  });
  if (!converge)
    render.add_option("--spp", o.spp, "samples per pixel (with a budget: the most, if given)")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
  render.add_option("--sampler", o.sampler,
                    "where samples fall: independent (PCG32), stratified (jittered strata; needs --spp, so no budget) "
                    "or sobol (Owen-scrambled Sobol (0,2)-sequence, shuffled per dimension pair)")
      ->check(CLI::IsMember({"independent", "stratified", "sobol"}))
      ->capture_default_str();
  render.add_option("--light-sampling", o.light_sampling,
                    "how paths gather light: mis (light and BSDF samples, power heuristic), nee (light samples; "
                    "BSDF-sampled rays count only what light sampling cannot reach) or bsdf (no shadow rays)")
      ->check(CLI::IsMember({"mis", "nee", "bsdf"}))
      ->capture_default_str();
  render.add_option("--specialise", o.specialise,
                    "on: the integrator compiled for what the scene has (no light sampling without emitters, no "
                    "environment look-up in a closed scene, no first hit without AOVs); off: the general one, "
                    "the same image, to measure what that saves")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  render.add_option("--occluder-cache", o.occluder_cache,
                    "on: a shadow ray first tests the triangle that last occluded a ray toward its light (grid and "
                    "grid2), the same image with fewer walks; off: every shadow ray walks, to measure what it saves")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  if (!converge) {
    render.add_option("--time-budget", o.time_budget,
                      "render in passes until this time is spent: a number and a unit, 500ms, 30s, 2m, 1h");
    render.add_option("--target-relmse", o.target_relmse,
                      "render in passes until the estimated relMSE (mean of (s^2/n)/(mean^2 + 0.01)) is below this");
    render.add_flag("--adaptive", o.adaptive, "pixels whose own estimate is below --target-relmse stop sampling");
    render.add_option("--adaptive-min-spp", o.adaptive_min_spp, "samples a pixel takes before --adaptive may stop it")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    render.add_option("--checkpoint-every", o.checkpoint_every,
                      "render in passes and save the completed ones beside the image (IMAGE.checkpoint) this often: "
                      "a number and a unit, 30s, 10m, 1h");
    render.add_flag("--resume", o.resume,
                    "go on from the image's checkpoint (the same scene and settings), to the image a render not "
                    "stopped makes");
  }
  render.add_option("--max-depth", o.max_depth, "bounces after the camera ray (1 = direct lighting)")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  render.add_option("--rr-depth", o.rr_depth, "Russian roulette from this bounce on")
      ->check(CLI::Range(0, 1 << 20))
      ->capture_default_str();
  render.add_flag("--no-rr", o.no_rr, "disable Russian roulette");
  render.add_option("--seed", o.seed, "random seed (0 to 2^53 - 1)")->check(whole_number(0, kMaxSeed))->capture_default_str();
  render.add_option("--threads", o.threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  render.add_option("--width", o.width, "film width (overrides the scene)")->check(CLI::Range(1, 1 << 15));
  render.add_option("--height", o.height, "film height (overrides the scene)")->check(CLI::Range(1, 1 << 15));
  render.add_option("--camera", o.camera, "a glTF scene's camera, by name or index (default: its first perspective camera)");
  if (!converge) {
    render.add_option("--out", o.out, "output EXR (default out/<scene name>.exr)");
    render.add_option("--aov", o.aov, "extra EXR channels: comma list of albedo, normal, depth, cost, variance, spp");
  }
  render.add_flag("-q,--quiet", o.quiet, "no progress bar, summary line or statistics table");
  if (!statistics_built()) o.stats = "off";  // kappa-nostats: the only setting it has
  render.add_option("--stats", o.stats, "per ray class: rays, hits and time; with the grid also cells, tests and hits, per cell and in total")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  render.add_option("--cell-sample", o.cell_sample,
                    "count per cell for 1 path in N (auto: every path on grids of up to 65536 cells, 1 in N_c/8192 rounded down to a power of two, within 64..1024, on larger ones); "
                    "totals always count every ray")
      ->capture_default_str();
  if (converge) return;
  render.add_option("--report", o.report, "write the per-frame JSON report (stats/README.md) here");
  render.add_option("--preview", o.preview,
                    "also an 8-bit sRGB picture of the render to F.png (or .jpg, .tif): radiance x 2^EV, clipped, "
                    "sRGB-encoded (Blender's Standard view)");
  render.add_option("--preview-exposure", o.preview_exposure, "the preview's exposure EV (default 0)")
      ->check(CLI::Range(-64.0, 64.0));
  render.add_option("--cell-map", o.cell_map, "per-cell p_i and Theta_i projected along an axis, to F.exr or F.png");
  render.add_option("--cell-map-axis", o.cell_map_axis, "projection axis of the cell map")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  render.add_option("--calibration", o.calibration, "cost model constants from kappa calibrate (default: beside the executable)");
}

/// `kappa render` and its flags, bound to `o`.
CLI::App* add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App& render = *app.add_subcommand("render", "render a scene to EXR");
  render.add_option("scene", o.scene, "scene.json or .obj file")->required();
  add_render_flags(render, o, false);
  return &render;
}

/// `kappa converge` and its flags, bound to `o`.
CLI::App* add_converge_command(CLI::App& app, ConvergeOptions& o) {
  CLI::App& converge = *app.add_subcommand(
      "converge", "error against time: render progressively, compare with a reference, one curve per setting");
  converge.add_option("scene", o.render.scene, "scene.json or .obj file")->required();
  o.render.stats = "off";  // times without counting, unless asked
  add_render_flags(converge, o.render, true);
  converge.add_option("--reference", o.reference,
                      "reference EXR (default: rendered at 16x the largest --spp with another seed, cached in "
                      "references/ beside the executable)");
  converge.add_option("--cache", o.cache, "folder of self-made references (default: references/ beside the executable)");
  converge.add_option("--spp", o.spp, "sample counts at which the error is measured, ascending")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  converge.add_option("--vary", o.vary,
                      "KEY=V1,V2,...: one curve per value of render's option --KEY, the others at their defaults "
                      "(several --vary keys vary one at a time)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  converge.add_option("--equal-time", o.equal_time_s,
                      "rank the settings by relMSE at this render time in seconds (default: the longest time every "
                      "setting reached; past a curve's end, extrapolated as 1/time)")
      ->check(finite_number(1e-9, 1e9));
  converge.add_option("--json", o.json, "write the curves and the ranking as JSON");
  converge.add_option("--plot", o.plot, "plot relMSE against time, log-log, to F.png (python3-matplotlib)");
  return &converge;
}

/// `kappa bench` and its flags, bound to `o`.
CLI::App* add_bench_command(CLI::App& app, BenchOptions& o) {
  CLI::App& bench = *app.add_subcommand("bench", "time every accelerator on the same rays (Mrays/s)");
  bench.add_option("scene", o.scene, "scene.json or .obj file")->required();
  add_accel_list_flag(bench, o.accels, "accelerators to compare");
  bench.add_option("--rays", o.rays, "ray classes")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(CLI::IsMember({"camera", "bounce", "shadow", "lines"}))
      ->capture_default_str();
  bench.add_option("--threads", o.threads, "thread counts")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(CLI::Range(1, 4096))->capture_default_str();
  bench.add_option("--repeat", o.repeat, "timed passes per figure (the median is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  bench.add_option("--n", o.n, "rays per class")->check(CLI::Range(std::size_t(1), std::size_t(1) << 28))->capture_default_str();
  bench.add_option("--seed", o.seed, "random seed of the ray sets")->check(whole_number(0, kMaxSeed))->capture_default_str();
  bench.add_option("--json", o.json, "also write the figures as JSON");
  add_grid_flags(bench, o.build);
  bench.add_option("--naive-budget", o.naive_budget_s, "skip naive when its estimated run time exceeds this (s)")
      ->check(finite_number(0, 1e12))
      ->capture_default_str();
  return &bench;
}

/// `kappa sweep` and its flags, bound to `o`.
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& o) {
  CLI::App& sweep = *app.add_subcommand(
      "sweep", "the grid's cost against its resolution: bench's rays timed and counted at each, beside the models");
  sweep.add_option("scene", o.scene, "scene.json or .obj file")->required();
  sweep.add_option("--grid-density", o.grid_density,
                   "A:B: lambda (cells per triangle) from A to B, N_c = lambda N (default 1:1024)");
  sweep.add_option("--grid-res", o.grid_res, "A:B: N_c from A^3 to B^3, instead of --grid-density");
  sweep.add_option("--steps", o.steps, "resolutions, geometric in N_c")->check(CLI::Range(1, 1000))->capture_default_str();
  sweep.add_option("--rays", o.rays, "ray classes (kappa bench's sets)")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(CLI::IsMember({"camera", "bounce", "shadow", "lines"}))
      ->capture_default_str();
  sweep.add_option("--n", o.n, "rays per class")->check(CLI::Range(std::size_t(1), std::size_t(1) << 28))->capture_default_str();
  sweep.add_option("--repeat", o.repeat, "timed passes per resolution and class (the median is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sweep.add_option("--threads", o.threads, "threads tracing each timed pass")->check(CLI::Range(1, 4096))->capture_default_str();
  sweep.add_option("--seed", o.seed, "random seed of the ray sets")->check(whole_number(0, kMaxSeed))->capture_default_str();
  sweep.add_option("--grid-max-bytes", o.grid_max_bytes,
                   "skip resolutions whose grid would exceed this many bytes (default: a quarter of RAM)")
      ->check(whole_number(1, std::numeric_limits<std::uint64_t>::max()));
  sweep.add_option("--calibration", o.calibration,
                   "cost-model constants from kappa calibrate (default: beside the executable, else built in)");
  sweep.add_option("--json", o.json, "write every point as JSON");
  sweep.add_option("--plot", o.plot, "plot measured and predicted cost against N_c to F.png (python3-matplotlib)");
  sweep.add_flag("-q,--quiet", o.quiet, "no progress line, no table");
  return &sweep;
}

/// `kappa cast` and its flags, bound to `o`.
CLI::App* add_cast_command(CLI::App& app, CastOptions& o) {
  CLI::App& cast = *app.add_subcommand("cast", "cast synthetic or renderer rays with statistics on (kappa, p_tot, ...)");
  cast.add_option("scene", o.scene, "scene.json or .obj file")->required();
  cast.add_option("--rays", o.rays, "ray distribution")
      ->check(CLI::IsMember({"lines", "segments", "camera", "bounce", "shadow"}))
      ->capture_default_str();
  cast.add_option("--n", o.n, "rays to cast")->check(CLI::Range(std::size_t(1), std::size_t(1) << 30))->capture_default_str();
  add_accel_flag(cast, o.accel, "accelerator (per-cell statistics need grid)");
  add_grid_flags(cast, o.build);
  cast.add_option("--seed", o.seed, "random seed")->check(whole_number(0, kMaxSeed))->capture_default_str();
  cast.add_option("--length", o.length, "segment length for --rays segments (default: two mean cell widths)")
      ->check(finite_number(1e-300, 1e300));
  cast.add_option("--threads", o.threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  cast.add_option("--report", o.report, "write the JSON report here");
  cast.add_flag("-q,--quiet", o.quiet, "no progress line on a terminal, no table on stdout");
  return &cast;
}

/// `kappa calibrate` and its flags, bound to `o`.
CLI::App* add_calibrate_command(CLI::App& app, CalibrateOptions& o) {
  CLI::App& calibrate = *app.add_subcommand("calibrate", "measure the cost model's T0, Ts, Th on this machine");
  calibrate.add_option("scenes", o.scenes, "scenes to measure (default: the Cornell box and the low-res bunny)");
  calibrate
      .add_option("--density", o.densities,
                  "grid densities (cells per triangle) to measure at; grid2 at top densities 1/64 of each")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(finite_number(1e-6, 1e6))
      ->capture_default_str();
  calibrate.add_option("--spp", o.spp, "samples per pixel of each calibration frame")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  calibrate.add_option("--size", o.size, "calibration frames are SIZE x SIZE pixels")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  calibrate.add_flag("--no-generated", o.no_generated,
                     "measure only the scenes given, not also the generated soups of 3,000, 30,000 and 300,000 "
                     "triangles that span the working-set sizes (the naive model's room and soups of 100 and 1,000 triangles are "
                     "measured always)");
  calibrate.add_option("--repeat", o.repeat, "timed passes (median)")->check(CLI::Range(1, 100))->capture_default_str();
  calibrate.add_option("--threads", o.threads,
                       "threads walking at once; times are thread-seconds, as the render report measures them "
                       "(default: all cores)")
      ->check(CLI::Range(1, 4096));
  add_grid_max_bytes_flag(calibrate, o.build);
  calibrate.add_option("--out", o.out, "calibration file (default: kappa_calibration.json beside the executable)");
  return &calibrate;
}

}  // namespace

std::optional<int> parse_command_line(int argc, char** argv, Command& command) {
  CLI::App app{"Kappa: a path tracer that measures the cost of ray casting", "kappa"};
  app.set_version_flag("--version", std::string("kappa ") + version_string());
  app.require_subcommand(1);
  // A repeated option takes its last value, so wrappers such as tools/run.sh
  // can pass defaults that the user's own arguments override.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  RenderOptions render_options;
  BenchOptions bench_options;
  CastOptions cast_options;
  CalibrateOptions calibrate_options;
  ConvergeOptions converge_options;
  SweepOptions sweep_options;
  const CLI::App* render = add_render_command(app, render_options);
  const CLI::App* converge = add_converge_command(app, converge_options);
  const CLI::App* bench = add_bench_command(app, bench_options);
  const CLI::App* cast = add_cast_command(app, cast_options);
  const CLI::App* sweep = add_sweep_command(app, sweep_options);
  add_calibrate_command(app, calibrate_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version: printed, exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11's own codes are 105-109; Kappa's contract for bad options is 2.
    std::fprintf(stderr, "kappa: error: %s (see kappa --help)\n", printable_line(e.what()).c_str());
    return 2;
  }
  if (render->parsed()) {
    render_options.spp_given = render->count("--spp") > 0;
    render_options.adaptive_min_spp_given = render->count("--adaptive-min-spp") > 0;
    render_options.time_budget_given = render->count("--time-budget") > 0;
    render_options.target_relmse_given = render->count("--target-relmse") > 0;
    render_options.checkpoint_every_given = render->count("--checkpoint-every") > 0;
    command = std::move(render_options);
  }
  else if (bench->parsed()) command = std::move(bench_options);
  else if (cast->parsed()) command = std::move(cast_options);
  else if (converge->parsed()) command = std::move(converge_options);
  else if (sweep->parsed()) command = std::move(sweep_options);
  else command = std::move(calibrate_options);  // require_subcommand(1): one of the six
  return std::nullopt;
}

RenderOptions vary_render_option(const RenderOptions& base, const std::string& key, const std::string& value) {
  RenderOptions o = base;
  CLI::App app{"kappa converge --vary"};
  add_render_flags(app, o, true);
  std::vector<std::string> args = {"--" + key + "=" + value};  // CLI11 parses a reversed vector
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw InputError("--vary " + key + "=" + value + ": " + e.what() +
                     " (keys are render's options that kappa converge takes)");
  }
  // This parse saw no --accel, so the rule that grid flags alone mean the
  // uniform grid must not replace the accelerator the base run has.
  if (key != "accel") o.accel = base.accel;
  return o;
}

int exit_code_of(const std::function<int()>& run) {
  // The warnings counted but not shown are summed up before the last line.
  try {
    const int code = run();
    warning_log().finish();
    return code;
  } catch (const InputError& e) {
    warning_log().finish();
    std::fprintf(stderr, "kappa: error: %s\n", printable_line(e.what()).c_str());
    return 2;
  } catch (const OutputError& e) {
    warning_log().finish();
    std::fprintf(stderr, "kappa: error: %s\n", printable_line(e.what()).c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    // Too big an input for this machine (or its limits): the input's
    // doing, exit 2, naming what needed the memory.
    std::fprintf(stderr, "kappa: error: %s\n", out_of_memory_message().c_str());
    return 2;
  } catch (const std::exception& e) {
    warning_log().finish();
    std::fprintf(stderr, "kappa: internal error: %s\n", printable_line(e.what()).c_str());
    return 1;
  }
}

}  // namespace kappa
