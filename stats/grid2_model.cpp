#include "grid2_model.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

#include "accel/grid2_traverse.h"
#include "core/parallel.h"

namespace kappa {
namespace {

/// Adds each walk's counts into one sum (the recorder protocol of
/// accel/recorder.h; cells, tests and hits are in the counts it finishes with).
struct SumCounts {
  WalkCounts* sum;
  template <class BoxFn>
  void cell(std::uint64_t, int, BoxFn&&) {}
  void test() {}
  void hit() {}
  void finish(const WalkCounts& c, const WalkSegment&) {
    sum->cells += c.cells;
    sum->occupied += c.occupied;
    sum->tests += c.tests;
    sum->skips += c.skips;
  }
};

struct ClassSums {
  std::array<WalkCounts, kRenderClasses> walks{};
  std::array<std::uint64_t, kRenderClasses> rays{}, hits{};
};

}  // namespace

std::array<QueryLoad, kRenderClasses> count_segments(const NestedGrid& grid, std::span<const PilotSegment> segments) {
  tbb::enumerable_thread_specific<ClassSums> per_thread;
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 1024), [&](const auto& range) {
    ClassSums& sums = per_thread.local();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const PilotSegment& s = segments[i];
      SumCounts tally{&sums.walks[s.ray_class]};
      const bool hit = s.ray_class == kShadow ? grid.any_hit(s.ray, tally) : grid.closest_hit(s.ray, tally).has_value();
      ++sums.rays[s.ray_class];
      sums.hits[s.ray_class] += hit;
    }
  });
  ClassSums all;
  per_thread.combine_each([&](const ClassSums& t) {
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      all.walks[k].cells += t.walks[k].cells;
      all.walks[k].occupied += t.walks[k].occupied;
      all.walks[k].tests += t.walks[k].tests;
      all.walks[k].skips += t.walks[k].skips;
      all.rays[k] += t.rays[k];
      all.hits[k] += t.hits[k];
    }
  });
  const double working_set = double(grid.bytes()) + double(grid.info().N * sizeof(Triangle));
  std::array<QueryLoad, kRenderClasses> loads{};
  for (std::size_t k = 0; k < kRenderClasses; ++k)
    loads[k] = QueryLoad{RenderClass(k),           double(all.rays[k]),        double(all.walks[k].cells),
                         double(all.walks[k].occupied), double(all.walks[k].tests), double(all.walks[k].skips),
                         double(all.hits[k]),      working_set};
  return loads;
}

Grid2Prediction predict_grid2(const NestedGrid& grid, std::span<const PilotSegment> segments, const ChoiceSettings& settings,
                              const Grid2Model& model) {
  Grid2Prediction p;
  const auto loads = count_segments(grid, segments);
  // Thread-seconds by the model (as calibrate times them), shared by the
  // frame's threads; the build model gives its wall time.
  for (std::size_t k = 0; k < kRenderClasses; ++k)
    p.traversal_s += model.traversal.seconds(loads[k]) * settings.rays_scale[k] / double(std::max(1, settings.threads));
  const Grid2Info& info = grid.info();
  p.build_s = model.build.seconds(double(info.N), double(info.theta_tot), double(info.leaves), settings.threads);
  return p;
}

nlohmann::ordered_json to_json(const Grid2Model& model) {
  return {{"traversal", to_json(model.traversal)}, {"build", to_json(model.build)}};
}

bool from_json(const nlohmann::json& j, Grid2Model& model) {
  if (!j.is_object()) return false;
  return from_json(j.value("traversal", nlohmann::json()), model.traversal) && model.traversal.form == ModelForm::extended &&
         from_json(j.value("build", nlohmann::json()), model.build);
}

}  // namespace kappa
