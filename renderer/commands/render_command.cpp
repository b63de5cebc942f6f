#include "renderer/commands/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iterator>
#include <chrono>
#include <optional>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include "accel/cell_layout.h"
#include "accel/factory.h"
#include "core/byte_size.h"
#include "core/error.h"
#include "core/memory_need.h"
#include "core/thread_limit.h"
#include "core/warning_log.h"
#include "renderer/io/calibration_file.h"
#include "renderer/cli/duration.h"
#include "renderer/cli/interrupt.h"
#include "renderer/cli/progress.h"
#include "renderer/cli/render_settings.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/cell_map.h"
#include "renderer/io/checkpoint_file.h"
#include "renderer/io/preview.h"
#include "renderer/io/exr_output.h"
#include "renderer/io/output_guard.h"
#include "renderer/io/output_target.h"
#include "renderer/render/accel_choice.h"
#include "renderer/render/frame_accumulator.h"
#include "renderer/render/frame_progress.h"
#include "renderer/render/frame_split.h"
#include "renderer/render/integrator.h"
#include "renderer/render/sampler_kind.h"
#include "renderer/report/render_record.h"
#include "renderer/report/render_report.h"
#include "renderer/report/report_sections.h"
#include "renderer/report/stats_table.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/version.h"
#include "stats/builtin_calibration.h"
#include "stats/calibration.h"
#include "stats/machine_probe.h"

namespace kappa {
namespace {

AovSelection parse_aovs(const std::string& list) {
  AovSelection aov;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    if (name == "albedo") aov.albedo = true;
    else if (name == "normal") aov.normal = true;
    else if (name == "depth") aov.depth = true;
    else if (name == "cost") aov.cost = true;
    else if (name == "variance") aov.variance = true;
    else if (name == "spp") aov.spp = true;
    else if (!name.empty())
      throw InputError("--aov: unknown AOV '" + name + "' (expected albedo, normal, depth, cost, variance, spp)");
  }
  return aov;
}

/// The image's path; the default's folder is made by the process that writes
/// (`writer`: kappa-mpi's other ranks, maybe on other hosts, make nothing).
std::filesystem::path output_path(const RenderOptions& options, const Scene& scene, bool writer) {
  if (!options.out.empty()) return options.out;
  const std::filesystem::path dir = "out";
  std::error_code ec;
  if (writer) std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("out: cannot create the output folder: " + ec.message());
  return dir / (scene.name + ".exr");
}

/// The budgets asked for (pass_planner.h), refused before anything is loaded.
Budget budget_of(const RenderOptions& options) {
  Budget budget;
  if (options.time_budget_given) budget.time_s = parse_duration(options.time_budget, "--time-budget");
  if (options.target_relmse_given) {
    const std::string& text = options.target_relmse;
    double e = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), e);
    if (ec != std::errc() || end != text.data() + text.size() || !(e > 0) || !std::isfinite(e))
      throw InputError("--target-relmse: '" + text + "' is not a number above 0");
    // The estimate falls as c / spp, c = a pixel's variance over (mean^2 +
    // 0.01): even a smooth scene's c of 1e-3 needs 1e9 spp, Kappa's limit of
    // 2^30, to reach 1e-12. A target below would render without end.
    if (e < kMinTargetRelmse)
      throw InputError("--target-relmse: '" + text + "' is below 1e-12, which no render reaches within Kappa's limit of " +
                       std::to_string(kMaxSpp) + " samples per pixel");
    budget.target_relmse = e;
  }
  if (options.adaptive && budget.target_relmse == 0)
    throw InputError("--adaptive: needs --target-relmse (the estimate at which a pixel stops sampling)");
  if (options.adaptive_min_spp_given && !options.adaptive)
    throw InputError("--adaptive-min-spp: needs --adaptive");
  budget.adaptive = options.adaptive;
  budget.adaptive_min_spp = options.adaptive_min_spp;
  if (options.spp_given) budget.spp_cap = options.spp;
  if (options.checkpoint_every_given)
    budget.longest_pass_s = parse_duration(options.checkpoint_every, "--checkpoint-every");
  // Checkpoints (and a resume) make a render of --spp progressive: its
  // passes end at --spp as the one pass would.
  if (!budget.any() && (options.checkpoint_every_given || options.resume)) budget.spp_cap = options.spp;
  if ((budget.any() || options.checkpoint_every_given || options.resume) && needs_total(parse_sampler(options.sampler)))
    throw InputError("--sampler " + options.sampler +
                     ": needs the samples per pixel in advance, which a budget decides as it goes (use independent or sobol)");
  return budget;
}

