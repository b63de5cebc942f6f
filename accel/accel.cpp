#include "accel.h"

#include <stdexcept>

#include "naive.h"

namespace kappa {

void Accelerator::closest_hit(std::span<const Ray> rays, std::span<Hit> hits) const {
  for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = closest_hit(rays[i]).value_or(Hit{});
}

void Accelerator::any_hit(std::span<const Ray> rays, std::span<bool> occluded) const {
  for (std::size_t i = 0; i < rays.size(); ++i) occluded[i] = any_hit(rays[i]);
}

std::vector<std::string> accelerator_names() { return {"naive"}; }

std::unique_ptr<Accelerator> make_accelerator(std::string_view name, std::span<const Triangle> triangles) {
  if (name == "naive") return std::make_unique<NaiveAccelerator>(triangles);
  throw std::invalid_argument("unknown accelerator '" + std::string(name) + "'");
}

}  // namespace kappa
