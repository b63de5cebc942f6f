// The report's machine probe (cost.machine_probe, stats/README.md): timed
// around a frame with statistics on, set against the calibration's own probe,
// and the extended model's error with the machine's speed taken out.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "stats/builtin_calibration.h"
#include "stats/calibration.h"
#include "test_util.h"

namespace kappa {
namespace {

nlohmann::json render_report(const std::vector<std::string>& extra) {
  test::TempDir tmp;
  std::vector<std::string> args = {"render", (test::assets_dir() / "cornell-box" / "scene.json").string(),
                                   "--spp", "2", "--width", "32", "--height", "32", "--accel", "grid",
                                   "--out", (tmp / "o.exr").string(), "--report", (tmp / "r.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  return nlohmann::json::parse(test::read_file(tmp / "r.json"));
}

TEST(MachineProbeReport, IsSetAgainstTheCalibrationsProbe) {
  test::TempDir tmp;
  Calibration c;  // constants that predict something: every term 1 ns
  c.eq10.ns = {1, 1, 1};
  for (double& ns : c.extended.ns) ns = 1;
  c.probe_s = 0.004;
  test::write_file(tmp / "cal.json", to_json(c).dump());
  const nlohmann::json j = render_report({"--stats", "on", "--calibration", (tmp / "cal.json").string()});
  const nlohmann::json& probe = j.at("cost").at("machine_probe");
  const double before = probe.at("before_s").get<double>(), after = probe.at("after_s").get<double>();
  EXPECT_GT(before, 0.0);
  EXPECT_GT(after, 0.0);
  EXPECT_EQ(probe.at("calibration_s").get<double>(), 0.004);
  const double ratio = 0.5 * (before + after) / 0.004;
  EXPECT_NEAR(probe.at("slowdown").get<double>(), ratio - 1.0, 1e-12);
  const nlohmann::json& extended = j.at("cost").at("extended");
  const double predicted = extended.at("predicted_s").get<double>();
  const double measured = j.at("cost").at("measured_s").get<double>();
  EXPECT_NEAR(extended.at("relative_error_at_probe_speed").get<double>(), predicted * ratio / measured - 1.0, 1e-9);
}

TEST(MachineProbeReport, IsTimedButNotComparedWithoutACalibrationProbe) {
  // The built-in constants hold no probe time: the probe is reported, the
  // comparison is not. (Given as a file: the one beside the binary, which a
  // render uses by default, may have been made by `kappa calibrate`, with a probe.)
  test::TempDir tmp;
  test::write_file(tmp / "builtin.json", to_json(builtin_calibration()).dump());
  const nlohmann::json j = render_report({"--stats", "on", "--calibration", (tmp / "builtin.json").string()});
  const nlohmann::json& probe = j.at("cost").at("machine_probe");
  EXPECT_GT(probe.at("before_s").get<double>(), 0.0);
  EXPECT_TRUE(probe.at("calibration_s").is_null());
  EXPECT_TRUE(probe.at("slowdown").is_null());
  EXPECT_TRUE(j.at("cost").at("extended").at("relative_error_at_probe_speed").is_null());
  // With statistics off there is no cost section, so no probe to report.
  EXPECT_TRUE(render_report({"--stats", "off"}).at("cost").is_null());
}

}  // namespace
}  // namespace kappa
