// `kappa cast`: every distribution runs, and the report carries the
// documented keys with numbers or null, never NaN.
#include <gtest/gtest.h>

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
                            "theta_tot_eq21", "theta_avg", "max_multiplicity", "empty_fraction"})
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
  const auto r = test::run_kappa({"render", cornell(), "--spp", "2", "--width", "24", "--height", "24", "--out",
                                  (tmp / "x.exr").string(), "--report", (tmp / "x.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  EXPECT_EQ(j.at("render").at("width"), 24);
  EXPECT_EQ(j.at("accel"), "grid");
  for (const char* cls : {"camera", "shadow", "bounce1", "bounce2", "bounce3+", "all"})
    EXPECT_TRUE(j.at("rays").at(cls).at("kappa").is_number()) << cls;
  EXPECT_TRUE(j.at("cost").is_null());
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
