// kappa render --accel auto: the exact accelerator the models predict
// fastest for the frame, the report's account of why, and the image, bitwise
// the same whichever exact accelerator ran.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "renderer/commands/exr_pixels.h"
#include "renderer/render/accel_choice.h"
#include "renderer/scene/scene_loader.h"
#include "stats/builtin_calibration.h"
#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

/// The camera inside a tetrahedron: 4 triangles, every ray hits one, and a
/// naive query's 4 tests cost less than a grid's walk to its hit (measured:
/// tools/ab.sh, 0.22 s naive against 0.29 s grid at 128 x 128 x 16 spp).
std::filesystem::path four_triangles(const test::TempDir& tmp) {
  test::write_file(tmp / "tet.obj", "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  test::write_file(tmp / "tet.json", R"({"meshes": ["tet.obj"], "environment": [1, 1, 1],
    "camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "vfov_deg": 60},
    "film": {"width": 32, "height": 32}})");
  return tmp / "tet.json";
}

/// A detailed sphere (3,968 triangles, radius 0.05) filling the view, over a
/// 100-unit floor: the grid's cells are about 2 units, so one of them holds
/// the whole sphere and each ray to it tests every triangle (as naive does),
/// while grid2 refines that cell down to leaves of a few triangles.
std::filesystem::path small_sphere_over_a_large_floor(const test::TempDir& tmp) {
  constexpr int kRings = 32, kSegments = 64;
  constexpr double kPi = 3.14159265358979323846;
  std::string obj = "v -50 -50 -50\nv 50 -50 -50\nv 50 -50 50\nv -50 -50 50\nf 1 3 2\nf 1 4 3\n";
  for (int r = 0; r <= kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      const double theta = kPi * r / kRings, phi = 2 * kPi * s / kSegments;
      obj += "v " + std::to_string(0.05 * std::sin(theta) * std::cos(phi)) + " " + std::to_string(0.05 * std::cos(theta)) +
             " " + std::to_string(0.05 * std::sin(theta) * std::sin(phi)) + "\n";
    }
  const auto vertex = [&](int r, int s) { return std::to_string(5 + r * kSegments + s % kSegments); };
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      // Not the triangles with two vertices at a pole.
      if (r + 1 < kRings) obj += "f " + vertex(r, s) + " " + vertex(r + 1, s) + " " + vertex(r + 1, s + 1) + "\n";
      if (r > 0) obj += "f " + vertex(r, s) + " " + vertex(r + 1, s + 1) + " " + vertex(r, s + 1) + "\n";
    }
  test::write_file(tmp / "sphere.obj", obj);
  test::write_file(tmp / "sphere.json", R"({"meshes": ["sphere.obj"], "environment": [1, 1, 1],
    "camera": {"eye": [0, 0, 0.2], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 30},
    "film": {"width": 32, "height": 32}})");
  return tmp / "sphere.json";
}

nlohmann::json render_report(const std::vector<std::string>& extra, const test::TempDir& tmp, const std::string& name) {
  std::vector<std::string> args = extra;
  args.insert(args.end(), {"--out", (tmp / (name + ".exr")).string(), "--report", (tmp / (name + ".json")).string(),
                           "--quiet"});
  const auto r = run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(r.std_err.empty()) << r.std_err;  // no notice on a valid scene
  return nlohmann::json::parse(test::read_file(tmp / (name + ".json")));
}

TEST(AccelChoice, OnFourTrianglesWithStatisticsOffAutoRunsNaiveAndTheImageIsTheGrids) {
  test::TempDir tmp;
  const std::vector<std::string> frame = {"render", four_triangles(tmp).string(), "--spp", "2", "--width", "32",
                                          "--height", "32", "--stats", "off"};
  auto args = frame;
  args.insert(args.end(), {"--accel", "auto"});
  const auto j = render_report(args, tmp, "auto");
  EXPECT_EQ(j.at("accel"), "naive");
  EXPECT_EQ(j.at("render").at("settings").at("accel"), "auto");
  const auto& choice = j.at("accel_choice");
  ASSERT_TRUE(choice.is_object());
  EXPECT_EQ(choice.at("requested"), "auto");
  EXPECT_EQ(choice.at("chosen"), "naive");
  EXPECT_EQ(choice.at("candidates"), nlohmann::json::array({"naive", "grid", "grid2"}));
  const double naive_s = choice.at("predicted_s").at("naive").get<double>();
  EXPECT_GT(naive_s, 0.0);
  EXPECT_LT(naive_s, choice.at("predicted_s").at("grid").get<double>());
  EXPECT_LT(naive_s, choice.at("predicted_s").at("grid2").get<double>());
  EXPECT_GT(choice.at("pilot").at("rays").get<double>(), 1000.0);
  EXPECT_TRUE(j.at("grid_choice").is_null());
  args = frame;
  args.insert(args.end(), {"--accel", "grid"});
  const auto g = render_report(args, tmp, "grid");
  EXPECT_TRUE(g.at("accel_choice").is_null());
  EXPECT_TRUE(test::bitwise_equal(test::exr_rgb(tmp / "auto.exr"), test::exr_rgb(tmp / "grid.exr")));
}

