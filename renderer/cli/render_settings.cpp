#include "renderer/cli/render_settings.h"

#include <charconv>

#include "core/error.h"
#include "renderer/render/sampler_kind.h"
#include "renderer/render/statistics_built.h"

namespace kappa {

std::uint64_t parse_cell_sample(const std::string& text) {
  if (text == "auto") return 0;
  std::uint64_t n = 0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto [end, ec] = std::from_chars(first, last, n);
  if (ec != std::errc() || end != last || n < 1 || n > (std::uint64_t(1) << 20))
    throw InputError("--cell-sample: '" + text + "' is neither auto nor a whole number from 1 to 1048576");
  return n;
}

RenderSettings render_settings_of(const RenderOptions& options, const AovSelection& aov) {
  if (options.stats == "on" && !statistics_built())
    throw InputError("--stats on: this is kappa-nostats, built without statistics (the overhead baseline); use kappa");
  RenderSettings settings;
  settings.spp = options.spp;
  settings.max_depth = options.max_depth;
  settings.rr_depth = options.no_rr ? -1 : options.rr_depth;
  settings.seed = options.seed;
  settings.sampler = parse_sampler(options.sampler);
  settings.light_sampling = parse_light_sampling(options.light_sampling);
  settings.specialise = options.specialise == "on";
  settings.occluder_cache = options.occluder_cache == "on";
  settings.aov = aov;
  settings.stats = options.stats == "on";
  settings.stats_max_bytes = options.build.max_bytes();
  settings.cell_sample = parse_cell_sample(options.cell_sample);
  return settings;
}

}  // namespace kappa
