// The parts every report shares, written once for `kappa render` and `kappa
// cast` (keys in stats/README.md): the header, the "stats" block that says how
// the counting ran, and what any accelerator reports about a class of rays.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "accel/accel.h"
#include "core/warning_log.h"
#include "renderer/render/frame_split.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// The scene's images: texture maps, cut-out masks, the environment image,
/// the texture cache's statistics (OpenImageIO's own) and whether the
/// OpenImageIO module was loaded at all.
nlohmann::ordered_json images_section(const Scene& scene);

/// A frame shared by processes (kappa-mpi): {ranks, threads_per_rank (a
/// number, or one per rank where they differ), per_rank [{rank, host,
/// threads, tiles, rays, time_s}], imbalance (the slowest rank's time over
/// the mean, 1 when even; null with no time), tile_seconds [each tile's,
/// by tile], first_pass_order ("pilot" or "tiles"), tile_predicted [each
/// tile's cost predicted from the pilot, by tile; null without one]}.
nlohmann::ordered_json mpi_section(const std::vector<ProcessShare>& shares, const std::vector<double>& tile_seconds,
                                   const std::vector<double>& tile_predicted);

/// The run's warnings by kind: [{kind, count, first}], in the order first
/// seen (core/warning_log.h); the terminal showed only the first few of each.
nlohmann::ordered_json warnings_section(const std::vector<WarningKind>& kinds);

/// schema_version, kappa_version, scene and accel: the keys every report starts with.
nlohmann::ordered_json report_header(const Scene& scene, const Accelerator& accel);

/// "stats": {"per_cell", and "cell_sample" when given}, and "stats_note" when
/// per-cell counters were refused (`note` says why).
void add_stats_block(nlohmann::ordered_json& report, bool per_cell, std::optional<std::uint64_t> cell_sample,
                     const std::string& note);

/// One class of rays through an accelerator without cell counters: count,
/// hit_fraction (null without rays) and time_s.
/// `alpha_tests`: the cut-out lookups of the class's queries (0 without cut-outs).
nlohmann::ordered_json any_accel_class_section(std::uint64_t rays, std::uint64_t hits, double seconds,
                                               std::uint64_t alpha_tests = 0);

}  // namespace kappa
