#include "accel.h"

#include <stdexcept>

#include "embree.h"
#include "grid.h"
#include "naive.h"

namespace kappa {

void Accelerator::closest_hit(std::span<const Ray> rays, std::span<Hit> hits) const {
  for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = closest_hit(rays[i]).value_or(Hit{});
}

void Accelerator::any_hit(std::span<const Ray> rays, std::span<bool> occluded) const {
  for (std::size_t i = 0; i < rays.size(); ++i) occluded[i] = any_hit(rays[i]);
}

std::vector<std::string> accelerator_names() { return {"embree", "grid", "naive"}; }

std::unique_ptr<Accelerator> make_accelerator(std::string_view name, std::span<const Triangle> triangles,
                                              const AccelOptions& options) {
  if (name == "naive") return std::make_unique<NaiveAccelerator>(triangles);
  if (name == "embree") return std::make_unique<EmbreeAccelerator>(triangles);
  if (name == "grid") {
    GridOptions grid;
    grid.resolution = parse_grid_resolution(options.grid_res);
    if (options.grid_density > 0) grid.density = options.grid_density;
    if (options.grid_max_bytes > 0) grid.max_bytes = options.grid_max_bytes;
    return std::make_unique<UniformGrid>(triangles, grid);
  }
  throw std::invalid_argument("unknown accelerator '" + std::string(name) + "'");
}

}  // namespace kappa
