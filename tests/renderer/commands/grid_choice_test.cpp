// kappa render --grid-res model: the report's account of the choice, the
// image it renders (bitwise that of any other resolution: the grid is exact)
// and its refusals.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "renderer/commands/exr_pixels.h"
#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

TEST(GridChoice, TheReportGivesTheChoiceAndTheImageIsTheGridsAtAnyResolution) {
  test::TempDir tmp;
  const std::vector<std::string> frame = {"render", cornell(), "--spp", "4", "--width", "48", "--height", "48", "--quiet"};
  auto args = frame;
  args.insert(args.end(), {"--grid-res", "model", "--out", (tmp / "m.exr").string(), "--report", (tmp / "m.json").string()});
  const auto r = run_kappa(args);
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(r.std_err.empty()) << r.std_err;  // no notice on a valid scene
  const auto j = nlohmann::json::parse(test::read_file(tmp / "m.json"));
  const auto& choice = j.at("grid_choice");
  ASSERT_TRUE(choice.is_object());
  EXPECT_EQ(choice.at("requested"), "model");
  const auto& res = j.at("grid").at("res");
  const std::string built = res.at(0).dump() + "x" + res.at(1).dump() + "x" + res.at(2).dump();
  EXPECT_EQ(choice.at("chosen"), built);
  EXPECT_EQ(j.at("render").at("settings").at("grid_res"), built);
  EXPECT_EQ(choice.at("frame_paths").get<double>(), 48.0 * 48 * 4);
  EXPECT_GT(choice.at("pilot").at("rays").get<double>(), 1000.0);
  EXPECT_GT(choice.at("seconds").get<double>(), 0.0);
  ASSERT_GE(choice.at("candidates").size(), 3u);
  double least = 1e300;
  bool chosen_listed = false;
  for (const auto& c : choice.at("candidates")) {
    for (const char* key : {"res", "N_c", "lambda", "theta_tot", "bytes", "traversal_s", "build_s", "predicted_s"})
      ASSERT_TRUE(c.contains(key)) << key;
    EXPECT_NEAR(c.at("predicted_s").get<double>(), c.at("traversal_s").get<double>() + c.at("build_s").get<double>(),
                1e-12);
    least = std::min(least, c.at("predicted_s").get<double>());
    if (c.at("res") == choice.at("chosen")) {
      chosen_listed = true;
      EXPECT_EQ(c.at("predicted_s"), choice.at("predicted_s"));
    }
  }
  EXPECT_TRUE(chosen_listed);
  EXPECT_LE(choice.at("predicted_s").get<double>(), 1.02 * least + 1e-15);  // the 2 % rule
  // Without a calibration file beside the binary or named: the built-in constants, said so.
  if (!std::filesystem::exists(std::filesystem::path(KAPPA_BINARY).parent_path() / "kappa_calibration.json")) {
    EXPECT_EQ(choice.at("calibration"), "built-in");
  }
  EXPECT_EQ(choice.at("calibration"), j.at("cost").at("calibration"));

  // The same image at the default resolution: every exact grid finds the same hits.
  args = frame;
  args.insert(args.end(), {"--out", (tmp / "a.exr").string(), "--report", (tmp / "a.json").string()});
  ASSERT_EQ(run_kappa(args).exit_code, 0);
  EXPECT_TRUE(test::bitwise_equal(test::exr_rgb(tmp / "m.exr"), test::exr_rgb(tmp / "a.exr")));
  EXPECT_TRUE(nlohmann::json::parse(test::read_file(tmp / "a.json")).at("grid_choice").is_null());
}

TEST(GridChoice, ModelIsRefusedWhereThereIsNoFrameOrNoGrid) {
  test::TempDir tmp;
  auto r = run_kappa({"render", cornell(), "--grid-res", "model", "--accel", "naive", "--out", (tmp / "x.exr").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.std_err.find("--grid-res model: needs --accel grid"), std::string::npos) << r.std_err;
  r = run_kappa({"cast", cornell(), "--grid-res", "model", "--n", "10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.std_err.find("--grid-res"), std::string::npos) << r.std_err;
  r = run_kappa({"bench", cornell(), "--grid-res", "model", "--n", "10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
}

TEST(GridChoice, AGridBudgetNoCandidateFitsIsRefusedBeforeRendering) {
  test::TempDir tmp;
  const auto r = run_kappa({"render", cornell(), "--grid-res", "model", "--grid-max-bytes", "64", "--stats", "off",
                            "--out", (tmp / "x.exr").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.std_err.find("no candidate resolution fits --grid-max-bytes"), std::string::npos) << r.std_err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
}

}  // namespace
}  // namespace kappa
