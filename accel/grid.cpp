// The grid's virtual queries: the walk of grid_traverse.h with nothing recorded.
#include "grid.h"

#include "grid_traverse.h"

namespace kappa {

namespace {
/// Records nothing: every call compiles away.
struct NothingRecorded {
  void cell(std::uint64_t, std::uint32_t) {}
  void test() {}
  void skip() {}
  void hit() {}
};
}  // namespace

std::optional<Hit> UniformGrid::closest_hit(const Ray& ray) const {
  NothingRecorded none;
  return closest_hit(ray, none);
}

bool UniformGrid::any_hit(const Ray& ray) const {
  NothingRecorded none;
  return any_hit(ray, none);
}

}  // namespace kappa
