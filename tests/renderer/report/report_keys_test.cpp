// Every key stats/README.md documents for the report is in the reports Kappa
// writes: read off the README's report block, looked for in a render's and in
// casts' reports (lines, segments, and one whose per-cell counts were sampled
// for memory, which carries stats_note).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "stats/builtin_calibration.h"
#include "stats/calibration.h"
#include "test_util.h"

namespace kappa {
namespace {

struct DocumentedKeys {
  std::set<std::string> top;  ///< the report's top-level keys
  std::set<std::string> all;  ///< every key, at any depth
};

/// The keys of the ``` block under "## Report" in stats/README.md.
DocumentedKeys documented_keys() {
  std::ifstream in(test::source_dir() / "stats" / "README.md");
  std::string line, block;
  bool in_section = false, in_block = false;
  while (std::getline(in, line)) {
    if (line.rfind("## Report", 0) == 0) in_section = true;
    else if (in_section && line.rfind("```", 0) == 0) {
      if (in_block) break;
      in_block = true;
    } else if (in_block) {
      block += line + "\n";
    }
  }
  DocumentedKeys keys;
  static const std::regex leading(R"(^([a-z_][a-z_0-9]*(, [a-z_][a-z_0-9]*)*)  )");
  static const std::regex name(R"([A-Za-z_][A-Za-z_0-9]*)");
  std::istringstream lines(block);
  int depth = 0;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (depth == 0 && std::regex_search(line, m, leading)) {
      std::istringstream names(m[1].str());
      for (std::string key; std::getline(names, key, ',');) {
        key.erase(0, key.find_first_not_of(' '));
        keys.top.insert(key), keys.all.insert(key);
      }
    }
    // Names inside braces are keys, except what brackets or parentheses
    // qualify ([nx,ny,nz], (lines only)) and the CLASS placeholder.
    int skip = 0;
    std::string word;
    const auto flush = [&] {
      if (!word.empty() && depth > 0 && skip == 0 && word != "CLASS") keys.all.insert(word);
      word.clear();
    };
    for (char c : line) {
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
        word += c;
        continue;
      }
      flush();
      if (c == '{') ++depth;
      else if (c == '}') --depth;
      else if (c == '[' || c == '(') ++skip;
      else if (c == ']' || c == ')') --skip;
    }
    flush();
  }
  return keys;
}

void collect(const nlohmann::json& j, std::set<std::string>& into) {
  if (j.is_array()) {  // lists of objects (grid2's levels): their keys too
    for (const auto& element : j) collect(element, into);
    return;
  }
  if (!j.is_object()) return;
  for (const auto& [key, value] : j.items()) {
    into.insert(key);
    collect(value, into);
  }
}

nlohmann::json report_of(std::vector<std::string> args) {
  test::TempDir tmp;
  args.insert(args.end(), {"--report", (tmp / "r.json").string(), "--quiet"});
  const auto r = test::run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  return nlohmann::json::parse(test::read_file(tmp / "r.json"));
}