TEST(AccelChoice, OnTheBunnyAutoRunsTheGridAtTheResolutionAsked) {
  test::TempDir tmp;
  const std::string bunny = (test::assets_dir() / "bunny-lowres" / "scene_lowres.json").string();
  const std::vector<std::string> frame = {"render", bunny, "--spp", "1", "--width", "48", "--height", "48", "--stats",
                                          "off", "--accel", "auto"};
  const auto j = render_report(frame, tmp, "auto");
  EXPECT_EQ(j.at("accel"), "grid");
  EXPECT_EQ(j.at("accel_choice").at("chosen"), "grid");
  EXPECT_GT(j.at("accel_choice").at("predicted_s").at("naive").get<double>(),
            10 * j.at("accel_choice").at("predicted_s").at("grid").get<double>());
  // With --grid-res model too: one pilot, and the grid's prediction is the model's choice's.
  auto args = frame;
  args.insert(args.end(), {"--grid-res", "model"});
  const auto m = render_report(args, tmp, "model");
  EXPECT_EQ(m.at("accel"), "grid");
  ASSERT_TRUE(m.at("grid_choice").is_object());
  EXPECT_EQ(m.at("accel_choice").at("predicted_s").at("grid"), m.at("grid_choice").at("predicted_s"));
  EXPECT_EQ(m.at("accel_choice").at("pilot").at("rays"), m.at("grid_choice").at("pilot").at("rays"));
}

TEST(AccelChoice, OnASmallDetailedObjectInALargeSceneAutoRunsGrid2AndTheImageIsTheGrids) {
  test::TempDir tmp;
  const std::vector<std::string> frame = {"render", small_sphere_over_a_large_floor(tmp).string(), "--spp", "2",
                                          "--stats", "off"};
  auto args = frame;
  args.insert(args.end(), {"--accel", "auto"});
  const auto j = render_report(args, tmp, "auto");
  EXPECT_EQ(j.at("accel"), "grid2");
  const auto& choice = j.at("accel_choice");
  EXPECT_EQ(choice.at("chosen"), "grid2");
  const auto& predicted = choice.at("predicted_s");
  // Every ray to the sphere tests all its triangles in the grid's one cell
  // (and in naive's list); grid2's leaves hold a few each.
  EXPECT_LT(5 * predicted.at("grid2").get<double>(), predicted.at("grid").get<double>()) << predicted;
  EXPECT_LT(5 * predicted.at("grid2").get<double>(), predicted.at("naive").get<double>()) << predicted;
  EXPECT_TRUE(j.at("grid_choice").is_null());
  EXPECT_TRUE(j.at("grid2").is_object());
  args = frame;
  args.insert(args.end(), {"--accel", "grid"});
  render_report(args, tmp, "grid");
  EXPECT_TRUE(test::bitwise_equal(test::exr_rgb(tmp / "auto.exr"), test::exr_rgb(tmp / "grid.exr")));
}

/// The phases a build of the frame's accelerator names, in order.
std::vector<std::string> build_phases(const Scene& scene, const AccelRequest& request, std::string& chosen) {
  TaskProgress progress;
  std::vector<std::string> phases;
  progress.set_observer([&](const TaskProgress::Snapshot& s) { phases.push_back(s.phase); });
  const FrameAccelerator out = build_frame_accelerator(scene, RenderSettings{}, request, builtin_calibration(), &progress);
  chosen = out.accel_choice.is_null() ? request.accel : out.accel_choice.at("chosen").get<std::string>();
  return phases;
}

bool builds_a_grid(const std::vector<std::string>& phases) {
  for (const std::string& phase : phases)
    if (phase.rfind("grid ", 0) == 0) return true;  // "grid RES: counting cells", not "grid2 RES: ..."
  return false;
}

