// The cold steps a choice predicts a frame to make (stats/pilot_replay.h):
// the pilot's segments replayed tile by tile, the same for any thread count,
// and its camera rays' cold steps those of the frame's rather than of the
// pilot's sparser film.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/grid.h"
#include "core/thread_limit.h"
#include "renderer/render/pilot.h"
#include "renderer/scene/scene_loader.h"
#include "stats/resolution_choice.h"
#include "test_util.h"

namespace kappa {
namespace {

constexpr double kDensity = 64;  // cells a triangle: the Cornell box's walks cross many cells

GridOptions dense() {
  GridOptions o;
  o.density = kDensity;
  return o;
}

TEST(PilotReplay, ThePilotsSegmentsAndColdStepsAreTheSameForAnyThreadCount) {
  Warnings warnings;
  const Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  const UniformGrid grid(scene.triangles, dense());
  const auto pilot_at = [&](int threads) {
    const ThreadLimit limit(threads);
    return run_pilot(scene, 128, 128, 16384, grid, RenderSettings{});
  };
  const Pilot one = pilot_at(1);
  // Which thread takes which tile changes from run to run: a few runs.
  for (int run = 0; run < 4; ++run) {
    const Pilot two = pilot_at(2);
    ASSERT_EQ(one.segments.size(), two.segments.size());
    for (std::size_t i = 0; i < one.segments.size(); ++i) {
      const PilotSegment &a = one.segments[i], &b = two.segments[i];
      ASSERT_TRUE(a.tile == b.tile && a.pixel == b.pixel && a.ray_class == b.ray_class && a.ray.o == b.ray.o &&
                  a.ray.d == b.ray.d && a.t_hit == b.t_hit)
          << "run " << run << ", segment " << i << " of " << one.segments.size();
    }
  }
  const auto cold = [&](const Pilot& p, int threads) {
    const ThreadLimit limit(threads);
    std::vector<double> out;
    for (const QueryLoad& l : count_segments(grid, p.segments, std::nullopt, 16)) {
      out.push_back(l.cold_cells);
      out.push_back(l.cold_tests);
    }
    return out;
  };
  const std::vector<double> counted = cold(one, 1);
  EXPECT_EQ(counted, cold(one, 2));
  EXPECT_GT(counted[2 * kCamera], 0.0);
  EXPECT_GT(counted[2 * kShadow], 0.0);
}

TEST(PilotReplay, AModelWithoutColdTermsCountsTheSameStepsButNoColdOnes) {
  // --accel auto predicts by the extended model: the replay's table and the
  // camera rays' second walk would be work for nothing.
  EXPECT_FALSE(cold_steps_spp(extended_model(1 << 20), 16).has_value());
  EXPECT_EQ(cold_steps_spp(coherent_model(1 << 20), 16), std::optional<double>(16));

  Warnings warnings;
  const Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  const UniformGrid grid(scene.triangles, dense());
  const Pilot pilot = run_pilot(scene, 64, 64, 4096, grid, RenderSettings{});
  const auto with_cold = count_segments(grid, pilot.segments, std::nullopt, 16);
  const auto without = count_segments(grid, pilot.segments, std::nullopt, std::nullopt);
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const QueryLoad &a = with_cold[k], &b = without[k];
    EXPECT_TRUE(a.rays == b.rays && a.cells == b.cells && a.occupied == b.occupied && a.tests == b.tests &&
                a.skips == b.skips && a.hits == b.hits)
        << "class " << k;
    EXPECT_EQ(b.cold_cells, 0.0) << "class " << k;
    EXPECT_EQ(b.cold_tests, 0.0) << "class " << k;
  }
  EXPECT_GT(with_cold[kCamera].cold_cells, 0.0);
}

TEST(PilotReplay, CameraRaysColdStepsAreTheFramesNotTheSparsePilots) {
  // The frame: 128 x 128 at 16 spp through the same grid, its cold steps
  // counted by the render (stats/recent_cells.h).
  test::TempDir tmp;
  const std::string scene_path = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene_path, "--spp", "16", "--width", "128", "--height", "128", "--accel",
                                  "grid", "--grid-density", "64", "--stats", "on", "--out", (tmp / "x.exr").string(),
                                  "--report", (tmp / "x.json").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto report = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  const double frame_cold = report.at("cost").at("per_class").at("camera").at("cold_cells_per_ray").get<double>();
  ASSERT_GT(frame_cold, 0.0);

  // The pilot a choice would run for it: 1/256 of its paths, 1 sample a
  // pixel, so its neighbouring camera rays are 4 frame pixels apart.
  Warnings warnings;
  Scene scene = load_scene(scene_path, warnings);
  scene.width = scene.height = 128;
  const UniformGrid grid(scene.triangles, dense());
  const Pilot pilot = run_pilot(scene, 128, 128, pilot_pixels(128.0 * 128 * 16), grid, RenderSettings{});
  const QueryLoad camera = count_segments(grid, pilot.segments, std::nullopt, 16)[kCamera];
  const QueryLoad where_it_is = count_segments(grid, pilot.segments, std::nullopt, 1)[kCamera];
  const double predicted = camera.cold_cells / camera.rays;
  EXPECT_NEAR(predicted / frame_cold, 1.0, 0.3) << "predicted " << predicted << ", the frame's " << frame_cold;
  // The pilot's camera rays walked where they are, as a 1-spp frame's
  // first samples: far colder than the frame's.
  EXPECT_GT(where_it_is.cold_cells / where_it_is.rays, 1.5 * frame_cold);
}

}  // namespace
}  // namespace kappa
