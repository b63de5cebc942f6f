// Every setting that changes the image is recorded: the command line rebuilt
// from the EXR header alone renders a bitwise identical image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "image_files.h"
#include "test_util.h"

namespace kappa::test {
namespace {

/// `kappa render` arguments from nothing but the image's kappa:* attributes.
std::vector<std::string> command_from_header(const ExrFile& h, const std::filesystem::path& out) {
  std::vector<std::string> args = {"render", h.string_attribute("kappa:scene"),
                                   "--accel", h.string_attribute("kappa:accel"),
                                   "--spp", std::to_string(h.int_attribute("kappa:spp")),
                                   "--max-depth", std::to_string(h.int_attribute("kappa:max_depth")),
                                   "--rr-depth", std::to_string(h.int_attribute("kappa:rr_depth")),
                                   "--width", std::to_string(h.int_attribute("kappa:width")),
                                   "--height", std::to_string(h.int_attribute("kappa:height")),
                                   "--stats", h.string_attribute("kappa:stats"),
                                   "--cell-sample", h.string_attribute("kappa:cell_sample"),
                                   "--out", out.string(), "-q"};
  const double* seed = h.double_attribute("kappa:seed");
  EXPECT_TRUE(seed) << "kappa:seed is a double";
  if (seed) {
    char digits[32];
    std::snprintf(digits, sizeof digits, "%.0f", *seed);
    args.insert(args.end(), {"--seed", digits});
  }
  if (h.int_attribute("kappa:russian_roulette", 1) == 0) args.push_back("--no-rr");
  if (const std::string aov = h.string_attribute("kappa:aov"); !aov.empty()) args.insert(args.end(), {"--aov", aov});
  if (const std::string res = h.string_attribute("kappa:grid_res"); res != "none") args.insert(args.end(), {"--grid-res", res});
  return args;
}

TEST(RenderRecord, TheCommandRebuiltFromTheExrHeaderRendersTheSameImage) {
  TempDir tmp;
  const std::string scene = (assets_dir() / "cornell-box" / "scene.json").string();
  const RunResult first = run_kappa({"render", scene, "--spp", "3", "--max-depth", "5", "--no-rr", "--seed",
                                     "9007199254740991", "--width", "24", "--height", "16", "--aov", "albedo,depth",
                                     "--grid-density", "7", "--out", (tmp / "a.exr").string(), "--report",
                                     (tmp / "a.json").string(), "-q"});
  ASSERT_EQ(first.exit_code, 0) << first.std_err;
  const ExrFile a = read_exr_file(tmp / "a.exr");
  const std::vector<std::string> again = command_from_header(a, tmp / "b.exr");
  const RunResult second = run_kappa(again);
  ASSERT_EQ(second.exit_code, 0) << second.std_err << ::testing::PrintToString(again);
  const ExrFile b = read_exr_file(tmp / "b.exr");
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  // The same record in the report, with natural types.
  const auto j = nlohmann::json::parse(read_file(tmp / "a.json"));
  const auto& s = j.at("render").at("settings");
  EXPECT_EQ(s.at("seed").get<double>(), 9007199254740991.0);
  EXPECT_EQ(s.at("max_depth").get<int>(), 5);
  EXPECT_FALSE(s.at("russian_roulette").get<bool>());
  EXPECT_EQ(s.at("input_hash").get<std::string>(), a.string_attribute("kappa:input_hash"));
  EXPECT_EQ(s.at("input_hash").get<std::string>().size(), 16u);
  EXPECT_EQ(a.int_attribute("kappa:max_depth"), 5);
  EXPECT_TRUE(a.double_attribute("kappa:rays"));
}

TEST(RenderRecord, TheInputHashFollowsTheInputFilesBytes) {
  TempDir tmp;
  std::filesystem::copy(assets_dir() / "cornell-box", tmp / "c", std::filesystem::copy_options::recursive);
  const auto hash_of_render = [&](const std::string& name) {
    const RunResult r = run_kappa({"render", (tmp / "c" / "scene.json").string(), "--spp", "1", "--width", "8",
                                   "--height", "8", "--out", (tmp / (name + ".exr")).string(), "--report",
                                   (tmp / (name + ".json")).string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.std_err;
    return nlohmann::json::parse(read_file(tmp / (name + ".json"))).at("render").at("settings").at("input_hash");
  };
  const auto before = hash_of_render("a");
  EXPECT_EQ(hash_of_render("b"), before);
  std::ofstream(tmp / "c" / "cornell_box.mtl", std::ios::app) << "# a comment changes the bytes\n";
  EXPECT_NE(hash_of_render("c"), before);
}

}  // namespace
}  // namespace kappa::test
