// The first pass's tile order of a frame shared by processes
// (renderer/render/tile_costs.h): each tile's cost predicted from the pilot's
// pixels' queries, and the tiles handed out the costliest first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/factory.h"
#include "renderer/render/pilot.h"
#include "renderer/render/tile_costs.h"
#include "renderer/render/tile_schedule.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(TileCosts, EachFramePixelTakesThePilotPixelItFallsIn) {
  // A 4 x 2 pilot of a 64 x 32 frame (4 x 2 tiles): each pilot pixel covers
  // one tile, 256 frame pixels.
  Pilot pilot;
  pilot.width = 4;
  pilot.height = 2;
  pilot.pixel_rays = {1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<double> costs = predicted_tile_costs(pilot, 4 * kTileSize, 2 * kTileSize);
  ASSERT_EQ(costs.size(), 8u);
  for (std::size_t t = 0; t < 8; ++t) EXPECT_DOUBLE_EQ(costs[t], 256.0 * double(t + 1)) << "tile " << t;

  // A frame whose tiles are cut by its edges (40 x 20: 3 x 2 tiles), filmed
  // by a 2 x 1 pilot: its left half costs 1 a pixel, its right half 10.
  pilot.width = 2;
  pilot.height = 1;
  pilot.pixel_rays = {1, 10};
  const std::vector<double> cut = predicted_tile_costs(pilot, 40, 20);
  ASSERT_EQ(cut.size(), 6u);
  EXPECT_DOUBLE_EQ(cut[0], 16.0 * 16 * 1);              // columns 0-15: left
  EXPECT_DOUBLE_EQ(cut[1], 16.0 * (4 * 1 + 12 * 10));   // columns 16-19 left, 20-31 right
  EXPECT_DOUBLE_EQ(cut[2], 16.0 * 8 * 10);              // columns 32-39: right
  EXPECT_DOUBLE_EQ(cut[3], 4.0 * 16 * 1);               // rows 16-19
  EXPECT_DOUBLE_EQ(cut[5], 4.0 * 8 * 10);
}

TEST(TileCosts, ThePilotCountsEachPixelsQueries) {
  Warnings warnings;
  const Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  const auto accel = make_accelerator("grid", scene.triangles, {}, nullptr);
  const Pilot pilot = run_pilot(scene, 80, 56, 1024, *accel, RenderSettings{});
  ASSERT_EQ(pilot.pixel_rays.size(), std::size_t(pilot.width) * std::size_t(pilot.height));
  std::uint64_t sum = 0, most = 0;
  for (std::size_t p = 0; p < pilot.pixel_rays.size(); ++p) {
    EXPECT_GT(pilot.pixel_rays[p], 0u) << "pixel " << p << ": its camera ray at least";
    sum += pilot.pixel_rays[p];
    most = std::max<std::uint64_t>(most, pilot.pixel_rays[p]);
  }
  std::uint64_t rays = 0;
  for (std::uint64_t r : pilot.rays) rays += r;
  EXPECT_EQ(sum, rays);  // every query, each in its own pixel
  EXPECT_GT(most, 2u);   // bounces and shadow rays too
  EXPECT_EQ(predicted_tile_costs(pilot, 80, 56).size(), 5u * 4u);
}

TEST(TileCosts, APilotThatCountedNothingPredictsNothing) {
  Pilot pilot;
  pilot.width = 4;
  pilot.height = 2;  // and no pixel counted
  EXPECT_TRUE(predicted_tile_costs(pilot, 64, 32).empty());
}

TEST(TileCosts, TilesGoOutCostliestFirstTiesAndMissingCostsInTileOrder) {
  EXPECT_EQ(costliest_first({1, 5, 3, 5, 0}, 5), (std::vector<std::size_t>{1, 3, 2, 0, 4}));
  EXPECT_EQ(costliest_first({}, 4), (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(costliest_first({9, 1}, 3), (std::vector<std::size_t>{0, 1, 2}));  // not this frame's
}

}  // namespace
}  // namespace kappa
