// Statistics during a render: free of side effects on the image, independent
// of the thread count, and complete in the report.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/grid.h"
#include "render_helpers.h"
#include "renderer/render_report.h"
#include "renderer/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

Scene small_cornell() {
  Warnings w;
  Scene s = load_scene(test::assets_dir() / "cornell-box" / "scene.json", w);
  s.width = s.height = 32;
  return s;
}

RenderResult render_with(const Scene& scene, const Accelerator& accel, bool stats, int threads, Film& film,
                         std::uint64_t max_bytes = std::uint64_t(1) << 32) {
  RenderSettings settings;
  settings.spp = 4;
  settings.stats = stats;
  settings.threads = threads;
  settings.stats_max_bytes = max_bytes;
  return render(scene, accel, settings, film);
}

TEST(RenderStats, CountingDoesNotChangeThePixels) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film off(scene.width, scene.height, {}), on(scene.width, scene.height, {});
  const RenderResult a = render_with(scene, *grid, false, 0, off);
  const RenderResult b = render_with(scene, *grid, true, 0, on);
  EXPECT_EQ(std::memcmp(off.rgb.data(), on.rgb.data(), off.rgb.size() * sizeof(float)), 0);
  EXPECT_EQ(a.rays, b.rays);
  EXPECT_FALSE(a.counters);
  ASSERT_TRUE(b.counters);
  std::uint64_t counted = 0;
  for (const auto& c : b.counters->classes) counted += c.totals.rays;
  EXPECT_EQ(counted, b.rays);  // every query is in exactly one class
}

TEST(RenderStats, CountersDoNotDependOnTheThreadCount) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film f1(scene.width, scene.height, {}), f2(scene.width, scene.height, {});
  const RenderResult one = render_with(scene, *grid, true, 1, f1);
  const RenderResult two = render_with(scene, *grid, true, 2, f2);
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const CellCounters &a = one.counters->classes[k], &b = two.counters->classes[k];
    EXPECT_EQ(a.visits(), b.visits()) << kRenderClassNames[k];
    EXPECT_EQ(a.tests_in(), b.tests_in()) << kRenderClassNames[k];
    EXPECT_EQ(a.hits_in(), b.hits_in()) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.tests, b.totals.tests) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.mailbox_skips, b.totals.mailbox_skips) << kRenderClassNames[k];
    EXPECT_EQ(one.counters->predicted_fixed[k], two.counters->predicted_fixed[k]) << kRenderClassNames[k];
  }
}

TEST(RenderStats, ReportHasEveryClassAndNoNaN) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film film(scene.width, scene.height, {});
  const RenderResult result = render_with(scene, *grid, true, 0, film);
  const auto report = render_report(scene, *grid, FrameFacts{32, 32, 4, 2, 0}, result);
  for (const char* key : {"width", "height", "spp", "threads", "seed", "time_s", "rays", "mrays_per_s"})
    EXPECT_TRUE(report["render"].contains(key)) << key;
  for (const char* cls : {"camera", "shadow", "bounce1", "bounce2", "bounce3+", "all"}) {
    ASSERT_TRUE(report["rays"].contains(cls)) << cls;
    for (const auto& [key, value] : report["rays"][cls].items())
      EXPECT_TRUE(value.is_null() || (value.is_number() && std::isfinite(value.get<double>()))) << cls << "." << key;
  }
  EXPECT_EQ(report["rays"]["all"]["count"].get<std::uint64_t>(), result.rays);
  const std::string text = report.dump();
  EXPECT_EQ(text.find("NaN"), std::string::npos);
}

TEST(RenderStats, PerCellCountersOverTheBudgetAreRefusedButTotalsStay) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film film(scene.width, scene.height, {});
  const RenderResult result = render_with(scene, *grid, true, 0, film, /*max_bytes=*/1000);
  ASSERT_TRUE(result.counters);
  EXPECT_FALSE(result.counters->classes[kCamera].per_cell());
  EXPECT_GT(result.counters->classes[kCamera].totals.cells, 0u);
  EXPECT_NE(result.stats_note.find("refused"), std::string::npos);
  const auto report = render_report(scene, *grid, FrameFacts{32, 32, 4, 2, 0}, result);
  EXPECT_TRUE(report["rays"]["camera"]["kappa"].is_null());
  EXPECT_TRUE(report["rays"]["camera"]["p_tot"].is_number());
}

TEST(RenderStats, NonGridAcceleratorsCountNothingPerClass) {
  const Scene scene = small_cornell();
  const auto naive = make_accelerator("naive", scene.triangles);
  Film film(scene.width, scene.height, {});
  const RenderResult result = render_with(scene, *naive, true, 0, film);
  EXPECT_FALSE(result.counters);
  const auto report = render_report(scene, *naive, FrameFacts{32, 32, 4, 2, 0}, result);
  EXPECT_FALSE(report.contains("grid"));
  EXPECT_TRUE(report["rays"].empty());
}

}  // namespace
}  // namespace kappa