TEST(ReportKeys, EveryDocumentedKeyIsInTheReports) {
  const DocumentedKeys documented = documented_keys();
  ASSERT_GE(documented.top.size(), 10u) << "the README's report block was not found";
  ASSERT_GE(documented.all.size(), 50u);
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  test::TempDir tmp;
  // A calibration file, so that the render's cost section is filled from
  // one (the built-in constants, written as calibrate writes them; running
  // calibrate here took 2.5 of the ASan suite's 15 minutes).
  // With a coherent model for the grid, which the built-in constants lack.
  Calibration calibration = builtin_calibration();
  calibration.coherent = coherent_model(calibration.extended.cache_bytes);
  for (std::size_t k = 0; k < calibration.extended.ns.size(); ++k) calibration.coherent->ns[k] = calibration.extended.ns[k];
  test::write_file(tmp / "cal.json", to_json(calibration).dump(2));
  const nlohmann::json render = report_of({"render", scene, "--accel", "grid", "--spp", "2", "--width", "32", "--height", "32", "--out",
                                           (tmp / "x.exr").string(), "--calibration", (tmp / "cal.json").string()});
  ASSERT_TRUE(render.at("cost").is_object());
  // A budgeted render: the settings of its budgets; its grid chosen by the model: grid_choice.
  const nlohmann::json budgeted =
      report_of({"render", scene, "--spp", "16", "--width", "16", "--height", "16", "--time-budget", "1h",
                 "--target-relmse", "0.5", "--adaptive", "--accel", "auto", "--grid-res", "model", "--out",
                 (tmp / "b.exr").string()});
  ASSERT_TRUE(budgeted.at("grid_choice").is_object());
  ASSERT_TRUE(budgeted.at("accel_choice").contains("reason"));
  // --accel auto with nothing counted per cell: a pilot and both predictions.
  const nlohmann::json chosen = report_of({"render", scene, "--spp", "2", "--width", "16", "--height", "16", "--stats",
                                           "off", "--accel", "auto", "--out", (tmp / "c.exr").string()});
  ASSERT_TRUE(chosen.at("accel_choice").contains("pilot"));
  const nlohmann::json lines = report_of({"cast", scene, "--rays", "lines", "--n", "2000"});
  const nlohmann::json segments = report_of({"cast", scene, "--rays", "segments", "--n", "2000"});
  // Per-thread counters of 2 threads over 64^3 cells do not fit: one shared sampled set.
  const nlohmann::json sampled = report_of({"cast", scene, "--rays", "lines", "--n", "2000", "--grid-res", "64",
                                            "--threads", "2", "--grid-max-bytes", "9000000"});
  ASSERT_TRUE(sampled.contains("stats_note"));
  // grid2's section, in place of grid's, and its levels per class.
  const nlohmann::json grid2_render = report_of({"render", scene, "--accel", "grid2", "--spp", "1", "--width", "16",
                                                 "--height", "16", "--out", (tmp / "g.exr").string()});
  const nlohmann::json grid2_lines = report_of({"cast", scene, "--accel", "grid2", "--rays", "lines", "--n", "2000"});
  // Textures, cut-outs and an environment image: the images section filled.
  test::write_file(tmp / "sky.json",
                   nlohmann::json{{"meshes", {(test::assets_dir() / "textured-box" / "textured_box.obj").string()}},
                                  {"environment", (test::assets_dir() / "sky" / "sky.hdr").string()},
                                  {"environment_rotation_deg", 30}}
                       .dump());
  const nlohmann::json textured = report_of({"render", (tmp / "sky.json").string(), "--spp", "1", "--width", "16",
                                             "--height", "16", "--out", (tmp / "t.exr").string()});
  ASSERT_TRUE(textured.at("images").at("environment_image").is_object());
  ASSERT_TRUE(textured.at("images").at("texture_cache").is_object());
  // A glTF scene: its file's counts and the camera it was seen through.
  const nlohmann::json gltf = report_of({"render", (test::assets_dir() / "gltf" / "cameras.gltf").string(), "--spp",
                                         "1", "--width", "16", "--height", "8", "--out", (tmp / "l.exr").string()});
  ASSERT_TRUE(gltf.at("camera").is_object());
  std::set<std::string> seen;
  for (const auto* j :
       {&render, &budgeted, &chosen, &lines, &segments, &sampled, &grid2_render, &grid2_lines, &textured, &gltf})
    collect(*j, seen);
  // kappa-mpi's own section, from one rank started without mpirun (MPI's
  // singleton); where kappa-mpi is not built, its keys are not asked for.
  const std::set<std::string> mpi_only = {"mpi", "ranks", "threads_per_rank", "per_rank", "rank", "host",
                                          "tiles", "imbalance", "tile_size", "tile_seconds", "first_pass_order",
                                          "tile_predicted"};
#ifdef KAPPA_MPI_BINARY
  const nlohmann::json mpi_render = [&] {
    const std::string cmd = test::shell_quote(KAPPA_MPI_BINARY) + " render " + test::shell_quote(scene) +
                            " --spp 1 --width 16 --height 16 -q --out " + test::shell_quote((tmp / "m.exr").string()) +
                            " --report " + test::shell_quote((tmp / "m.json").string()) + " </dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return nlohmann::json::parse(test::read_file(tmp / "m.json"));
  }();
  ASSERT_TRUE(mpi_render.at("mpi").is_object());
  collect(mpi_render, seen);
#else
  for (const auto& key : mpi_only) seen.insert(key);
#endif
  for (const auto& key : documented.all) EXPECT_TRUE(seen.count(key)) << key << " is documented but in no report";
  // Top-level keys: in a render's report and in a cast's (render is null in a
  // cast, cast absent from a render, stats_note only when there is a note).
  // The accelerator's own section is the one of the accelerator that ran:
  // grid in the default reports, grid2 in grid2's.
  for (const auto& key : documented.top) {
    if (mpi_only.count(key)) continue;  // kappa-mpi's reports only: above
    const bool grid2_only = key == "grid2", grid_only = key == "grid";
    if (key != "cast" && key != "stats_note") {
      EXPECT_TRUE((grid2_only ? grid2_render : render).contains(key)) << key << " (render)";
      if (!grid_only) {
        EXPECT_TRUE(grid2_render.contains(key)) << key << " (grid2 render)";
      }
    }
    if (key != "stats_note") {
      EXPECT_TRUE((grid2_only ? grid2_lines : lines).contains(key)) << key << " (cast)";
      if (!grid_only) {
        EXPECT_TRUE(grid2_lines.contains(key)) << key << " (grid2 cast)";
      }
    }
  }
  // The version the README documents is the one the reports carry.
  std::ifstream readme(test::source_dir() / "stats" / "README.md");
  const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
  std::smatch version;
  ASSERT_TRUE(std::regex_search(text, version, std::regex(R"(\nschema_version +([0-9]+))")));
  for (const auto* j : {&render, &lines, &grid2_render}) EXPECT_EQ(j->at("schema_version").get<int>(), std::stoi(version[1].str()));
  // And nothing undocumented at the top.
  for (const auto* j : {&render, &lines, &sampled, &grid2_render, &grid2_lines})
    for (const auto& [key, value] : j->items()) EXPECT_TRUE(documented.top.count(key)) << key << " is not documented";
}

}  // namespace
}  // namespace kappa
