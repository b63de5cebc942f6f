#include "factory.h"

#include <stdexcept>

#include "core/input_error.h"
#include "embree.h"
#include "grid.h"
#include "grid2.h"
#include "naive.h"

namespace kappa {

std::uint64_t AccelOptions::max_bytes() const { return grid_max_bytes > 0 ? grid_max_bytes : default_grid_max_bytes(); }

GridOptions grid_options(const AccelOptions& options) {
  if (options.grid_res == "model")
    throw InputError("--grid-res model: only kappa render chooses by the cost model (from a pilot of its frame); "
                     "use auto, N or NxNxN here");
  GridOptions grid;
  grid.resolution = parse_grid_resolution(options.grid_res);
  if (options.grid_density > 0) grid.density = options.grid_density;
  grid.max_bytes = options.max_bytes();
  return grid;
}

Grid2Options grid2_options(const AccelOptions& options) {
  Grid2Options grid2;
  if (options.grid2_top_density > 0) grid2.top_density = options.grid2_top_density;
  if (options.grid2_leaf_density > 0) grid2.leaf_density = options.grid2_leaf_density;
  grid2.max_bytes = options.max_bytes();
  return grid2;
}

std::vector<std::string> accelerator_names() { return {"embree", "embree-fast", "grid", "grid2", "naive"}; }

std::unique_ptr<Accelerator> make_accelerator(std::string_view name, std::span<const Triangle> triangles,
                                              const AccelOptions& options, TaskProgress* progress) {
  if (name == "naive") return std::make_unique<NaiveAccelerator>(triangles);
  if (name == "embree") return std::make_unique<EmbreeAccelerator>(triangles, progress, options.filtered);
  if (name == "embree-fast")
    return std::make_unique<EmbreeAccelerator>(triangles, progress, options.filtered, EmbreeMode::fast);
  if (name == "grid") return std::make_unique<UniformGrid>(triangles, grid_options(options), progress);
  if (name == "grid2") return std::make_unique<NestedGrid>(triangles, grid2_options(options), progress);
  throw InputError("unknown accelerator '" + std::string(name) + "'");
}

}  // namespace kappa
