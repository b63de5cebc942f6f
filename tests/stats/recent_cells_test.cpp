// Coherence as the counting frames count it (stats/recent_cells.h): the
// table's own rule, and counts that are the frame's alone, the same for any
// thread count.
#include "stats/recent_cells.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "stats/render_counters.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(RecentCells, AStepIsColdUntilItsCellWasEnteredAndAgainOnceEvicted) {
  RecentCells recent;
  EXPECT_TRUE(recent.visit(7));   // never entered
  EXPECT_FALSE(recent.visit(7));  // just entered
  EXPECT_TRUE(recent.visit(0));   // cell 0 is not the empty slot's mark
  EXPECT_FALSE(recent.visit(0));
  // Far more cells than slots: cell 7 has been evicted by one of them.
  for (std::uint64_t c = 100; c < 100 + 64 * RecentCells::kSlots; ++c) recent.visit(c);
  EXPECT_TRUE(recent.visit(7));
  // A run of neighbouring cells fits: one pass makes every one of them warm.
  RecentCells fresh;
  int cold = 0;
  for (std::uint64_t c = 5000; c < 5000 + RecentCells::kSlots / 4; ++c) fresh.visit(c);
  for (std::uint64_t c = 5000; c < 5000 + RecentCells::kSlots / 4; ++c) cold += fresh.visit(c);
  EXPECT_LE(cold, int(RecentCells::kSlots / 64)) << "neighbouring cells collide in the table";
  // So do the cells of a walk along y or z, whose indices stride by a row or
  // a slab of the grid (a mask of the low bits would put strides of 1,024
  // and 65,536 in one slot). Multiples of 4,096 collide more (108 cold of
  // 256 at 4,096): a slab of exactly such a size is rare, as the grid's
  // resolution follows the scene's box.
  for (const std::uint64_t stride : {64ull, 100ull, 1000ull, 1024ull, 65536ull}) {
    RecentCells strided;
    int strided_cold = 0;
    for (std::uint64_t k = 0; k < RecentCells::kSlots / 4; ++k) strided.visit(k * stride);
    for (std::uint64_t k = 0; k < RecentCells::kSlots / 4; ++k) strided_cold += strided.visit(k * stride);
    EXPECT_LE(strided_cold, int(RecentCells::kSlots / 16)) << "cells " << stride << " apart collide in the table";
  }
}

/// Each class's cold steps and cold tests per ray in a counting frame's report.
nlohmann::json cold_counts(const test::TempDir& tmp, const char* threads, const char* accel) {
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const std::string report = (tmp / (std::string(accel) + threads + ".json")).string();
  const auto r = test::run_kappa({"render", scene, "--spp", "4", "--width", "64", "--height", "64", "--accel", accel,
                                  "--grid-density", "64", "--stats", "on", "--threads", threads, "--out",
                                  (tmp / "x.exr").string(), "--report", report, "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  nlohmann::json out;
  const auto j = nlohmann::json::parse(test::read_file(report));
  for (const auto& [cls, c] : j.at("cost").at("per_class").items()) {
    out[cls] = {c.at("cold_cells_per_ray"), c.at("cold_tests_per_ray")};
    if (c.at("cold_cells_per_ray").is_number()) {
      EXPECT_GT(c.at("cold_cells_per_ray").get<double>(), 0.0) << cls;
      EXPECT_LT(c.at("cold_cells_per_ray").get<double>(), j.at("rays").at(cls).at("cells_per_ray").get<double>()) << cls;
      EXPECT_LE(c.at("cold_tests_per_ray").get<double>(), j.at("rays").at(cls).at("tests_per_ray").get<double>()) << cls;
    }
  }
  return out;
}

TEST(RecentCells, NaiveCountsNoColdSteps) {
  // No cells, no coherence: null, not a frame of perfectly coherent rays.
  test::TempDir tmp;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "1", "--width", "16", "--height", "16", "--accel", "naive",
                                  "--stats", "on", "--out", (tmp / "x.exr").string(), "--report",
                                  (tmp / "x.json").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto camera = nlohmann::json::parse(test::read_file(tmp / "x.json")).at("cost").at("per_class").at("camera");
  EXPECT_TRUE(camera.at("cold_cells_per_ray").is_null()) << camera;
  EXPECT_TRUE(camera.at("cold_tests_per_ray").is_null()) << camera;
}

TEST(RecentCells, AFramesColdStepsAreTheSameForAnyThreadCount) {
  test::TempDir tmp;
  for (const char* accel : {"grid", "grid2"}) {
    SCOPED_TRACE(accel);
    const nlohmann::json one = cold_counts(tmp, "1", accel);
    EXPECT_EQ(one, cold_counts(tmp, "2", accel));
    EXPECT_EQ(one.size(), kRenderClasses);
  }
}

}  // namespace
}  // namespace kappa
