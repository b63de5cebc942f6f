// `kappa cast`: every distribution runs, and the report carries the
// documented keys with numbers or null, never NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

nlohmann::json cast_report(const std::vector<std::string>& extra) {
  test::TempDir tmp;
  std::vector<std::string> args = {"cast", cornell(), "--report", (tmp / "r.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  return nlohmann::json::parse(test::read_file(tmp / "r.json"));
}

TEST(Cast, EveryDistributionReportsTheDocumentedKeys) {
  for (const char* rays : {"lines", "segments", "camera", "bounce", "shadow"}) {
    SCOPED_TRACE(rays);
    const auto j = cast_report({"--rays", rays, "--n", "5000"});
    for (const char* key : {"schema_version", "kappa_version", "scene", "accel", "render", "grid", "rays", "cost"})
      EXPECT_TRUE(j.contains(key)) << key;
    for (const char* key : {"res", "N_c", "N", "cell_size", "build_s", "bytes", "theta_tot", "theta_tot_eq19",
                            "theta_tot_eq21", "theta_avg", "theta_max", "max_multiplicity", "empty_fraction"})
      EXPECT_TRUE(j.at("grid").contains(key)) << key;
    const auto& c = j.at("rays").at(rays);
    for (const char* key : {"count", "cells_per_ray", "cells_per_ray_predicted", "tests_per_ray", "refs_per_ray",
                            "hit_fraction", "p_tot", "p_avg", "sigma_p", "sigma_theta", "r", "kappa", "kappa_eq25",
                            "time_s"}) {
      ASSERT_TRUE(c.contains(key)) << key;
      EXPECT_TRUE(c.at(key).is_number() || c.at(key).is_null()) << key;
    }
    EXPECT_EQ(c.contains("p_tot_predicted"), std::string(rays) == "lines");
    EXPECT_EQ(c.at("count"), 5000);
    // p_tot is the mean number of cells per ray; refs_per_ray = p_avg theta_tot kappa.
    EXPECT_NEAR(c.at("p_tot").get<double>(), c.at("cells_per_ray").get<double>(), 1e-12 * c.at("p_tot").get<double>());
    EXPECT_NEAR(c.at("refs_per_ray").get<double>(),
                c.at("p_avg").get<double>() * j.at("grid").at("theta_tot").get<double>() * c.at("kappa").get<double>(),
                1e-9 * c.at("refs_per_ray").get<double>());
  }
}

TEST(Cast, UniformLinesOnTheCornellBoxHaveKappaNearOne) {
  const auto j = cast_report({"--rays", "lines", "--n", "100000", "--grid-res", "12"});
  const auto& c = j.at("rays").at("lines");
  EXPECT_NEAR(c.at("kappa").get<double>(), 1.0, 0.03);
  EXPECT_NEAR(c.at("p_tot").get<double>() / c.at("p_tot_predicted").get<double>(), 1.0, 0.01);
}

// A budget that holds the grid (64^3 cells, about 1 MiB) but not its
// per-cell counters (about 22 MiB): totals only, with the same kappa.
TEST(Cast, PerCellCountersOverTheBudgetAreRefusedButTotalsStay) {
  const std::vector<std::string> args = {"--rays", "lines", "--n", "20000", "--grid-res", "64", "--threads", "2"};
  const auto full = cast_report(args);
  std::vector<std::string> tight = args;
  tight.insert(tight.end(), {"--grid-max-bytes", "4000000"});
  const auto refused = cast_report(tight);
  EXPECT_TRUE(full.at("stats").at("per_cell").get<bool>());
  EXPECT_FALSE(full.contains("stats_note"));
  EXPECT_FALSE(refused.at("stats").at("per_cell").get<bool>());
  EXPECT_NE(refused.at("stats_note").get<std::string>().find("refused"), std::string::npos);
  const auto &a = full.at("rays").at("lines"), &b = refused.at("rays").at("lines");
  // The same counts (from per-cell sums in one, from totals in the other).
  for (const char* key : {"kappa", "p_tot", "refs_per_ray"})
    EXPECT_NEAR(a.at(key).get<double>(), b.at(key).get<double>(), 1e-9 * a.at(key).get<double>()) << key;
  EXPECT_TRUE(a.at("sigma_p").is_number());
  EXPECT_TRUE(b.at("sigma_p").is_null());
  EXPECT_TRUE(b.at("r").is_null());
  EXPECT_TRUE(b.at("kappa_eq25").is_null());
}

TEST(Cast, NonGridAcceleratorsReportWhatApplies) {
  const auto j = cast_report({"--rays", "camera", "--n", "2000", "--accel", "naive"});
  EXPECT_FALSE(j.contains("grid"));
  const auto& c = j.at("rays").at("camera");
  EXPECT_EQ(c.at("count"), 2000);
  EXPECT_TRUE(c.contains("hit_fraction"));
  EXPECT_FALSE(c.contains("kappa"));
}

TEST(Cast, BadOptionsAreRefused) {
  test::TempDir tmp;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"cast", cornell(), "--rays", "diagonals"}, {"cast", cornell(), "--n", "0"},
        {"cast", cornell(), "--rays", "segments", "--length", "1e9"}, {"cast", cornell(), "--length", "-1"}}) {
    const auto r = run_kappa(args);
    EXPECT_EQ(r.exit_code, 2) << args[2] << " " << args[3];
    EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
  }
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(RenderReport, WrittenBesideTheImageWithEveryClass) {
  test::TempDir tmp;
  // A calibration of known constants, so that the cost section does not
  // depend on a file another run may have left beside the binary.
  // Extended constants: T0 per class 11, 12, ..., 15; Ts 1, Ts_occupied 19, Th 7, T_hit 23; the
  // per-class miss terms 2 + class (cells) and 3 + class (tests).
  // grid2's own: Ts 5 and T0 per class 31, 32, ..., 35, T_descend 13, the rest the grid's.
  const char* classes[] = {"camera", "shadow", "bounce1", "bounce2", "bounce3+"};
  const auto extended_constants = [&](int t0, int ts) {
    std::string constants;
    for (int k = 0; k < 5; ++k) constants += "\"T0_" + std::string(classes[k]) + "_ns\": " + std::to_string(t0 + k) + ", ";
    constants += "\"Ts_ns\": " + std::to_string(ts) + R"(, "Ts_occupied_ns": 19, "Th_ns": 7, "T_hit_ns": 23)";
    for (int k = 0; k < 5; ++k)
      constants += ", \"Ts_miss_" + std::string(classes[k]) + "_ns\": " + std::to_string(2 + k) + ", \"Th_miss_" +
                   classes[k] + "_ns\": " + std::to_string(3 + k);
    return R"({"cache_bytes": 1024, "constants": {)" + constants + "}}";
  };
  const std::string build = R"({"threads": 1, "constants": {"per_triangle_ns": 50, "per_reference_ns": 20, "per_cell_ns": 2}})";
  std::string grid2_constants = extended_constants(31, 5);
  grid2_constants.insert(grid2_constants.size() - 2, R"(, "T_descend_ns": 13)");
  test::write_file(tmp / "cal.json", R"({"format": 9, "machine": "test", "clock": "tsc", "samples": 0,
    "eq10": {"constants": {"T0_ns": 20, "Ts_ns": 3, "Th_ns": 7}},
    "naive": {"constants": {"T0_ns": 30, "Th_ns": 2, "Th_occluded_ns": 1}},
    "build": )" + build + R"(, "extended": )" + extended_constants(11, 1) + R"(,
    "grid2": {"traversal": )" + grid2_constants + R"(, "build": )" + build + "}}");
  const auto r = test::run_kappa({"render", cornell(), "--accel", "grid", "--spp", "2", "--width", "24", "--height",
                                  "24", "--out", (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(),
                                  "--calibration", (tmp / "cal.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  EXPECT_EQ(j.at("render").at("width"), 24);
  EXPECT_EQ(j.at("accel"), "grid");
  for (const char* cls : {"camera", "shadow", "bounce1", "bounce2", "bounce3+", "all"})
    EXPECT_TRUE(j.at("rays").at(cls).at("kappa").is_number()) << cls;
  // Both models per class from the class's own counts, summed.
  const auto& cost = j.at("cost");
  ASSERT_TRUE(cost.is_object());
  EXPECT_EQ(cost.at("eq10").at("T0_ns").get<double>(), 20.0);
  // A step's share beyond the 1024-byte cache is its cells', a test's its lists' and triangles'.
  const auto beyond = [](double bytes) { return bytes > 1024 ? 1 - 1024 / bytes : 0.0; };
  const auto shares = [&](const nlohmann::json& section) {
    const double references = section.at("theta_tot").get<double>() * 4, triangles = section.at("N").get<double>() * 36;
    return std::pair{beyond(section.at("bytes").get<double>() - references), beyond(references + triangles)};
  };
  const auto [step_miss, test_miss] = shares(j.at("grid"));
  double eq10 = 0, extended = 0;
  for (const char* cls : classes) {
    const auto& c = j.at("rays").at(cls);
    const double n = c.at("count").get<double>();
    const auto& mine = cost.at("per_class").at(cls);
    if (n == 0) continue;
    const double cells = c.at("cells_per_ray").get<double>(), tests = c.at("tests_per_ray").get<double>();
    const double occupied = c.at("occupied_cells_per_ray").get<double>();
    const int k = int(std::find_if(std::begin(classes), std::end(classes), [&](const char* x) { return std::string(x) == cls; }) -
                      std::begin(classes));
    const double e10 = n * (20 + 3 * cells + 7 * tests) * 1e-9;
    const double ext = n * 1e-9 *
                       (11 + k + cells + 19 * occupied + 7 * tests + 23 * c.at("hit_fraction").get<double>() +
                        (2 + k) * cells * step_miss + (3 + k) * tests * test_miss);
    EXPECT_NEAR(mine.at("eq10_s").get<double>(), e10, 1e-9 * e10) << cls;
    EXPECT_NEAR(mine.at("extended_s").get<double>(), ext, 1e-9 * ext) << cls;
    eq10 += e10, extended += ext;
  }
  EXPECT_NEAR(cost.at("eq10").at("predicted_s").get<double>(), eq10, 1e-9 * eq10);
  EXPECT_NEAR(cost.at("extended").at("predicted_s").get<double>(), extended, 1e-9 * extended);
  EXPECT_EQ(cost.at("extended").at("constants").at("T_hit_ns").get<double>(), 23.0);

  // grid2: the extended model with grid2's constants on its leaf counts;
  // eq 10, the uniform grid's, is not applied.
  const auto r2 = test::run_kappa({"render", cornell(), "--spp", "2", "--width", "24", "--height", "24", "--accel",
                                   "grid2", "--out", (tmp / "g.exr").string(), "--report", (tmp / "g.json").string(),
                                   "--calibration", (tmp / "cal.json").string()});
  ASSERT_EQ(r2.exit_code, 0) << r2.std_err;
  const auto g = nlohmann::json::parse(test::read_file(tmp / "g.json"));
  const auto& cost2 = g.at("cost");
  EXPECT_TRUE(cost2.at("eq10").is_null());
  const auto [step_miss2, test_miss2] = shares(g.at("grid2"));
  double descents = 0;
  double extended2 = 0;
  for (int k = 0; k < 5; ++k) {
    const auto& c = g.at("rays").at(classes[k]);
    const double n = c.at("count").get<double>();
    if (n == 0) continue;
    const double cells = c.at("cells_per_ray").get<double>(), tests = c.at("tests_per_ray").get<double>();
    const double ext = n * 1e-9 *
                       (31 + k + 5 * cells + 19 * c.at("occupied_cells_per_ray").get<double>() + 7 * tests +
                        23 * c.at("hit_fraction").get<double>() + (2 + k) * cells * step_miss2 +
                        (3 + k) * tests * test_miss2 + 13 * c.at("descents_per_ray").get<double>());
    descents += n * c.at("descents_per_ray").get<double>();
    EXPECT_NEAR(cost2.at("per_class").at(classes[k]).at("extended_s").get<double>(), ext, 1e-9 * ext) << classes[k];
    extended2 += ext;
  }
  EXPECT_GT(extended2, 0.0);
  EXPECT_GT(descents, 0.0);  // the Cornell box's grid2 has sub-grids its rays enter
  EXPECT_NEAR(cost2.at("extended").at("predicted_s").get<double>(), extended2, 1e-9 * extended2);
  EXPECT_EQ(cost2.at("extended").at("constants").at("T0_camera_ns").get<double>(), 31.0);
}

TEST(RenderReport, TraversalTimeNeverExceedsTheThreadsTime) {
  // Every query is timed: a class's time, and their sum, fit in the frame's
  // thread time (threads x wall), which sampled timing (one query in 64,
  // counted 64 times) did not guarantee.
  test::TempDir tmp;
  for (const char* accel : {"grid", "naive"}) {
    const auto r = test::run_kappa({"render", cornell(), "--spp", "4", "--width", "32", "--height", "32", "--accel",
                                    accel, "--out", (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(),
                                    "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.std_err;
    const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json"));
    const double thread_time = j.at("render").at("threads").get<double>() * j.at("render").at("time_s").get<double>();
    const auto& cost = j.at("cost");
    double sum = 0;
    for (const auto& [cls, c] : cost.at("per_class").items()) {
      const double s = c.at("measured_s").get<double>();
      EXPECT_GE(s, 0.0) << cls;
      EXPECT_LE(s, thread_time) << accel << " " << cls;
      EXPECT_EQ(s, j.at("rays").at(cls).at("time_s").get<double>()) << cls;
      sum += s;
    }
    EXPECT_GT(sum, 0.0) << accel;
    EXPECT_NEAR(cost.at("measured_s").get<double>(), sum, 1e-12 * sum);
    EXPECT_LE(sum, thread_time) << accel;
    EXPECT_TRUE(cost.at("capped_queries").is_number_unsigned()) << accel;
    EXPECT_EQ(cost.at("eq10").is_null(), std::string(accel) == "naive" || cost.at("calibration").is_null()) << accel;
  }
}

TEST(RenderReport, UnwritableReportPathIsRefusedBeforeRendering) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"render", cornell(), "--spp", "1", "--out", (tmp / "x.exr").string(), "--report",
                                  (tmp / "missing" / "x.json").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
}

}  // namespace
}  // namespace kappa

#include "image_files.h"

namespace kappa {
namespace {

/// Sum of one channel of an image file.
double channel_sum(const std::filesystem::path& file, const std::string& channel) {
  double sum = 0;
  for (const float v : test::read_exr_file(file).values(channel)) sum += v;
  return sum;
}

TEST(CostPictures, CostAovsAndCellMapAddUpToTheReport) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"render", cornell(), "--accel", "grid", "--spp", "2", "--width", "24", "--height", "24", "--aov", "cost",
                                  "--out", (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(),
                                  "--cell-map", (tmp / "map.exr").string(), "--cell-map-axis", "z"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  const auto& all = j.at("rays").at("all");
  const double rays = all.at("count").get<double>();
  // Every ray's cells and tests land in exactly one pixel.
  EXPECT_NEAR(channel_sum(tmp / "x.exr", "cost.cells"), all.at("cells_per_ray").get<double>() * rays, 0.5);
  // The tests include the occluder cache's, which belong to no walk.
  const double cache_tests = j.at("rays").at("shadow").at("occluder_cache").at("tests").get<double>();
  EXPECT_GT(cache_tests, 0.0);
  EXPECT_NEAR(channel_sum(tmp / "x.exr", "cost.tests"), all.at("tests_per_ray").get<double>() * rays + cache_tests,
              0.5);
  // The projection keeps the sums: sum of p_i = p_tot, sum of Theta_i = theta_tot.
  EXPECT_NEAR(channel_sum(tmp / "map.exr", "p"), all.at("p_tot").get<double>(), 1e-3 * all.at("p_tot").get<double>());
  EXPECT_NEAR(channel_sum(tmp / "map.exr", "theta"), j.at("grid").at("theta_tot").get<double>(), 1e-3);
  // A PNG map for people.
  const auto png = test::run_kappa({"render", cornell(), "--accel", "grid", "--spp", "1", "--width", "8", "--height", "8", "--out",
                                    (tmp / "y.exr").string(), "--cell-map", (tmp / "map.png").string()});
  ASSERT_EQ(png.exit_code, 0) << png.std_err;
  // The same cells as the EXR map's pixels, sqrt(p_i / max p) in red and
  // sqrt(Theta_i / max Theta) in green, 8 bits: each channel reaches 255.
  const test::PngFile map = test::read_png_file(tmp / "map.png");
  const test::ExrFile exr_map = test::read_exr_file(tmp / "map.exr");
  EXPECT_EQ(map.width, exr_map.width);
  EXPECT_EQ(map.height, exr_map.height);
  ASSERT_EQ(map.rgb.size(), 3 * std::size_t(map.width) * std::size_t(map.height));
  std::uint8_t most[3] = {0, 0, 0};
  for (std::size_t i = 0; i < map.rgb.size(); ++i) most[i % 3] = std::max(most[i % 3], map.rgb[i]);
  EXPECT_EQ(most[0], 255);
  EXPECT_EQ(most[1], 255);
  EXPECT_EQ(most[2], 0);
}

TEST(CostPictures, NeedStatisticsOnTheGrid) {
  test::TempDir tmp;
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--aov", "cost", "--stats", "off"}, {"--aov", "cost", "--accel", "naive"},
        {"--cell-map", (tmp / "m.exr").string(), "--stats", "off"}, {"--cell-map", (tmp / "m.tiff").string()}}) {
    std::vector<std::string> args = {"render", cornell(), "--spp", "1", "--width", "8", "--height", "8", "--out",
                                     (tmp / "x.exr").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::run_kappa(args);
    EXPECT_EQ(r.exit_code, 2) << extra[0] << " " << extra[1];
    EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
  }
}

/// grid2's figures per level add up to the class's; kappa of each level is
/// eq 8 over its leaves; eq 24 is undefined over leaves of differing sizes.
void expect_grid2_levels(const nlohmann::json& report, const nlohmann::json& c) {
  const auto& levels = c.at("levels");
  const auto& g = report.at("grid2");
  ASSERT_EQ(levels.size(), g.at("levels").size()) << c.dump();
  ASSERT_GE(levels.size(), 2u) << c.dump();
  double cells = 0, tests = 0;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const auto& level = levels[k];
    EXPECT_EQ(level.at("level"), int(k));
    EXPECT_EQ(level.at("N_c"), g.at("levels")[k].at("N_c"));
    cells += level.at("cells_per_ray").get<double>();
    tests += level.at("tests_per_ray").get<double>();
    EXPECT_EQ(level.at("p_tot"), level.at("cells_per_ray"));
    const double theta = g.at("levels")[k].at("theta_tot").get<double>();
    EXPECT_EQ(level.at("kappa").is_null(), theta == 0 || level.at("cells_per_ray").get<double>() == 0) << k;
  }
  EXPECT_NEAR(cells, c.at("cells_per_ray").get<double>(), 1e-9 * cells);
  EXPECT_NEAR(tests, c.at("tests_per_ray").get<double>(), 1e-9 * (1 + tests));
  EXPECT_TRUE(c.at("cells_per_ray_predicted").is_null());
}

TEST(Grid2Statistics, RenderCountsLeavesPerLevelIntoTheReportTheAovsAndTheCellMap) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"render", cornell(), "--accel", "grid2", "--spp", "2", "--width", "24", "--height",
                                  "24", "--aov", "cost", "--out", (tmp / "x.exr").string(), "--report",
                                  (tmp / "x.json").string(), "--cell-map", (tmp / "map.exr").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  EXPECT_EQ(j.at("accel"), "grid2");
  EXPECT_FALSE(j.contains("grid"));
  const auto& all = j.at("rays").at("all");
  const double rays = all.at("count").get<double>();
  EXPECT_NEAR(channel_sum(tmp / "x.exr", "cost.cells"), all.at("cells_per_ray").get<double>() * rays, 0.5);
  const double cache_tests = j.at("rays").at("shadow").at("occluder_cache").at("tests").get<double>();  // in no walk
  EXPECT_NEAR(channel_sum(tmp / "x.exr", "cost.tests"), all.at("tests_per_ray").get<double>() * rays + cache_tests,
              0.5);
  // Leaves of two sizes projected at their own size keep the sums.
  EXPECT_NEAR(channel_sum(tmp / "map.exr", "p"), all.at("p_tot").get<double>(), 1e-3 * all.at("p_tot").get<double>());
  EXPECT_NEAR(channel_sum(tmp / "map.exr", "theta"), j.at("grid2").at("theta_tot").get<double>(), 1e-3);
  for (const char* k : {"camera", "shadow", "bounce1", "all"}) {
    SCOPED_TRACE(k);
    expect_grid2_levels(j, j.at("rays").at(k));
    const auto& c = j.at("rays").at(k);
    EXPECT_NEAR(c.at("refs_per_ray").get<double>(),
                c.at("p_avg").get<double>() * j.at("grid2").at("theta_tot").get<double>() * c.at("kappa").get<double>(),
                1e-9 * c.at("refs_per_ray").get<double>());
  }
}

TEST(Grid2Statistics, CastReportsItsSectionAndLevels) {
  const auto j = cast_report({"--accel", "grid2", "--rays", "lines", "--n", "5000"});
  EXPECT_EQ(j.at("accel"), "grid2");
  for (const char* key : {"top_res", "top_cell_size", "refined", "N_c", "N", "build_s", "bytes", "theta_tot",
                          "theta_avg", "theta_max", "empty_fraction", "degenerate", "levels"})
    EXPECT_TRUE(j.at("grid2").contains(key)) << key;
  EXPECT_FALSE(j.at("rays").at("lines").contains("p_tot_predicted"));  // eq 22 needs one cell size
  expect_grid2_levels(j, j.at("rays").at("lines"));
}

/// Inside "sample", eq 25 holds with the class's sigma_theta and the grid's
/// theta_avg: 1 + (sigma_p / p_avg)(sigma_theta / theta_avg) r = kappa_eq25.
void expect_sample_reproduces_eq25(const nlohmann::json& c, double theta_avg) {
  const auto& s = c.at("sample");
  ASSERT_TRUE(s.is_object());
  ASSERT_TRUE(s.at("r").is_number());
  const double eq25 = 1.0 + s.at("sigma_p").get<double>() / s.at("p_avg").get<double>() *
                                c.at("sigma_theta").get<double>() / theta_avg * s.at("r").get<double>();
  EXPECT_NEAR(eq25, s.at("kappa_eq25").get<double>(), 1e-12 * eq25);
}

// Per-thread counters (2 threads x 64^3 cells) that do not fit beside the
// grid fall back to one shared set counting 1 ray in 64: per-cell estimates
// from the sample, exact totals.
TEST(Cast, PerThreadCountersOverTheBudgetFallBackToOneSampledSet) {
  const std::vector<std::string> args = {"--rays", "lines", "--n", "64000", "--grid-res", "64", "--threads", "2"};
  const auto full = cast_report(args);
  const std::uint64_t cells = 64 * 64 * 64;
  const std::uint64_t shared_set = cells * (8 + 4 + 16);  // stats/per_cell_budget.h, one class
  const std::uint64_t budget = full.at("grid").at("bytes").get<std::uint64_t>() + shared_set + 1000;
  std::vector<std::string> tight = args;
  tight.insert(tight.end(), {"--grid-max-bytes", std::to_string(budget)});
  const auto sampled = cast_report(tight);
  EXPECT_TRUE(sampled.at("stats").at("per_cell").get<bool>());
  EXPECT_EQ(sampled.at("stats").at("cell_sample").get<int>(), 64);
  EXPECT_NE(sampled.at("stats_note").get<std::string>().find("1 path in 64"), std::string::npos);
  const auto &a = full.at("rays").at("lines"), &b = sampled.at("rays").at("lines");
  EXPECT_EQ(a.at("sample").at("N_s").get<int>(), 64000);
  EXPECT_NEAR(b.at("sample").at("N_s").get<double>(), 1000.0, 150.0);  // 1 in 64 of 64000, binomial
  for (const char* key : {"kappa", "p_tot", "refs_per_ray"})  // from the totals: exact either way
    EXPECT_NEAR(a.at(key).get<double>(), b.at(key).get<double>(), 1e-9 * a.at(key).get<double>()) << key;
  const double theta_avg = full.at("grid").at("theta_avg").get<double>();
  expect_sample_reproduces_eq25(a, theta_avg);
  expect_sample_reproduces_eq25(b, theta_avg);
}

}  // namespace
}  // namespace kappa