TEST(AccelChoice, WhenGrid2IsChosenNoGridIsBuiltNotEvenForThePilot) {
  test::TempDir tmp;
  Warnings warnings;
  const Scene scene = load_scene(small_sphere_over_a_large_floor(tmp), warnings);
  AccelRequest request;
  request.frame_paths = double(scene.width) * double(scene.height) * 16;
  request.accel = "grid";  // the observer sees a grid's build
  std::string chosen;
  EXPECT_TRUE(builds_a_grid(build_phases(scene, request, chosen)));
  // auto predicts the grid from a counting walk of the pilot's segments and
  // runs the pilot through grid2, which it builds in any case.
  request.accel = "auto";
  for (const char* grid_res : {"auto", "model", "24"}) {
    request.build.grid_res = grid_res;
    const auto phases = build_phases(scene, request, chosen);
    EXPECT_EQ(chosen, "grid2") << grid_res;
    EXPECT_FALSE(builds_a_grid(phases)) << grid_res << ": " << ::testing::PrintToString(phases);
  }
}

TEST(AccelChoice, ARenderThatCountsCellsChoosesBetweenTheCellBasedAccelerators) {
  test::TempDir tmp;
  const auto obj = four_triangles(tmp).string();
  for (const std::vector<std::string>& asks :
       {std::vector<std::string>{}, std::vector<std::string>{"--aov", "cost"},
        std::vector<std::string>{"--cell-map", (tmp / "map.png").string()}}) {
    std::vector<std::string> args = {"render", obj, "--spp", "1", "--width", "16", "--height", "16", "--accel", "auto"};
    args.insert(args.end(), asks.begin(), asks.end());
    const auto j = render_report(args, tmp, "stats");
    SCOPED_TRACE(::testing::PrintToString(asks));
    const auto& choice = j.at("accel_choice");
    EXPECT_EQ(choice.at("candidates"), nlohmann::json::array({"grid", "grid2"}));
    EXPECT_TRUE(choice.contains("reason"));
    EXPECT_TRUE(choice.contains("pilot"));
    EXPECT_FALSE(choice.at("predicted_s").contains("naive"));
    const double grid_s = choice.at("predicted_s").at("grid").get<double>();
    const double grid2_s = choice.at("predicted_s").at("grid2").get<double>();
    const double margin = choice.at("grid2_margin").get<double>();
    EXPECT_GT(margin, 0.0);  // the built-in constants' fit is not exact
    EXPECT_EQ(j.at("accel"), grid2_s * (1 + margin) < grid_s ? "grid2" : "grid");
    EXPECT_EQ(choice.at("chosen"), j.at("accel"));
    EXPECT_TRUE(j.at("rays").at("camera").at("kappa").is_number());  // --stats on, the default: kappa is reported
  }
}

TEST(AccelChoice, GridResModelChoosesByTheCoherentModelAndAutoByTheExtendedOne) {
  // A calibration with a coherent model (the built-in constants have one):
  // --grid-res model predicts with it; --accel auto weighs the grid against
  // grid2 by the extended model, also for the resolution it would run.
  test::TempDir tmp;
  nlohmann::json cal = to_json(builtin_calibration());
  ASSERT_TRUE(cal.at("coherent").at("grid").is_object());
  test::write_file(tmp / "cal.json", cal.dump());
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const std::vector<std::string> frame = {"render", scene, "--spp", "1", "--width", "32", "--height", "32",
                                          "--calibration", (tmp / "cal.json").string()};
  auto args = frame;
  args.insert(args.end(), {"--accel", "grid", "--grid-res", "model"});
  EXPECT_EQ(render_report(args, tmp, "model").at("grid_choice").at("model"), "coherent");
  args = frame;
  args.insert(args.end(), {"--accel", "auto", "--grid-res", "model"});
  const auto both = render_report(args, tmp, "auto");
  EXPECT_EQ(both.at("accel_choice").at("models"), nlohmann::json({{"grid", "extended"}, {"grid2", "extended"}}));
  // On the Cornell box auto runs the grid at the model's resolution: that choice's model too.
  ASSERT_EQ(both.at("accel_choice").at("chosen"), "grid") << both.at("accel_choice");
  EXPECT_EQ(both.at("grid_choice").at("model"), "extended");
  // Without a coherent model, --grid-res model falls back to the extended one.
  nlohmann::json without = cal;
  without["coherent"] = nullptr;
  test::write_file(tmp / "cal.json", without.dump());
  args = frame;
  args.insert(args.end(), {"--accel", "grid", "--grid-res", "model"});
  EXPECT_EQ(render_report(args, tmp, "fallback").at("grid_choice").at("model"), "extended");
}

TEST(AccelChoice, AutoIsRenderOnly) {
  test::TempDir tmp;
  const auto obj = four_triangles(tmp).string();
  for (const char* command : {"cast", "bench"}) {
    const auto r = run_kappa({command, obj, "--accel", "auto", "--n", "10"});
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.std_err.find("--accel"), std::string::npos) << r.std_err;
  }
}

}  // namespace
}  // namespace kappa