/// "pass 4: 24 spp, relMSE 0.0123": what the progress line says of a budgeted render.
std::string pass_text(const FrameState& state, int passes, const Budget& budget) {
  char text[160];
  int n = std::snprintf(text, sizeof text, "rendering, pass %d: %d spp, relMSE %.4g", passes, state.spp,
                        state.relmse_estimate);
  if (budget.adaptive && n > 0 && n < int(sizeof text))
    std::snprintf(text + n, sizeof text - std::size_t(n), ", %zu pixels sampling", state.active_pixels);
  return text;
}

/// The cell structure for the EXR's metadata: "64x32x16", or "none".
std::string resolution_text(const Accelerator& accel) {
  return accel.cells() ? accel.cells()->resolution_text() : std::string("none");
}

/// ", traversal 1.23 s measured, 1.20 s predicted" (thread-seconds; the
/// extended model's prediction), or nothing with statistics off.
std::string traversal_summary(const nlohmann::ordered_json& cost) {
  if (!cost.is_object()) return "";
  char text[128];
  if (cost["extended"].is_object())
    std::snprintf(text, sizeof text, ", traversal %.3f s measured, %.3f s predicted", cost["measured_s"].get<double>(),
                  cost["extended"]["predicted_s"].get<double>());
  else
    std::snprintf(text, sizeof text, ", traversal %.3f s measured", cost["measured_s"].get<double>());
  return text;
}

/// With --accel auto or --grid-res model on a frame shared by processes: the
/// writer chooses (its calibration, its pilot) and builds; the others build
/// what it chose, "grid2", "naive", "grid" or "grid 64x32x16" (a resolution
/// the model chose), without a pilot of their own. An empty choice: the
/// writer failed, and reports it.
FrameAccelerator build_as_the_writer_chooses(FrameSplit& split, const Scene& scene, const RenderSettings& settings,
                                             const AccelRequest& request, const Calibration& calibration,
                                             TaskProgress* progress) {
  if (split.writer()) {
    FrameAccelerator built;
    try {
      built = build_frame_accelerator(scene, settings, request, calibration, progress);
    } catch (...) {
      split.writer_text("");
      throw;
    }
    std::string choice(built.accel->name());
    if (built.grid_choice) choice += " " + built.accel->cells()->resolution_text();
    split.writer_text(choice);
    return built;
  }
  const std::string choice = split.writer_text("");
  if (choice.empty()) throw InputError("the writing rank failed to build the accelerator");
  AccelRequest chosen = request;
  const std::size_t space = choice.find(' ');
  chosen.accel = choice.substr(0, space);
  if (space != std::string::npos) chosen.build.grid_res = choice.substr(space + 1);
  return {make_accelerator(chosen.accel, scene.triangles, chosen.build, progress), {}, nullptr, {}};
}

/// The settings a checkpoint must have been made with to be resumed here:
/// the render record's, which decide the image and the counts, less the
/// scene's path (its inputs' hash stands for it, wherever it is run from)
/// and the time budget (a resumed render may be given more time); with the
/// camera and the occluder cache added (the cache decides which shadow rays
/// walk, so the counts).
nlohmann::ordered_json checkpoint_settings(const RenderOptions& options, const Scene& scene, const Accelerator& accel,
                                           const Budget& budget) {
  nlohmann::ordered_json settings = to_json(render_record(options, scene, resolution_text(accel), options.spp, budget));
  settings.erase("scene");
  settings.erase("time_budget");
  settings["camera"] = options.camera;
  settings["occluder_cache"] = options.occluder_cache;
  return settings;
}

/// The checkpoint beside the image is a plain file Kappa writes, replaces
/// and removes: anything else there (a link, a pipe, a device, a folder) is
/// refused rather than written through, blocked on or removed. Without
/// --resume, a checkpoint already there is one a stopped render left: a new
/// render would write over it at its first save.
void refuse_checkpoint_path(const std::filesystem::path& file, bool resume) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::symlink_status(file, ec);
  if (ec || status.type() == std::filesystem::file_type::not_found) return;
  if (status.type() != std::filesystem::file_type::regular)
    throw InputError(file.string() + ": not a plain file, where the render keeps its checkpoint (move it away)");
  if (!resume)
    throw InputError(file.string() + ": the checkpoint of a render stopped before: --resume to go on from it, or remove it");
}

