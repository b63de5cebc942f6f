// Accelerators by name: the names --accel accepts, the build settings the
// command line gives (--grid-res, --grid-density, --grid-max-bytes), and the
// one place that builds an accelerator from them.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel.h"
#include "core/task_progress.h"
#include "grid.h"
#include "grid2.h"

namespace kappa {

/// Build settings of the accelerators that have any: what --grid-res,
/// --grid-density and --grid-max-bytes set, for every command alike.
struct AccelOptions {
  std::string grid_res = "auto";  ///< "auto", "N" or "NxNxN"; "model" in kappa render (renderer/render/grid_choice.h)
  double grid_density = 0;        ///< lambda in N_c = lambda * N for "auto"; 0 = the grid's default
  std::uint64_t grid_max_bytes = 0;  ///< refuse grids larger than this; 0 = the default (a quarter of RAM)
  double grid2_top_density = 0;   ///< grid2's top cells per triangle; 0 = its default
  double grid2_leaf_density = 0;  ///< grid2's leaves per triangle of a top cell; 0 = its default
  /// Queries will pass a hit filter (cut-outs): Embree installs its filter
  /// callback; the others need nothing at build time.
  bool filtered = false;

  /// grid_max_bytes, or the default when it is 0: the budget of the grid and
  /// of any per-cell counters kept beside it.
  std::uint64_t max_bytes() const;
};

/// The grid's options from the build settings, for code that builds a grid
/// directly (calibration).
GridOptions grid_options(const AccelOptions& options);

/// grid2's options from the build settings.
Grid2Options grid2_options(const AccelOptions& options);

/// The names make_accelerator accepts, for help texts and validation.
std::vector<std::string> accelerator_names();

/// Builds the accelerator called `name` over `triangles` (which must outlive
/// it). Throws InputError for an unknown name or options the
/// accelerator refuses (e.g. a grid over its memory limit).
/// Reports the build's phases to `progress`, if given.
std::unique_ptr<Accelerator> make_accelerator(std::string_view name, std::span<const Triangle> triangles,
                                              const AccelOptions& options = {}, TaskProgress* progress = nullptr);

}  // namespace kappa
