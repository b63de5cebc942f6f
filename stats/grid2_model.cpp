#include "grid2_model.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

#include "accel/grid2_traverse.h"
#include "core/parallel.h"
#include "pilot_replay.h"

namespace kappa {

std::array<QueryLoad, kRenderClasses> count_segments(const NestedGrid& grid, std::span<const PilotSegment> segments,
                                                     std::optional<double> frame_spp) {
  const double triangles = double(grid.info().N * sizeof(Triangle));
  return replay_segments(
      segments,
      [&](const PilotSegment& s, auto& recorder) {
        return s.ray_class == kShadow ? grid.any_hit(s.ray, recorder) : grid.closest_hit(s.ray, recorder).has_value();
      },
      double(grid.bytes()) + triangles, double(grid.reference_bytes()) + triangles, frame_spp);
}

Grid2Prediction predict_grid2(const NestedGrid& grid, std::span<const PilotSegment> segments, const ChoiceSettings& settings,
                              const Grid2Model& model) {
  Grid2Prediction p;
  const auto loads = count_segments(grid, segments, cold_steps_spp(model.traversal, settings.frame_spp));
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
