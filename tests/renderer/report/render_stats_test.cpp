// Statistics during a render: free of side effects on the image, independent
// of the thread count, and complete in the report.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/factory.h"
#include "accel/grid.h"
#include "core/thread_limit.h"
#include "renderer/render/render_helpers.h"
#include "renderer/report/render_report.h"
#include "renderer/scene/scene_loader.h"
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
                         std::uint64_t max_bytes = std::uint64_t(1) << 32, std::uint64_t cell_sample = 1,
                         int spp = 4) {
  RenderSettings settings;
  settings.spp = spp;
  settings.cell_sample = cell_sample;
  settings.stats = stats;
  settings.stats_max_bytes = max_bytes;
  const ThreadLimit limit(threads);
  return render(scene, accel, settings, film);
}

/// Every number anywhere in `j` is finite (a NaN or infinity left in the
/// report object would be written as null or break readers).
void expect_finite_numbers(const nlohmann::ordered_json& j, const std::string& path = "report") {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) expect_finite_numbers(value, path + "." + key);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) expect_finite_numbers(j[i], path + "[" + std::to_string(i) + "]");
  } else if (j.is_number_float()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << path;
  }
}

TEST(RenderStats, CountingDoesNotChangeThePixels) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film off(scene.width, scene.height, {}), on(scene.width, scene.height, {});
  const RenderResult a = render_with(scene, *grid, false, 0, off);
  const RenderResult b = render_with(scene, *grid, true, 0, on);
  EXPECT_TRUE(test::bitwise_equal(off.rgb, on.rgb));
  EXPECT_EQ(a.rays, b.rays);
  EXPECT_FALSE(a.counters);
  ASSERT_TRUE(b.counters);
  std::uint64_t counted = 0;
  for (const auto& c : b.counters->classes) counted += c.totals.rays;
  // Every query is in exactly one class, or answered by the occluder cache.
  EXPECT_GT(b.counters->occluder_cache_hits, 0u);
  EXPECT_EQ(counted + b.counters->occluder_cache_hits, b.rays);
}

// The grid's case is above; naive and Embree count through ClassQueries.
TEST(RenderStats, CountingDoesNotChangeThePixelsOfNaiveOrEmbree) {
  const Scene scene = small_cornell();
  for (const char* name : {"naive", "embree"}) {
    SCOPED_TRACE(name);
    const auto accel = make_accelerator(name, scene.triangles);
    Film off(scene.width, scene.height, {}), on(scene.width, scene.height, {});
    const RenderResult a = render_with(scene, *accel, false, 0, off);
    const RenderResult b = render_with(scene, *accel, true, 0, on);
    EXPECT_TRUE(test::bitwise_equal(off.rgb, on.rgb));
    EXPECT_EQ(a.rays, b.rays);
    ASSERT_TRUE(b.counters);
  }
}

// A stats-on frame counting every path per cell, with the cost AOVs: image,
// AOVs and counts the same for 1, 2 and 4 threads.
TEST(RenderStats, StatsOnFramesAndCostAovsDoNotDependOnTheThreadCount) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  RenderSettings settings;
  settings.spp = 4;
  settings.stats = true;
  settings.cell_sample = 1;
  settings.aov = AovSelection{true, true, true, true};
  std::vector<Film> films;
  std::vector<RenderResult> results;
  for (int threads : {1, 2, 4}) {
    const ThreadLimit limit(threads);
    films.emplace_back(scene.width, scene.height, settings.aov);
    results.push_back(render(scene, *grid, settings, films.back()));
  }
  for (std::size_t k = 1; k < films.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_TRUE(test::bitwise_equal(films[0].rgb, films[k].rgb));
    EXPECT_TRUE(test::bitwise_equal(films[0].albedo, films[k].albedo));
    EXPECT_TRUE(test::bitwise_equal(films[0].cost_cells, films[k].cost_cells));
    EXPECT_TRUE(test::bitwise_equal(films[0].cost_tests, films[k].cost_tests));
    EXPECT_EQ(results[0].cell_sample, 1u);
    EXPECT_EQ(results[0].counters->classes[kCamera].visits(), results[k].counters->classes[kCamera].visits());
  }
  double cells = 0;
  for (float v : films[0].cost_cells) cells += v;
  EXPECT_GT(cells, 0.0);  // the cost AOV holds counts
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
    EXPECT_EQ(a.totals.rays, b.totals.rays) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.cells, b.totals.cells) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.refs, b.totals.refs) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.hits, b.totals.hits) << kRenderClassNames[k];
    EXPECT_EQ(a.per_cell_queries(), b.per_cell_queries()) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.tests, b.totals.tests) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.mailbox_skips, b.totals.mailbox_skips) << kRenderClassNames[k];
    EXPECT_EQ(a.totals.predicted_fixed, b.totals.predicted_fixed) << kRenderClassNames[k];
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
      EXPECT_TRUE(value.is_null() || value.is_object() || (value.is_number() && std::isfinite(value.get<double>())))
          << cls << "." << key;  // objects (sample) are checked by expect_finite_numbers below
  }
  // The classes count the walks; the occluder cache's hits are the rest of the queries.
  EXPECT_EQ(report["rays"]["all"]["count"].get<std::uint64_t>() +
                report["rays"]["shadow"]["occluder_cache"]["hits"].get<std::uint64_t>(),
            result.rays);
  expect_finite_numbers(report);
}

