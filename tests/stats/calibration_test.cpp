// The cost model's constants: the fit recovers known values, files round-trip,
// and a calibrated render reports predicted beside measured time.
#include "stats/calibration.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "accel/input_error.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(Calibration, FitRecoversExactConstants) {
  // seconds = T0 + cells Ts + refs Th with T0 = 30 ns, Ts = 5 ns, Th = 8 ns.
  std::vector<CostSample> samples;
  for (double cells : {2.0, 10.0, 40.0})
    for (double refs : {1.0, 7.0, 90.0}) samples.push_back({(30 + 5 * cells + 8 * refs) * 1e-9, cells, refs, ""});
  const Calibration c = fit_calibration(samples);
  EXPECT_NEAR(c.T0_ns, 30.0, 1e-6);
  EXPECT_NEAR(c.Ts_ns, 5.0, 1e-6);
  EXPECT_NEAR(c.Th_ns, 8.0, 1e-6);
  EXPECT_NEAR(c.rms_relative_error, 0.0, 1e-9);
  EXPECT_NEAR(c.seconds_per_ray(3, 4), (30 + 15 + 32) * 1e-9, 1e-15);
}

TEST(Calibration, NoConstantComesOutNegative) {
  // Times that the free fit explains with T0 = -20 ns: the fit holds T0 at 0
  // and is then the best non-negative one, which for T0 = 0 is the least
  // squares fit of (cells, refs) alone; checked against that fit computed
  // here in closed form.
  std::vector<CostSample> samples;
  for (double cells : {10.0, 40.0, 80.0})
    for (double refs : {5.0, 20.0, 60.0}) samples.push_back({(-20 + 5 * cells + 8 * refs) * 1e-9, cells, refs, ""});
  const Calibration c = fit_calibration(samples);
  EXPECT_EQ(c.T0_ns, 0.0);
  EXPECT_GT(c.Ts_ns, 0.0);
  EXPECT_GT(c.Th_ns, 0.0);
  // Weighted normal equations of the two-term fit (weights 1/b^2).
  double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
  for (const CostSample& s : samples) {
    const double w = 1.0 / (s.seconds_per_ray * s.seconds_per_ray);
    a11 += w * s.cells_per_ray * s.cells_per_ray;
    a12 += w * s.cells_per_ray * s.refs_per_ray;
    a22 += w * s.refs_per_ray * s.refs_per_ray;
    b1 += w * s.cells_per_ray * s.seconds_per_ray;
    b2 += w * s.refs_per_ray * s.seconds_per_ray;
  }
  const double det = a11 * a22 - a12 * a12;
  EXPECT_NEAR(c.Ts_ns, (b1 * a22 - b2 * a12) / det * 1e9, 1e-6);
  EXPECT_NEAR(c.Th_ns, (a11 * b2 - a12 * b1) / det * 1e9, 1e-6);
}

TEST(Calibration, TooFewOrDegenerateMeasurementsAreRefused) {
  std::vector<CostSample> two = {{1e-7, 1, 1, ""}, {2e-7, 2, 2, ""}};
  EXPECT_THROW(fit_calibration(two), std::runtime_error);
  std::vector<CostSample> collinear = {{1e-7, 1, 1, ""}, {2e-7, 2, 2, ""}, {3e-7, 3, 3, ""}};
  EXPECT_THROW(fit_calibration(collinear), std::runtime_error);
}

TEST(Calibration, FileRoundTripAndErrors) {
  test::TempDir tmp;
  EXPECT_FALSE(load_calibration(tmp / "none.json"));
  Calibration c;
  c.T0_ns = 1.5, c.Ts_ns = 2.5, c.Th_ns = 3.5, c.samples = 9;
  test::write_file(tmp / "c.json", to_json(c).dump());
  const auto back = load_calibration(tmp / "c.json");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->Ts_ns, 2.5);
  test::write_file(tmp / "bad.json", "{\"T0_ns\": \"fast\"}");
  EXPECT_THROW(load_calibration(tmp / "bad.json"), InputError);
}

TEST(Calibration, CalibrateThenRenderReportsTheCost) {
  test::TempDir tmp;
  const auto cal = (tmp / "cal.json").string();
  const auto c = test::run_kappa({"calibrate", "--n", "2000", "--repeat", "1", "--density", "2,16", "--out", cal});
  ASSERT_EQ(c.exit_code, 0) << c.std_err;
  const auto calibration = nlohmann::json::parse(test::read_file(cal));
  EXPECT_EQ(calibration.at("samples"), 16);  // 2 scenes x 2 densities x 4 ray classes
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "2", "--width", "32", "--height", "32", "--out",
                                  (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(), "--calibration", cal});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto report = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  const auto& cost = report.at("cost");
  for (const char* key : {"T0_ns", "Ts_ns", "Th_ns", "predicted_s", "measured_s", "relative_error"})
    EXPECT_TRUE(cost.at(key).is_number()) << key;
  EXPECT_GT(cost.at("predicted_s").get<double>(), 0.0);
  EXPECT_GT(cost.at("measured_s").get<double>(), 0.0);
  // A named calibration that does not exist is an error, not a silent null.
  const auto missing = test::run_kappa({"render", scene, "--spp", "1", "--out", (tmp / "y.exr").string(),
                                        "--calibration", (tmp / "nope.json").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(tmp / "y.exr"));
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(Calibration, NonPositiveTimesAreRefused) {
  std::vector<CostSample> samples = {{1e-7, 1, 1, "a"}, {0.0, 2, 5, "b"}, {3e-7, 3, 2, "c"}};
  EXPECT_THROW(fit_calibration(samples), std::runtime_error);
}

TEST(Calibration, ABadCalibrationFileIsRefusedBeforeRendering) {
  test::TempDir tmp;
  test::write_file(tmp / "bad.json", "{\"T0_ns\": null}");
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "1000", "--out", (tmp / "x.exr").string(), "--calibration",
                                  (tmp / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
}

TEST(Calibration, RefusedPerCellStatisticsSkipTheCellMapButKeepTheImage) {
  test::TempDir tmp;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "1", "--width", "8", "--height", "8", "--out",
                                  (tmp / "x.exr").string(), "--cell-map", (tmp / "m.exr").string(), "--grid-max-bytes",
                                  "9000", "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(std::filesystem::exists(tmp / "x.exr"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "m.exr"));
  EXPECT_NE(r.std_err.find("--cell-map skipped"), std::string::npos) << r.std_err;
}

}  // namespace
}  // namespace kappa
