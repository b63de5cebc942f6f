#include "renderer/commands/converge_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "accel/factory.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/thread_limit.h"
#include "core/warning_log.h"
#include "renderer/cli/accel_flags.h"
#include "renderer/cli/command_line.h"
#include "renderer/cli/progress.h"
#include "renderer/cli/render_settings.h"
#include "renderer/converge/curves.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/exr_input.h"
#include "renderer/io/exr_output.h"
#include "renderer/io/output_guard.h"
#include "renderer/io/plot_script.h"
#include "renderer/render/frame_accumulator.h"
#include "renderer/render/integrator.h"
#include "renderer/render/sampler_kind.h"
#include "renderer/report/render_record.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/version.h"
#include "stats/calibration.h"

#ifndef KAPPA_TOOLS_DIR
#define KAPPA_TOOLS_DIR "tools"
#endif

namespace kappa {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// One curve's settings: the defaults, or the defaults with one option changed.
struct Setting {
  std::string name, key, value;
  RenderOptions options;
};

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, by)) parts.push_back(part);
  if (!text.empty() && text.back() == by) parts.emplace_back();
  return parts;
}

/// --vary KEY=V1,V2 ...: one setting per value, each key alone (one factor
/// at a time); the defaults alone without --vary.
std::vector<Setting> settings_of(const ConvergeOptions& options) {
  std::vector<Setting> settings;
  for (const std::string& vary : options.vary) {
    const std::size_t eq = vary.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == vary.size())
      throw InputError("--vary: '" + vary + "' is not KEY=V1,V2,...");
    std::string key = vary.substr(0, eq);
    if (key.rfind("--", 0) == 0) key = key.substr(2);
    if (key == "width" || key == "height")
      throw InputError("--vary " + key + ": the film's size is the reference's; set it with --" + key);
    for (const std::string& value : split(vary.substr(eq + 1), ',')) {
      if (value.empty()) throw InputError("--vary: '" + vary + "' has an empty value");
      settings.push_back({key + "=" + value, key, value, vary_render_option(options.render, key, value)});
    }
  }
  if (settings.empty()) settings.push_back({"defaults", "", "", options.render});
  return settings;
}

struct Reference {
  ReferenceImage image;
  std::string path;
  bool self_made = false;
  int spp = 0;
  std::uint64_t seed = 0;
  double relmse_floor = -1;  ///< from its variance channels; < 0 without them
};

/// Renders `options` at `spp` into a film, single pass.
RenderResult render_once(const Scene& scene, const RenderOptions& options, int spp, const AovSelection& aov, Film& film,
                         bool show_progress) {
  const ThreadLimit limit(options.threads);
  AccelOptions build = options.build;
  build.filtered = scene.has_cutouts();
  const auto accel = make_accelerator(options.accel, scene.triangles, build);
  RenderSettings settings = render_settings_of(options, aov);
  settings.spp = spp;
  ProgressBar bar(show_progress);
  return render(scene, *accel, settings, film, [&bar](std::size_t done, std::size_t total) { bar.update(done, total); });
}

/// What identifies this binary's images: its version, and for a build from an
/// edited tree ("-dirty") the executable's size and time too, so that a
/// changed integrator does not reuse an older reference.
std::string binary_identity() {
  std::string id = version_string();
  if (id.find("dirty") != std::string::npos) {
    std::error_code ec;
    if (const auto exe = executable_path(); !exe.empty()) {
      const auto size = std::filesystem::file_size(exe, ec);
      const auto time = std::filesystem::last_write_time(exe, ec).time_since_epoch().count();
      id += "|" + std::to_string(size) + "|" + std::to_string(time);
    }
  }
  return id;
}