// Direct lighting only (--max-depth 1): the deeper bounce classes have no
// rays, and their per-ray quantities are null, not NaN.
TEST(RenderStats, ClassesWithoutRaysReportNullNotNaN) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  Film film(scene.width, scene.height, {});
  RenderSettings settings;
  settings.spp = 2;
  settings.max_depth = 1;
  settings.stats = true;
  const RenderResult result = render(scene, *grid, settings, film);
  const auto report = render_report(scene, *grid, FrameFacts{32, 32, 2, 0, 0}, result);
  for (const char* cls : {"bounce2", "bounce3+"}) {
    SCOPED_TRACE(cls);
    const auto& c = report["rays"][cls];
    EXPECT_EQ(c["count"].get<std::uint64_t>(), 0u);
    for (const char* key : {"cells_per_ray", "tests_per_ray", "refs_per_ray", "hit_fraction", "p_tot", "p_avg",
                            "sigma_p", "r", "kappa", "kappa_eq25"})
      EXPECT_TRUE(c[key].is_null()) << key;
  }
  EXPECT_GT(report["rays"]["camera"]["count"].get<std::uint64_t>(), 0u);
  EXPECT_GT(report["rays"]["shadow"]["count"].get<std::uint64_t>(), 0u);
  expect_finite_numbers(report);
}

