// Which accelerator a render runs when none is named: grid2, the fastest
// exact one; the uniform grid when only its own flags (--grid-res,
// --grid-density) are given; always the one named. converge's --vary keeps
// the base run's accelerator.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "renderer/cli/command_line.h"

namespace kappa {
namespace {

/// The accelerator `kappa ARGS...` would render with.
std::string accel_of(std::vector<std::string> args) {
  args.insert(args.begin(), "kappa");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  Command command;
  const std::optional<int> early = parse_command_line(int(argv.size()), argv.data(), command);
  EXPECT_FALSE(early.has_value()) << "the command line was refused or answered";
  if (const auto* render = std::get_if<RenderOptions>(&command)) return render->accel;
  if (const auto* converge = std::get_if<ConvergeOptions>(&command)) return converge->render.accel;
  return "(not a render)";
}

TEST(DefaultAccel, Grid2UnlessOnlyTheUniformGridsFlagsAreGiven) {
  EXPECT_EQ(accel_of({"render", "scene.json"}), "grid2");
  EXPECT_EQ(accel_of({"render", "scene.json", "--grid-res", "32"}), "grid");
  EXPECT_EQ(accel_of({"render", "scene.json", "--grid-density", "8"}), "grid");
  EXPECT_EQ(accel_of({"render", "scene.json", "--grid-res", "model"}), "grid");
  // Flags that both grids read leave the default alone.
  EXPECT_EQ(accel_of({"render", "scene.json", "--grid-max-bytes", "1000000000"}), "grid2");
  // A named accelerator is the one that runs.
  EXPECT_EQ(accel_of({"render", "scene.json", "--accel", "naive", "--grid-density", "8"}), "naive");
  EXPECT_EQ(accel_of({"render", "scene.json", "--grid-res", "16", "--accel", "grid2"}), "grid2");
  EXPECT_EQ(accel_of({"converge", "scene.json", "--reference", "r.exr", "--spp", "1,2"}), "grid2");
}

TEST(DefaultAccel, ConvergeVaryingAGridFlagKeepsTheBaseAccelerator) {
  RenderOptions base;
  base.accel = "naive";
  EXPECT_EQ(vary_render_option(base, "grid-density", "16").accel, "naive");
  EXPECT_EQ(vary_render_option(base, "grid-res", "8").accel, "naive");
  base.accel = "grid2";
  EXPECT_EQ(vary_render_option(base, "grid-res", "8").accel, "grid2");
  EXPECT_EQ(vary_render_option(base, "accel", "embree").accel, "embree");
}

}  // namespace
}  // namespace kappa