/// The reference: --reference, or one rendered at 16x the largest spp with a
/// seed no curve uses, cached (--cache) under a key of everything that
/// changes it.
Reference reference_for(const ConvergeOptions& options, const std::vector<Setting>& settings, const Scene& scene,
                        bool show_progress) {
  Reference ref;
  if (!options.reference.empty()) {
    ref.image = read_reference(options.reference, FilmSize{scene.width, scene.height});
    ref.path = options.reference;
  } else {
    const RenderOptions& base = options.render;
    ref.self_made = true;
    ref.spp = 16 * options.spp.back();
    ref.seed = base.seed;
    const auto used = [&](std::uint64_t seed) {
      for (const Setting& s : settings)
        if (s.options.seed == seed) return true;
      return base.seed == seed;
    };
    while (used(ref.seed)) ref.seed = ref.seed == kMaxSeed ? 0 : ref.seed + 1;
    RenderOptions o = base;
    o.seed = ref.seed;
    o.stats = "off";
    std::ostringstream key;
    key << input_hash(scene) << '|' << scene.width << 'x' << scene.height << '|' << ref.spp << '|' << ref.seed << '|'
        << o.accel << '|' << o.sampler << '|' << o.light_sampling << '|' << o.max_depth << '|'
        << (o.no_rr ? -1 : o.rr_depth) << '|' << binary_identity();
    const std::filesystem::path exe = executable_path();
    const std::filesystem::path dir = !options.cache.empty() ? std::filesystem::path(options.cache)
                                      : exe.empty()          ? std::filesystem::path("references")
                                                             : exe.parent_path() / "references";
    const std::filesystem::path file = dir / (scene.name + "-" + hex16(fnv1a64(key.str())) + ".exr");
    ref.path = file.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
      std::fprintf(stderr, "kappa: converge: rendering the reference, %d spp with seed %llu ...\n", ref.spp,
                   static_cast<unsigned long long>(ref.seed));
      std::filesystem::create_directories(dir, ec);
      if (ec) throw InputError(dir.string() + ": cannot create the reference cache: " + ec.message());
      AtomicOutput out(file, OutputKind::image);
      AovSelection aov;
      aov.variance = true;
      Film film(scene.width, scene.height, aov);
      const RenderResult r = render_once(scene, o, ref.spp, aov, film, show_progress);
      write_exr(out.temp_path(), film,
                {{"Software", std::string("Kappa ") + version_string()},
                 {"kappa:spp", ref.spp},
                 {"kappa:seed", double(ref.seed)},
                 {"kappa:render_time_s", r.seconds}});
      out.commit();
      std::fprintf(stderr, "kappa: converge: reference rendered in %.1f s\n", r.seconds);
    }
    std::fprintf(stderr,
                 "kappa: converge: reference %s (%d spp, seed %llu): made by Kappa itself, it cannot reveal Kappa's "
                 "own bias; pass --reference with another renderer's image for that\n",
                 file.c_str(), ref.spp, static_cast<unsigned long long>(ref.seed));
    ref.image = read_reference(file, FilmSize{scene.width, scene.height});
  }
  if (!ref.image.variance.empty()) ref.relmse_floor = relmse_floor(ref.image.variance, ref.image.rgb);
  return ref;
}

/// One setting's curve: a progressive render whose passes end at every
/// sample count asked for, the film compared with the reference after each
/// (that comparison's time left out); a sampler that needs the total renders
/// each sample count on its own.
ConvergeCurve curve_of(const Setting& setting, const Scene& scene, const std::vector<int>& spp, const Reference& ref,
                       bool quiet) {
  ConvergeCurve curve{setting.name, setting.key, setting.value, "", {}};
  const RenderOptions& o = setting.options;
  const ThreadLimit limit(o.threads);
  AccelOptions build = o.build;
  build.filtered = scene.has_cutouts();
  const auto accel = make_accelerator(o.accel, scene.triangles, build);
  RenderSettings settings = render_settings_of(o, AovSelection{});
  const auto record = [&](int n, double time_s, const Film& film) {
    curve.points.push_back({n, time_s, image_error(film.rgb, ref.image.rgb)});
    if (!quiet)
      std::fprintf(stderr, "kappa: converge: %s: %d spp, %.3f s, relMSE %.5g\n", setting.name.c_str(), n, time_s,
                   curve.points.back().error.relmse);
  };
  if (needs_total(settings.sampler)) {
    for (int n : spp) {
      Film film(scene.width, scene.height, AovSelection{});
      settings.spp = n;
      const RenderResult r = render(scene, *accel, settings, film);
      curve.path_variant = r.path_variant;
      record(n, r.seconds, film);
    }
    return curve;
  }
  Budget budget;
  budget.spp_cap = spp.back();
  budget.checkpoints = spp;
  PassPlanner planner(budget, [] { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); });
  Film film(scene.width, scene.height, AovSelection{});
  Clock::time_point start;
  double paused = 0;  // seconds spent comparing, not rendering
  PassControl control{&planner, nullptr, [&](const FrameState& state, int) {
                        const double t = seconds_since(start) - paused;
                        if (std::find(spp.begin(), spp.end(), state.spp) == spp.end()) return;
                        const auto compare_start = Clock::now();
                        record(state.spp, t, film);
                        paused += seconds_since(compare_start);
                      }};
  settings.passes = &control;
  start = Clock::now();
  const RenderResult r = render(scene, *accel, settings, film);
  curve.path_variant = r.path_variant;
  return curve;
}

nlohmann::ordered_json to_json(const ConvergeCurve& c, double t_equal) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const ConvergePoint& p : c.points)
    points.push_back({{"spp", p.spp},
                      {"time_s", p.time_s},
                      {"rmse", p.error.rmse},
                      {"relmse", p.error.relmse},
                      {"bias", p.error.bias},
                      {"efficiency", p.efficiency()}});
  bool extrapolated = false;
  const double at = relmse_at_time(c.points, t_equal, &extrapolated);
  return {{"name", c.name},
          {"key", c.key.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(c.key)},
          {"value", c.value.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(c.value)},
          {"path_variant", c.path_variant},
          {"relmse_at_equal_time", at},
          {"efficiency_at_equal_time", at > 0 && t_equal > 0 ? 1.0 / (at * t_equal) : 0.0},
          {"extrapolated", extrapolated},
          {"points", points}};
}

