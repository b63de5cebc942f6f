// `kappa sweep`: the points it measures, its counts against kappa cast's on
// the same rays and resolution, its JSON keys, its plot and its refusals.
#include <gtest/gtest.h>

#include "image_files.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "core/error.h"
#include "renderer/cli/sweep_range.h"
#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

TEST(SweepPoints, RangesAreTwoPositiveNumbersInOrder) {
  const SweepRange r = parse_sweep_range("1:1024", "--grid-density");
  EXPECT_EQ(r.from, 1.0);
  EXPECT_EQ(r.to, 1024.0);
  EXPECT_EQ(parse_sweep_range("0.5:0.5", "--grid-density").to, 0.5);
  for (const char* bad : {"", "1", "1:", ":2", "2:1", "0:4", "-1:4", "1:inf", "nan:2", "1:2:3", "1x:2", "1 :2"}) {
    try {
      parse_sweep_range(bad, "--grid-res");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--grid-res: '" + std::string(bad) + "' is not a range A:B"), std::string::npos)
          << e.what();
    }
  }
}

TEST(SweepPoints, ResolutionsAreGeometricInCellsAndListedOnce) {
  const Vec3d cube{1, 1, 1};
  const auto r = sweep_resolutions(cube, 8, 512 * 512 * 512, 7);  // 2^3 ... 2^27, a factor 2^4 a step
  ASSERT_EQ(r.size(), 7u);
  for (std::size_t k = 0; k < r.size(); ++k) {
    EXPECT_NEAR(std::log2(double(r[k].cells())), 3.0 + 4.0 * double(k), 0.5) << r[k].to_string();
  }
  EXPECT_EQ(r.front(), (GridResolution{2, 2, 2}));
  EXPECT_EQ(r.back(), (GridResolution{512, 512, 512}));
  // A tiny range: every target rounds to the same resolution, listed once.
  EXPECT_EQ(sweep_resolutions(cube, 8, 9, 5).size(), 1u);
  // One step: the start of the range.
  const auto one = sweep_resolutions(cube, 27, 1000, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], (GridResolution{3, 3, 3}));
}

TEST(Sweep, CountsAreCastsOnTheSameRaysAndEveryPointHasItsKeys) {
  test::TempDir tmp;
  const auto json_path = tmp / "sweep.json";
  const auto r = run_kappa({"sweep", cornell(), "--grid-res", "2:16", "--steps", "4", "--n", "2000", "--repeat", "2",
                            "--json", json_path.string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(json_path));
  EXPECT_EQ(j.at("N"), 32);
  ASSERT_EQ(j.at("points").size(), 16u);  // 4 resolutions x 4 classes
  std::vector<std::pair<double, std::string>> resolutions;  // (N_c, res) in the order swept
  for (const auto& p : j.at("points")) {
    for (const char* key : {"res", "N_c", "class", "seconds_per_ray", "cells_per_ray", "tests_per_ray", "theta_tot",
                            "p_tot", "kappa", "bytes", "build_s", "eq10_s_per_ray", "extended_s_per_ray"})
      ASSERT_TRUE(p.contains(key)) << key << " in " << p.dump();
    if (p.at("class") == "camera") resolutions.emplace_back(p.at("N_c").get<double>(), p.at("res").get<std::string>());
    EXPECT_GT(p.at("seconds_per_ray").get<double>(), 0.0);
    EXPECT_GE(p.at("seconds_per_ray").get<double>(), p.at("seconds_per_ray_min").get<double>());
    EXPECT_LE(p.at("seconds_per_ray").get<double>(), p.at("seconds_per_ray_max").get<double>());
    EXPECT_GT(p.at("eq10_s_per_ray").get<double>(), 0.0);
    EXPECT_GT(p.at("extended_s_per_ray").get<double>(), 0.0);
    EXPECT_GT(p.at("bytes").get<double>(), 0.0);
  }
  // N_c from 2^3 to 16^3 in 4 steps: a factor 8 a step, rounded to near-cubic cells of the box.
  ASSERT_EQ(resolutions.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(std::log2(resolutions[k].first), 3.0 + 3.0 * double(k), 0.75) << resolutions[k].second;
  const std::string res = resolutions[1].second;

  // The counting pass is kappa cast's on the same rays: the same counts at the same resolution.
  for (const char* rays : {"camera", "shadow"}) {
    const auto report_path = tmp / (std::string(rays) + ".json");
    const auto c = run_kappa({"cast", cornell(), "--rays", rays, "--n", "2000", "--grid-res", res, "--report",
                              report_path.string(), "--quiet"});
    ASSERT_EQ(c.exit_code, 0) << c.std_err;
    const auto cast = nlohmann::json::parse(test::read_file(report_path)).at("rays").at(rays);
    bool found = false;
    for (const auto& p : j.at("points")) {
      if (p.at("res") != res || p.at("class") != rays) continue;
      found = true;
      EXPECT_DOUBLE_EQ(p.at("cells_per_ray").get<double>(), cast.at("cells_per_ray").get<double>()) << rays;
      EXPECT_DOUBLE_EQ(p.at("tests_per_ray").get<double>(), cast.at("tests_per_ray").get<double>()) << rays;
      EXPECT_DOUBLE_EQ(p.at("kappa").get<double>(), cast.at("kappa").get<double>()) << rays;
    }
    EXPECT_TRUE(found) << rays;
  }
}

TEST(Sweep, PlotsOnePanelPerClassIntoAPng) {
  test::TempDir tmp;
  const auto r = run_kappa({"sweep", cornell(), "--steps", "3", "--n", "500", "--repeat", "1", "--rays",
                            "camera,shadow", "--plot", (tmp / "s.png").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const test::PngFile png = test::read_png_file(tmp / "s.png");
  // Two panels of 4.2 x 3.8 inches at 90 dpi.
  EXPECT_EQ(png.width, 756);
  EXPECT_EQ(png.height, 342);
  // Only the PNG: the plot's JSON was a temporary.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(tmp.path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST(Sweep, RefusesBothRangesABadRangeAndAPlotThatIsNotAPng) {
  test::TempDir tmp;
  const auto refused = [&](const std::vector<std::string>& extra, const std::string& message) {
    std::vector<std::string> args = {"sweep", cornell(), "--n", "100"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_kappa(args);
    EXPECT_EQ(r.exit_code, 2) << message;
    EXPECT_NE(r.std_err.find(message), std::string::npos) << r.std_err;
  };
  refused({"--grid-res", "2:8", "--grid-density", "1:4"}, "give one range, not both");
  refused({"--grid-density", "8:2"}, "--grid-density: '8:2' is not a range A:B");
  refused({"--plot", (tmp / "s.jpg").string()}, "--plot: '");
  refused({"--calibration", (tmp / "none.json").string()}, "none.json: calibration file not found");
  // A budget no point fits: the sweep says so instead of an empty table.
  refused({"--grid-max-bytes", "1"}, "no resolution of the sweep fits --grid-max-bytes");
}

}  // namespace
}  // namespace kappa
