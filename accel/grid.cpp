// The grid's virtual queries: the walk of grid_traverse.h with nothing recorded.
#include "grid.h"

#include "grid_traverse.h"

namespace kappa {

std::optional<Hit> UniformGrid::closest_hit(const Ray& ray) const {
  NoRecorder none;
  return closest_hit(ray, none);
}

bool UniformGrid::any_hit(const Ray& ray) const {
  NoRecorder none;
  return any_hit(ray, none);
}

std::optional<Hit> UniformGrid::closest_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  NoRecorder none;
  return closest_hit(ray, none, filter);
}

bool UniformGrid::any_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  NoRecorder none;
  return any_hit(ray, none, filter);
}

}  // namespace kappa