// A flat scene (one square in the plane z = 0, seen from above under a sky):
// a one-cell-thick grid, Theta_i equal over the occupied cells.
TEST(RenderStats, FlatSceneReportsFiniteNumbers) {
  Scene s;
  s.materials.push_back(Material{"grey", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  s.triangles.push_back({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}});
  s.triangles.push_back({{-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
  s.material_of = {0, 0};
  s.environment = {1, 1, 1};
  s.camera = CameraSpec{{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 60.0f};
  s.width = s.height = 16;
  const auto grid = make_accelerator("grid", s.triangles);
  ASSERT_TRUE(grid->cells());
  ASSERT_EQ(grid->cells()->resolution_text().substr(grid->cells()->resolution_text().rfind('x')), "x1");  // flat: one layer
  Film film(s.width, s.height, {});
  RenderSettings settings;
  settings.spp = 2;
  settings.stats = true;
  const RenderResult result = render(s, *grid, settings, film);
  const auto report = render_report(s, *grid, FrameFacts{16, 16, 2, 0, 0}, result);
  EXPECT_GT(report["rays"]["camera"]["count"].get<std::uint64_t>(), 0u);
  EXPECT_TRUE(report["grid"]["theta_avg"].is_number());
  expect_finite_numbers(report);
}

TEST(RenderStats, AutoCellSampleFallsWithTheGridSize) {
  EXPECT_EQ(auto_cell_sample(1000), 1u);
  EXPECT_EQ(auto_cell_sample(65536), 1u);
  EXPECT_EQ(auto_cell_sample(65537), 64u);
  EXPECT_EQ(auto_cell_sample(118 * 1024), 64u);
  EXPECT_EQ(auto_cell_sample(1 << 20), 128u);
  EXPECT_EQ(auto_cell_sample(215 * 102 * 97), 256u);  // Sponza at the default density
  EXPECT_EQ(auto_cell_sample(std::uint64_t(1) << 40), 1024u);
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
  // kappa (eq 8) and p_tot come from the totals; what needs p_i per cell is null.
  const auto& camera = report["rays"]["camera"];
  const ClassTotals& t = result.counters->classes[kCamera].totals;
  const double N_c = double(grid->cells()->cell_count()), theta_tot = report["grid"]["theta_tot"].get<double>();
  ASSERT_TRUE(camera["kappa"].is_number());
  EXPECT_DOUBLE_EQ(camera["kappa"].get<double>(), N_c * double(t.refs) / (double(t.cells) * theta_tot));
  EXPECT_TRUE(camera["p_tot"].is_number());
  EXPECT_TRUE(camera["sigma_p"].is_null());
  EXPECT_TRUE(camera["r"].is_null());
  EXPECT_TRUE(camera["kappa_eq25"].is_null());
  EXPECT_FALSE(report["stats"]["per_cell"].get<bool>());
}

// Per-cell counts for 1 path in 8: every total (and so kappa by eq 8) is the
// same as when every path is counted; sigma_p, r and kappa_eq25 are estimates
// from about an eighth of the rays, near the full count's values.
TEST(RenderStats, SampledPerCellCountsKeepExactTotalsAndEstimateTheRest) {
  Scene scene = small_cornell();
  scene.width = scene.height = 64;
  const auto grid = make_accelerator("grid", scene.triangles);
  Film f1(scene.width, scene.height, {}), f8(scene.width, scene.height, {}), f8_two(scene.width, scene.height, {});
  const RenderResult full = render_with(scene, *grid, true, 0, f1, std::uint64_t(1) << 32, 1, 16);
  const RenderResult sampled = render_with(scene, *grid, true, 1, f8, std::uint64_t(1) << 32, 8, 16);
  const RenderResult sampled_two = render_with(scene, *grid, true, 2, f8_two, std::uint64_t(1) << 32, 8, 16);
  EXPECT_EQ(sampled.cell_sample, 8u);
  const FrameFacts facts{64, 64, 16, 2, 0};
  const auto a = render_report(scene, *grid, facts, full), b = render_report(scene, *grid, facts, sampled);
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const CellCounters &x = full.counters->classes[k], &y = sampled.counters->classes[k];
    const char* name = kRenderClassNames[k];
    EXPECT_EQ(x.totals.rays, y.totals.rays) << name;
    EXPECT_EQ(x.totals.cells, y.totals.cells) << name;
    EXPECT_EQ(x.totals.tests, y.totals.tests) << name;
    EXPECT_EQ(x.totals.refs, y.totals.refs) << name;
    EXPECT_EQ(x.per_cell_queries(), x.totals.rays) << name;
    // About 1 ray in 8 counted per cell (paths drawn by a hash: binomial).
    const double n = double(x.totals.rays), q = 1.0 / 8.0;
    EXPECT_NEAR(double(y.per_cell_queries()), n * q, 6.0 * std::sqrt(n * q)) << name;
    // The path choice depends on (seed, pixel, sample) only.
    EXPECT_EQ(y.visits(), sampled_two.counters->classes[k].visits()) << name;
    EXPECT_EQ(y.per_cell_queries(), sampled_two.counters->classes[k].per_cell_queries()) << name;
  }
  for (const char* cls : {"camera", "shadow", "bounce1", "all"}) {
    const auto &x = a["rays"][cls], &y = b["rays"][cls];
    EXPECT_NEAR(x["kappa"].get<double>(), y["kappa"].get<double>(), 1e-12 * x["kappa"].get<double>()) << cls;
    EXPECT_NEAR(x["p_tot"].get<double>(), y["p_tot"].get<double>(), 1e-12 * x["p_tot"].get<double>()) << cls;
    EXPECT_NEAR(y["sigma_p"].get<double>(), x["sigma_p"].get<double>(), 0.05 * x["sigma_p"].get<double>()) << cls;
    EXPECT_NEAR(y["kappa_eq25"].get<double>(), x["kappa_eq25"].get<double>(), 0.05 * x["kappa_eq25"].get<double>())
        << cls;
    EXPECT_NEAR(y["r"].get<double>(), x["r"].get<double>(), 0.05) << cls;
  }
  EXPECT_EQ(b["stats"]["cell_sample"].get<std::uint64_t>(), 8u);
}

// Naive (or Embree) with statistics on: per class the rays, hits and time,
// the same rays and hits as the grid counts; nothing grid-specific.
TEST(RenderStats, NonGridAcceleratorsReportWhatApplies) {
  const Scene scene = small_cornell();
  const auto naive = make_accelerator("naive", scene.triangles);
  const auto grid = make_accelerator("grid", scene.triangles);
  Film film(scene.width, scene.height, {}), grid_film(scene.width, scene.height, {});
  const RenderResult result = render_with(scene, *naive, true, 0, film);
  const RenderResult on_grid = render_with(scene, *grid, true, 0, grid_film);
  ASSERT_TRUE(result.counters);
  const auto report = render_report(scene, *naive, FrameFacts{32, 32, 4, 2, 0}, result);
  EXPECT_FALSE(report.contains("grid"));
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const char* name = kRenderClassNames[k];
    const auto& c = report["rays"][name];
    // The grid's shadow rays the occluder cache answered walk nothing; naive walks them all.
    const std::uint64_t cached = k == kShadow ? on_grid.counters->occluder_cache_hits : 0;
    EXPECT_EQ(c["count"].get<std::uint64_t>(), on_grid.counters->classes[k].totals.rays + cached) << name;
    EXPECT_EQ(result.counters->classes[k].totals.hits, on_grid.counters->classes[k].totals.hits + cached) << name;
    EXPECT_TRUE(c.contains("hit_fraction") && c.contains("time_s")) << name;
    EXPECT_FALSE(c.contains("kappa") || c.contains("cells_per_ray")) << name;
    total += c["count"].get<std::uint64_t>();
  }
  EXPECT_EQ(total, result.rays);
  // The classes count the walks; the occluder cache's hits are the rest of the queries.
  EXPECT_EQ(report["rays"]["all"]["count"].get<std::uint64_t>() +
                report["rays"]["shadow"]["occluder_cache"]["hits"].get<std::uint64_t>(),
            result.rays);
  expect_finite_numbers(report);
}

// In sampled mode the top-level sigma_p and r estimate the whole frame's
// (from thinned counts) while kappa_eq25 is the sample's: "sample" holds the
// sample's own moments, which reproduce its kappa_eq25 through eq 25.
TEST(RenderStats, SampleBlockReproducesItsKappaEq25) {
  const Scene scene = small_cornell();
  const auto grid = make_accelerator("grid", scene.triangles);
  for (std::uint64_t every : {std::uint64_t(1), std::uint64_t(8)}) {
    SCOPED_TRACE(every);
    Film film(scene.width, scene.height, {});
    const RenderResult result = render_with(scene, *grid, true, 0, film, std::uint64_t(1) << 32, every, 16);
    const auto report = render_report(scene, *grid, FrameFacts{32, 32, 16, 2, 0}, result);
    const double theta_avg = report["grid"]["theta_avg"].get<double>();
    int checked = 0;
    // The classes, and the bounce rays by lobe.
    std::vector<std::pair<std::string, nlohmann::ordered_json>> sections;
    for (const auto& [name, c] : report["rays"].items())
      if (name != "bounce_by_lobe") sections.emplace_back(name, c);
    for (const auto& [name, c] : report["rays"]["bounce_by_lobe"].items())
      if (c["count"].get<std::uint64_t>() > 0) sections.emplace_back("by " + name, c);  // a Lambertian scene: diffuse
    for (const auto& [name, c] : sections) {
      const auto& s = c["sample"];
      ASSERT_TRUE(s.is_object()) << name;
      EXPECT_EQ(s["N_s"].get<std::uint64_t>(), c["per_cell_rays"].get<std::uint64_t>()) << name;
      if (!s["r"].is_number()) continue;
      const double eq25 = 1.0 + s["sigma_p"].get<double>() / s["p_avg"].get<double>() *
                                    c["sigma_theta"].get<double>() / theta_avg * s["r"].get<double>();
      EXPECT_NEAR(eq25, s["kappa_eq25"].get<double>(), 1e-12 * eq25) << name;
      ++checked;
    }
    EXPECT_GE(checked, 4);
  }
}

}  // namespace
}  // namespace kappa