/// A file's bytes, or InputError saying why not.
std::string read_bytes(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(what + ": cannot read " + path.string() + " (a render with --checkpoint-every saves it)");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(what + ": cannot read " + path.string());
  return bytes;
}

/// The outputs a render claims before it renders (the writer's only).
struct ClaimedOutputs {
  std::unique_ptr<AtomicOutput> image, report, cell_map, preview;
};

}  // namespace

int run_render(const RenderOptions& options, FrameSplit* split) {
  const Budget budget = budget_of(options);
  const bool shared_frame = split && split->processes() > 1;
  const bool writer = !split || split->writer();
  AovSelection aov = parse_aovs(options.aov);
  aov.variance = aov.variance || budget.target_relmse > 0;  // the estimate's inputs, per pixel
  aov.spp = aov.spp || budget.adaptive;
  // auto counts as the grid here: a render that counts cells runs a cell-based accelerator.
  const bool cell_based = options.accel == "grid" || options.accel == "grid2" || options.accel == "auto";
  if (!options.cell_map.empty() && (options.stats != "on" || !cell_based))
    throw InputError("--cell-map: needs --accel grid or grid2 and --stats on");
  if (const auto ext = std::filesystem::path(options.cell_map).extension(); !options.cell_map.empty() && ext != ".exr" &&
                                                                            ext != ".png")
    throw InputError("--cell-map: '" + options.cell_map + "' must end in .exr or .png");
  if (!options.preview.empty()) check_preview_name(options.preview);
  RenderSettings settings = render_settings_of(options, aov);  // a bad setting is refused before loading
  const bool grid_by_model = options.build.grid_res == "model";
  if (grid_by_model && options.accel != "grid" && options.accel != "auto")
    throw InputError("--grid-res model: needs --accel grid or auto (it chooses the grid's resolution)");
  if (aov.cost && (options.stats != "on" || !cell_based))
    throw InputError("--aov cost: needs --accel grid or grid2 and --stats on (it counts the cells and tests)");
  // A device, FIFO or descriptor (`--out -`) gets OpenEXR whatever its name.
  if (!options.out.empty() && std::filesystem::path(options.out).extension() != ".exr" && !leads_to_stream(options.out))
    throw InputError("--out: '" + options.out + "' must end in .exr (or be a pipe, a device or -)");

  // --threads limits loading, the accelerator's build and the render alike.
  const ThreadLimit thread_limit(options.threads);
  // Progress lines while loading and building, erased when each is done.
  const bool show_progress = writer && progress_wanted(options.quiet);
  Warnings warnings;
  Scene scene = agreed_step(split, [&] {
    return with_progress(show_progress, [&](TaskProgress* progress) { return load_scene(options.scene, warnings, progress); });
  });
  print_warnings(warnings);
  apply_view(scene, options.camera, options.width, options.height);
  if (!scene.punctual_lights.empty() && options.light_sampling == "bsdf")
    print_warnings({"--light-sampling bsdf: the scene's " + std::to_string(scene.punctual_lights.size()) +
                    " punctual light(s) light nothing (BSDF sampling cannot hit a point, spot or directional light)"});
  refuse_frame_over_memory(scene.width, scene.height, aov);

  // No output may replace an input or another output; then claim the
  // outputs before rendering: an unwritable path fails now, not after an
  // hour of work.
  const std::filesystem::path calibration_path =
      options.calibration.empty() ? default_calibration_path() : std::filesystem::path(options.calibration);
  const std::filesystem::path out_path = output_path(options, scene, writer);
  std::vector<std::filesystem::path> inputs = scene.inputs;
  inputs.push_back(calibration_path);
  const bool checkpoints = options.checkpoint_every_given || options.resume;
  if (checkpoints && (options.out == "-" || leads_to_stream(out_path.string())))
    throw InputError(std::string(options.resume ? "--resume" : "--checkpoint-every") +
                     ": needs the image to be a file (its checkpoint is kept beside it)");
  const std::filesystem::path checkpoint_file = checkpoint_path(out_path);
  refuse_outputs_over_inputs({out_path, options.report, options.cell_map, options.preview,
                              checkpoints ? checkpoint_file.string() : std::string()},
                             inputs);
  // Claimed by the writer alone; every process waits for its verdict.
  ClaimedOutputs claimed = agreed_step(split, [&] {
    ClaimedOutputs c;
    if (!writer) return c;
    if (checkpoints) refuse_checkpoint_path(checkpoint_file, options.resume);
    c.image = std::make_unique<AtomicOutput>(out_path, OutputKind::image);
    c.report = optional_output(options.report);
    c.cell_map = optional_output(options.cell_map, OutputKind::image);
    c.preview = optional_output(options.preview, OutputKind::image);
    return c;
  });
  const auto& report_out = claimed.report;
  const auto& cell_map_out = claimed.cell_map;
  const auto& preview_out = claimed.preview;
  // The calibration too is read now: a bad file must not cost a finished render.
  // One left beside the binary by an older Kappa is set aside with a word (a
  // rebuild must not stop every render); one named with --calibration is
  // refused.
  std::optional<Calibration> calibration = agreed_step(split, [&] {
    std::optional<Calibration> c = read_calibration_file(calibration_path, !options.calibration.empty());
    // Without a file, the constants fitted on the project's machines: the
    // report's predictions and --grid-res model work on a fresh clone, silently.
    if (!c) c = builtin_calibration();
    return c;
  });

  const auto build_start = std::chrono::steady_clock::now();
  AccelRequest request;
  request.accel = options.accel;
  request.build = options.build;
  request.build.filtered = scene.has_cutouts();  // Embree installs its cut-out callback
  request.needs_cells = settings.stats || aov.cost || !options.cell_map.empty();
  // The frame's paths: its pixels at --spp (a budget's cap, or the default
  // 64 when a budget decides how many).
  request.frame_paths = double(scene.width) * double(scene.height) * double(options.spp);
  FrameAccelerator frame_accel = agreed_step(split, [&] {
    return with_progress(show_progress, [&](TaskProgress* progress) {
      const MemoryNeed need("building the accelerator over " + std::to_string(scene.triangles.size()) + " triangles", 0);
      if (!shared_frame || (options.accel != "auto" && !grid_by_model))
        return build_frame_accelerator(scene, settings, request, *calibration, progress);
      return build_as_the_writer_chooses(*split, scene, settings, request, *calibration, progress);
    });
  });
  std::unique_ptr<Accelerator> accel = std::move(frame_accel.accel);
  const std::optional<GridChoice>& grid_choice = frame_accel.grid_choice;
  // The writer's pilot, where one ran, orders the first pass's tiles.
  if (split && writer) split->predict_tile_costs(frame_accel.tile_costs);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();

  const int threads = active_threads();

  const MemoryNeed frame_need("rendering the " + std::to_string(scene.width) + "x" + std::to_string(scene.height) +
                                  " frame", 0);
  // The machine's speed just before and just after the frame, beside the
  // cost model's predictions in the report (stats/machine_probe.h): only
  // where the report has them, about 10 ms each.
  const bool probe = writer && report_out && settings.stats;
  double probe_before_s = 0;
  // The last step every process agrees on before the tiles go out (the
  // probe in it: should it fail, every rank stops, none waits).
  Film film = agreed_step(split, [&] {
    if (probe) probe_before_s = machine_probe().seconds;
    return Film(scene.width, scene.height, aov);
  });
  if (split) split->rendering_begins();
  ProgressBar bar(show_progress);
  begin_phase(bar.task(), "rendering", 0);
  RenderResult result;
  bool interrupted = false;
  // Alive until the outputs are committed: a first Ctrl-C while a finished
  // budgeted render writes its outputs lets them be written too.
  std::optional<InterruptGuard> guard;
  if (budget.any() || checkpoints) {
    // Passes until a budget is spent; Ctrl-C abandons the pass in progress
    // and keeps the completed ones (interrupt.h). The progress line shows
    // the budget's share spent: the time's, or the estimate's (which falls
    // as 1/spp, so target/estimate is the share of the samples taken).
    PassPlanner planner(budget, [] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    });
    // Ranks sharing a frame stop together or not at all: under kappa-mpi,
    // Ctrl-C ends the job (mpirun's), with nothing written.
    if (!shared_frame) guard.emplace();
    // Test hook: tests that interrupt a render read there how many passes
    // are complete, instead of guessing from the time.
    const char* passes_file = writer ? std::getenv("KAPPA_TEST_PASSES_FILE") : nullptr;
    const auto note_passes = [passes_file](int passes) {
      if (passes_file) std::ofstream(passes_file) << passes << "\n";
    };
    note_passes(0);
    PassControl control{&planner, guard ? &guard->flag() : nullptr, [&](const FrameState& state, int passes) {
                          note_passes(passes);
                          if (TaskProgress* task = bar.task()) task->rename(pass_text(state, passes, budget));
                          double share = budget.time_s > 0 ? planner.elapsed() / budget.time_s : 0;
                          if (budget.target_relmse > 0 && state.spp >= kFirstRelmseCheckSpp && state.relmse_estimate > 0)
                            share = std::max(share, budget.target_relmse / state.relmse_estimate);
                          bar.update(std::size_t(std::clamp(share, 0.0, 1.0) * 1000), 1000);
}};
    // --resume: the checkpoint, read by the writer and sent to the others
    // (which may not see its folder), for the settings of this render.
    const nlohmann::ordered_json fingerprint = checkpoint_settings(options, scene, *accel, budget);
    std::optional<FrameProgress> resumed;
    if (options.resume) {
      resumed = agreed_step(split, [&] {
        std::string bytes;
        std::exception_ptr failure;  // the writer's, after it has sent the others nothing
        try {
          if (writer) bytes = read_bytes(checkpoint_file, "--resume");
        } catch (...) {
          failure = std::current_exception();
        }
        if (shared_frame) bytes = split->writer_text(bytes);
        if (failure) std::rethrow_exception(failure);
        if (bytes.empty() && !writer) throw InputError("--resume: the writing rank read no checkpoint");
        return decode_checkpoint(bytes, checkpoint_file.string(), fingerprint, film.pixels(),
                                 aov.albedo || aov.normal || aov.depth || aov.cost);
      });
      if (!writer) {  // the counts are the writer's to add, once
        resumed->rays = resumed->nonfinite = 0;
        resumed->counters.clear();
      }
      control.resume = &*resumed;
    }
    // --checkpoint-every: the completed passes, saved by the writer when the
    // time has come since the last (or the start), beside the image.
    int saved = 0;
    if (options.checkpoint_every_given) {
      auto last = std::chrono::steady_clock::now();
      control.checkpoint_due = [&, last]() mutable {
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last).count() < budget.longest_pass_s) return false;
        last = now;
        return true;
      };
      control.checkpoint = [&](const FrameProgress& progress) {
        if (!writer) return;
        try {
          AtomicOutput out(checkpoint_file, OutputKind::text);
          write_temporary(out, encode_checkpoint(fingerprint, progress));
          out.commit();
          ++saved;
        } catch (const std::exception& e) {
          warning_log().add(checkpoint_file.string() + ": checkpoint not saved, the render goes on: " + e.what());
        }
      };
    }
    settings.passes = &control;
    settings.tiles = split;  // with one process too: the report's mpi section
    result = render(scene, *accel, settings, film);
    result.checkpoints_saved = saved;
    result.resumed_passes = resumed ? resumed->passes : 0;
    result.resumed_rays = resumed ? resumed->rays : 0;
    interrupted = result.interrupted || (guard && guard->interrupted());
    if (interrupted && !result.interrupted) {
      // Ctrl-C after the last pass's last sample: its passes are complete,
      // but the run was interrupted, and the report says so.
      result.interrupted = true;
      result.stop_reason = "interrupted";
    }
  } else {
    settings.tiles = split;  // with one process too: the report's mpi section
    result = render(scene, *accel, settings, film, [&bar](std::size_t done, std::size_t total) { bar.update(done, total); });
  }
  bar.finish();
  result.probe_before_s = probe_before_s;
  if (probe) result.probe_after_s = machine_probe().seconds;
  if (interrupted && result.passes == 0) {
    std::fprintf(stderr, "kappa: interrupted before a pass was complete: nothing written\n");
    return kInterruptedExitCode;  // the outputs' temporaries are removed as they go out of scope
  }
  if (result.nonfinite_samples > 0)
    warning_log().add(std::to_string(result.nonfinite_samples) +
                      " samples had non-finite radiance and were dropped from their pixels");
  if (!result.stats_note.empty()) warning_log().add(result.stats_note);
  if (!writer) return 0;  // the writer has this process's pixels and counts
  AtomicOutput& output = *claimed.image;

  // Every setting that changes the image, from one record, in both the EXR
  // header and the report; then what the run measured.
  const RenderRecord record = render_record(options, scene, resolution_text(*accel), result.spp, budget);
  Metadata metadata = {{"Software", std::string("Kappa ") + version_string()},
                       {"kappa:version", std::string(version_string())}};
  for (const auto& [key, value] : record)
    std::visit(
        [&, k = "kappa:" + key](const auto& v) {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, bool>) metadata.emplace_back(k, int(v));
          else metadata.emplace_back(k, v);
        },
        value);
  metadata.insert(metadata.end(), {{"kappa:threads", threads},
                                   {"kappa:render_time_s", result.seconds},
                                   {"kappa:load_s", scene.load_s},
                                   {"kappa:accel_build_s", build_s},
                                   {"kappa:rays", double(result.rays)}});
  write_exr(output.temp_path(), film, metadata, output.target());
  nlohmann::ordered_json report =
      render_report(scene, *accel,
                    FrameFacts{scene.width, scene.height, result.spp, threads, options.seed, budget.time_s,
                               budget.target_relmse},
                    result, calibration, to_json(record));
  if (grid_choice) report["grid_choice"] = grid_choice->report;
  if (!frame_accel.accel_choice.is_null()) report["accel_choice"] = frame_accel.accel_choice;
  if (split && !split->shares().empty()) report["mpi"] = mpi_section(split->shares(), split->tile_seconds(), split->first_pass_costs());

  if (cell_map_out && result.counters) {
    if (result.counters->classes[0].per_cell()) {
      write_cell_map(*cell_map_out, *accel->cells(), *result.counters, options.cell_map_axis[0] - 'x');
    } else {
      warning_log().add("--cell-map skipped: per-cell statistics were refused for this frame");
    }
  }
  {
    // The image and the report land together: a signal during the renames
    // waits until both are done (and then ends the process as it would have).
    report["warnings"] = warnings_section(warning_log().kinds());
    const std::string report_text = report.dump(2) + "\n";
    if (report_out) write_temporary(*report_out, report_text);
    if (preview_out) write_preview(*preview_out, film, float(options.preview_exposure));
    const SignalsHeld held;
    output.commit();
    if (preview_out) preview_out->commit();
    if (report_out) report_out->commit();
  }
  // A finished render's checkpoint has served; an interrupted one's is kept
  // (its image has the completed passes, the checkpoint the passes to go on from).
  // The writer's alone: it saved it, and only once its outputs are committed.
  // A resumed render that added no pass (given less than the checkpoint's
  // settings allowed, or none left) keeps it: its passes may yet be wanted.
  const bool added_none = options.resume && result.passes <= result.resumed_passes;
  if (checkpoints && !interrupted && writer && added_none)
    warning_log().add(checkpoint_file.string() + ": the resumed render added no pass to the checkpoint's " +
                      std::to_string(result.resumed_passes) + " (a time budget spent, or not given again?): it is kept");
  if (checkpoints && !interrupted && writer && !added_none) {
    std::error_code ec;
    std::filesystem::remove(checkpoint_file, ec);
    if (ec) warning_log().add(checkpoint_file.string() + ": the finished render's checkpoint was not removed: " + ec.message());
  }

  if (!options.quiet) {
    if (const CellLayout* cells = accel->cells()) {
      const nlohmann::ordered_json own = report.value(std::string(accel->name()), nlohmann::ordered_json::object());
      std::fprintf(stderr, "kappa: %s %s, N_c %llu, N %s, theta_tot %s, %s, built in %.3f s%s%s\n",
                   std::string(accel->name()).c_str(), cells->resolution_text().c_str(),
                   static_cast<unsigned long long>(cells->cell_count()), own.value("N", nlohmann::ordered_json()).dump().c_str(),
                   own.value("theta_tot", nlohmann::ordered_json()).dump().c_str(), byte_size(accel->bytes()).c_str(),
                   accel->build_s(), grid_choice ? ", " : "", grid_choice ? grid_choice->summary.c_str() : "");
    }
    std::fprintf(stderr, "kappa: %s %dx%d, %d spp, %s, %d threads: %.2f s, %llu rays, %.3g Mrays/s%s -> %s\n",
                 scene.name.c_str(), scene.width, scene.height, result.spp, std::string(accel->name()).c_str(), threads,
                 result.seconds, static_cast<unsigned long long>(result.rays),
                 result.seconds > 0 ? double(result.rays - result.resumed_rays) / result.seconds * 1e-6 : 0.0,
                 traversal_summary(report["cost"]).c_str(), output.target().c_str());
    std::fflush(stderr);
    std::fputs(stats_table(report).c_str(), stdout);
  }
  if (interrupted) {
    std::fprintf(stderr, "kappa: interrupted: wrote the %d completed passes (%d spp)\n", result.passes, result.spp);
    return kInterruptedExitCode;
  }
  return 0;
}

}  // namespace kappa