/// The settings ranked by relMSE at equal time, best first.
std::string ranking_table(const std::vector<ConvergeCurve>& curves, const std::vector<std::size_t>& order, double t) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-4s %-28s %14s %7s %11s %14s %9s %9s\n", "rank", "setting", "relMSE", "x best",
                "efficiency", "relMSE (last)", "time", "bias");
  out += line;
  const double best = order.empty() ? 0 : relmse_at_time(curves[order[0]].points, t);
  for (std::size_t r = 0; r < order.size(); ++r) {
    const ConvergeCurve& c = curves[order[r]];
    bool extrapolated = false;
    const double at = relmse_at_time(c.points, t, &extrapolated);
    const ConvergePoint& last = c.points.back();
    char spp_text[32];
    std::snprintf(spp_text, sizeof spp_text, "@%d", last.spp);
    std::snprintf(line, sizeof line, "%-4zu %-28s %13.5g%s %7.2f %11.4g %8.5g %5s %8.3fs %+9.4f\n", r + 1, c.name.c_str(),
                  at, extrapolated ? "*" : " ", best > 0 ? at / best : 0.0, at > 0 ? 1.0 / (at * t) : 0.0,
                  last.error.relmse, spp_text, last.time_s, last.error.bias);
    out += line;
  }
  return out;
}

}  // namespace

int run_converge(const ConvergeOptions& options) {
  std::vector<int> spp = options.spp;
  if (spp.empty()) throw InputError("--spp: give at least one sample count");
  for (std::size_t i = 1; i < spp.size(); ++i)
    if (spp[i] <= spp[i - 1]) throw InputError("--spp: the sample counts must be ascending, without repeats");
  const std::vector<Setting> settings = settings_of(options);
  for (const Setting& s : settings) (void)render_settings_of(s.options, AovSelection{});  // refused before loading
  if (!options.plot.empty() && std::filesystem::path(options.plot).extension() != ".png")
    throw InputError("--plot: '" + options.plot + "' must end in .png");

  const RenderOptions& base = options.render;
  const bool show_progress = progress_wanted(base.quiet);
  Scene scene = [&] {
    const ThreadLimit limit(base.threads);
    Warnings warnings;
    Scene s = with_progress(show_progress, [&](TaskProgress* p) { return load_scene(base.scene, warnings, p); });
    print_warnings(warnings);
    return s;
  }();
  apply_view(scene, base.camera, base.width, base.height);
  refuse_frame_over_memory(scene.width, scene.height, AovSelection{.variance = true});  // the reference's

  std::vector<std::filesystem::path> inputs = scene.inputs;
  if (!options.reference.empty()) inputs.push_back(options.reference);
  refuse_outputs_over_inputs({options.json, options.plot}, inputs);
  JsonAndPlot outputs(options.json, options.plot, "converge_plot.py");  // claimed, and matplotlib checked, now

  const Reference ref = reference_for(options, settings, scene, show_progress);
  std::vector<ConvergeCurve> curves;
  for (const Setting& s : settings) curves.push_back(curve_of(s, scene, spp, ref, base.quiet));

  const double t = options.equal_time_s > 0 ? options.equal_time_s : equal_time(curves);
  std::vector<std::size_t> order(curves.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return relmse_at_time(curves[a].points, t) < relmse_at_time(curves[b].points, t);
  });

  nlohmann::ordered_json j;
  j["kappa_version"] = version_string();
  j["scene"] = scene.source.string();
  j["scene_name"] = scene.name;
  j["width"] = scene.width;
  j["height"] = scene.height;
  j["threads"] = [&] {
    const ThreadLimit limit(base.threads);
    return active_threads();
  }();
  j["reference"] = {{"path", ref.path},
                    {"self_made", ref.self_made},
                    {"spp", ref.self_made ? nlohmann::ordered_json(ref.spp) : nlohmann::ordered_json()},
                    {"seed", ref.self_made ? nlohmann::ordered_json(double(ref.seed)) : nlohmann::ordered_json()},
                    {"relmse_floor", ref.relmse_floor >= 0 ? nlohmann::ordered_json(ref.relmse_floor)
                                                           : nlohmann::ordered_json()}};
  j["equal_time_s"] = t;
  nlohmann::ordered_json ranking = nlohmann::ordered_json::array();
  for (std::size_t i : order) ranking.push_back(curves[i].name);
  j["ranking"] = ranking;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ConvergeCurve& c : curves) list.push_back(to_json(c, t));
  j["settings"] = list;
  outputs.finish(j.dump(2) + "\n");

  std::printf("converge: %s %dx%d, %d thread(s); reference %s%s\n", scene.name.c_str(), scene.width, scene.height,
              j["threads"].get<int>(), ref.path.c_str(), ref.self_made ? " (self-made)" : "");
  if (ref.relmse_floor >= 0) std::printf("the reference's own noise adds about %.3g to every relMSE\n", ref.relmse_floor);
  std::printf("ranked by relMSE at %.3f s, %s (* extrapolated as 1/time):\n", t,
              options.equal_time_s > 0 ? "as asked" : "the longest time every setting reached");
  std::fputs(ranking_table(curves, order, t).c_str(), stdout);
  return 0;
}

}  // namespace kappa
