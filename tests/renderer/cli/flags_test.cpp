// The command line's contract for bad options (docs/command-line.md, "Exit codes",
// and docs/bad-input.md, "## Bad input"): exit code 2, exactly one line on stderr, and no output
// file created or touched. Plus the few things that must work: --help, a
// tiny render, and the default output path.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

/// One triangle, 64x64 film: the cheapest scene that renders.
std::string good_scene() { return (assets_dir() / "malformed" / "scene_ok_control.json").string(); }

/// Every file and folder under `dir`, relative, sorted: compared before and
/// after a run, it shows anything Kappa created (output, temporary, out/).
std::vector<std::string> tree(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.push_back(fs::relative(entry.path(), dir).string() + (entry.is_directory() ? "/" : ""));
  std::sort(names.begin(), names.end());
  return names;
}

void expect_one_line_refusal(const RunResult& r) {
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  const std::vector<std::string> lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << "a refusal is exactly one line on stderr:\n" << r.std_err;
  EXPECT_EQ(lines[0].rfind("kappa: error: ", 0), 0u) << lines[0];
}

// ---------------------------------------------------------------------------
// Refusals: each runs in an empty temp folder (also the working directory, so
// a wrongly accepted run without --out would leave out/ there and be seen).

struct BadCase {
  std::string name;
  /// Prepares the temp folder (e.g. a directory where a file is expected).
  std::function<void(const fs::path& tmp)> setup;
  std::function<std::vector<std::string>(const fs::path& tmp)> args;
};

/// `kappa render <good scene> <flags> --out tmp/x.exr --quiet`
BadCase bad_flags(std::string name, std::vector<std::string> flags) {
  return {std::move(name), nullptr, [flags](const fs::path& tmp) {
            std::vector<std::string> args = {"render", good_scene()};
            args.insert(args.end(), flags.begin(), flags.end());
            args.insert(args.end(), {"--out", (tmp / "x.exr").string(), "--quiet"});
            return args;
          }};
}

/// `kappa render <good scene> --out <out(tmp)> --quiet`
BadCase bad_out(std::string name, std::function<void(const fs::path&)> setup,
                std::function<std::string(const fs::path&)> out) {
  return {std::move(name), std::move(setup), [out](const fs::path& tmp) {
            return std::vector<std::string>{"render", good_scene(), "--out", out(tmp), "--quiet"};
          }};
}

/// `kappa render <scene(tmp)> --out tmp/x.exr --quiet`
BadCase bad_scene(std::string name, std::function<void(const fs::path&)> setup,
                  std::function<std::string(const fs::path&)> scene) {
  return {std::move(name), std::move(setup), [scene](const fs::path& tmp) {
            return std::vector<std::string>{"render", scene(tmp), "--out", (tmp / "x.exr").string(), "--quiet"};
          }};
}

void make_dir(const fs::path& p) { fs::create_directories(p); }

std::vector<BadCase> bad_cases() {
  return {
      bad_flags("UnknownFlag", {"--bogus"}),
      bad_flags("SppZero", {"--spp", "0"}),
      bad_flags("SppNegative", {"--spp", "-3"}),
      bad_flags("SppNotANumber", {"--spp", "abc"}),
      bad_flags("WidthNegative", {"--width", "-5"}),
      bad_flags("HeightZero", {"--height", "0"}),
      bad_flags("MaxDepthNegative", {"--max-depth", "-1"}),
      bad_flags("ThreadsZero", {"--threads", "0"}),
      bad_flags("UnknownAccel", {"--accel", "nosuch"}),
      bad_flags("UnknownAov", {"--aov", "bogus"}),
      bad_flags("StatsMaybe", {"--stats", "maybe"}),
      bad_flags("CellSampleZero", {"--cell-sample", "0"}),
      bad_flags("CellSampleFraction", {"--cell-sample", "1.5"}),
      bad_flags("CellSampleWord", {"--cell-sample", "some"}),
      bad_flags("CellSampleHuge", {"--cell-sample", "99999999999999999999"}),
      bad_flags("GridResZero", {"--grid-res", "0"}),
      bad_flags("GridResMalformed", {"--grid-res", "64x32"}),
      bad_flags("GridResNotANumber", {"--grid-res", "big"}),
      bad_flags("GridDensityZero", {"--grid-density", "0"}),
      // Numbers are never silently changed: NaN and infinities passed CLI11's
      // ranges, and a negative unsigned value wrapped to 2^64 - 1.
      bad_flags("GridDensityNaN", {"--grid-density", "nan"}),
      bad_flags("GridDensityInfinite", {"--grid-density", "inf"}),
      bad_flags("SeedNegative", {"--seed", "-1"}),
      bad_flags("SeedOver2To53", {"--seed", "9007199254740992"}),
      bad_flags("SeedOver2To64", {"--seed", "18446744073709551616"}),
      bad_flags("GridMaxBytesNegative", {"--grid-max-bytes", "-5"}),
      bad_flags("GridOverMemoryLimit", {"--grid-res", "1024", "--grid-max-bytes", "1000000"}),
      // Budgets: a duration has a unit; a target is a number above 0; the
      // adaptive flags need what they refine.
      bad_flags("TimeBudgetBareNumber", {"--time-budget", "10"}),
      bad_flags("TimeBudgetUnknownUnit", {"--time-budget", "10min"}),
      bad_flags("TimeBudgetZero", {"--time-budget", "0s"}),
      bad_flags("TimeBudgetNegative", {"--time-budget", "-2s"}),
      bad_flags("TimeBudgetNaN", {"--time-budget", "nans"}),
      bad_flags("TimeBudgetOverAYear", {"--time-budget", "9000h"}),
      bad_flags("TargetRelmseZero", {"--target-relmse", "0"}),
      bad_flags("TargetRelmseNaN", {"--target-relmse", "nan"}),
      bad_flags("TargetRelmseWord", {"--target-relmse", "low"}),
      bad_flags("AdaptiveWithoutTarget", {"--adaptive"}),
      bad_flags("AdaptiveMinSppWithoutAdaptive", {"--target-relmse", "0.1", "--adaptive-min-spp", "4"}),
      bad_flags("SamplerUnknown", {"--sampler", "halton"}),
      bad_flags("StratifiedWithABudget", {"--sampler", "stratified", "--time-budget", "1s"}),
      bad_flags("TimeBudgetEmpty", {"--time-budget", ""}),
      bad_flags("AdaptiveMinSppZero", {"--target-relmse", "0.1", "--adaptive", "--adaptive-min-spp", "0"}),
      bad_out("OutNotExr", nullptr, [](const fs::path& tmp) { return (tmp / "x.png").string(); }),
      bad_out("OutInMissingFolder", nullptr, [](const fs::path& tmp) { return (tmp / "nope" / "x.exr").string(); }),
      bad_out("OutIsDirectory", [](const fs::path& tmp) { make_dir(tmp / "d.exr"); },
              [](const fs::path& tmp) { return (tmp / "d.exr").string(); }),
      // Root ignores permission bits, but nothing can create a file in /proc.
      bad_out("OutUnwritable", nullptr, [](const fs::path&) { return std::string("/proc/kappa-test.exr"); }),
      bad_scene("SceneMissing", nullptr, [](const fs::path& tmp) { return (tmp / "nosuch.json").string(); }),
      bad_scene("SceneIsPlainDirectory", nullptr, [](const fs::path& tmp) { return tmp.string(); }),
      bad_scene("SceneIsDirectoryNamedJson", [](const fs::path& tmp) { make_dir(tmp / "s.json"); },
                [](const fs::path& tmp) { return (tmp / "s.json").string(); }),
      bad_scene("SceneIsDirectoryNamedObj", [](const fs::path& tmp) { make_dir(tmp / "s.obj"); },
                [](const fs::path& tmp) { return (tmp / "s.obj").string(); }),
      {"NoSubcommand", nullptr, [](const fs::path&) { return std::vector<std::string>{}; }},
      {"UnknownSubcommand", nullptr,
       [](const fs::path&) { return std::vector<std::string>{"frobnicate", good_scene()}; }},
  };
}

// Names the case in gtest's listings instead of dumping the struct's bytes.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadOption : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadOption, RefusedWithOneLineAndNoOutput) {
  const BadCase& c = GetParam();
  TempDir tmp;
  if (c.setup) c.setup(tmp.path());
  const std::vector<std::string> before = tree(tmp.path());
  const std::vector<std::string> args = c.args(tmp.path());
  SCOPED_TRACE("kappa " + ::testing::PrintToString(args));
  const RunResult r = run_kappa(args, tmp.path());
  expect_one_line_refusal(r);
  EXPECT_EQ(tree(tmp.path()), before) << "the refused run created or removed files";
}

INSTANTIATE_TEST_SUITE_P(Cli, BadOption, ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

// ---------------------------------------------------------------------------
// An existing output file survives every kind of refusal byte for byte: the
// output is only ever replaced by a finished render.

TEST(ExistingOutput, UntouchedByRefusals) {
  TempDir tmp;
  const fs::path out = tmp / "x.exr";
  const std::string bytes = "not an EXR: a previous render the user wants to keep\n";
  write_file(out, bytes);
  const std::string bad_mesh = (assets_dir() / "malformed" / "scene_bad_mesh_inside.json").string();
  const std::vector<std::vector<std::string>> refused = {
      {"render", (tmp / "nosuch.json").string()},  // missing scene
      {"render", good_scene(), "--spp", "0"},      // bad flag
      {"render", good_scene(), "--aov", "bogus"},  // bad value found after parsing
      {"render", bad_mesh},                        // the scene loader refuses
  };
  for (std::vector<std::string> args : refused) {
    args.insert(args.end(), {"--out", out.string(), "--quiet"});
    SCOPED_TRACE("kappa " + ::testing::PrintToString(args));
    const RunResult r = run_kappa(args, tmp.path());
    expect_one_line_refusal(r);
    EXPECT_EQ(read_file(out), bytes) << "the existing output was modified";
    EXPECT_EQ(tree(tmp.path()), std::vector<std::string>{"x.exr"}) << "stray files";
  }
}

TEST(ExistingOutput, ReplacedByAGoodRender) {
  // The control for the test above: the same file is overwritten when the
  // render succeeds, so "untouched" is not an accident of the setup.
  TempDir tmp;
  const fs::path out = tmp / "x.exr";
  write_file(out, "old");
  const RunResult r = run_kappa(
      {"render", good_scene(), "--width", "8", "--height", "8", "--spp", "1", "--out", out.string(), "--quiet"},
      tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(read_file(out), "old");
  EXPECT_EQ(tree(tmp.path()), std::vector<std::string>{"x.exr"}) << "stray temporary";
}

// ---------------------------------------------------------------------------
// What must work

TEST(Help, ExitsZero) {
  EXPECT_EQ(run_kappa({"--help"}).exit_code, 0);
  EXPECT_EQ(run_kappa({"render", "--help"}).exit_code, 0);
}

TEST(GoodRender, TinyRenderCreatesTheOutput) {
  TempDir tmp;
  const fs::path out = tmp / "x.exr";
  const RunResult r = run_kappa(
      {"render", good_scene(), "--width", "8", "--height", "8", "--spp", "1", "--out", out.string(), "--quiet"},
      tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_EQ(r.std_err, "") << "--quiet prints nothing on a clean render";
  EXPECT_TRUE(fs::is_regular_file(out));
  EXPECT_GT(fs::file_size(out), 0u);
  EXPECT_EQ(tree(tmp.path()), std::vector<std::string>{"x.exr"}) << "stray temporary";
}

/// Renders `scene` without --out from inside an empty temp folder and returns
/// what appeared there.
std::vector<std::string> files_from_default_output(const std::string& scene) {
  TempDir tmp;
  const RunResult r =
      run_kappa({"render", scene, "--width", "8", "--height", "8", "--spp", "1", "--quiet"}, tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  return tree(tmp.path());
}

TEST(GoodRender, DefaultOutputIsNamedAfterTheFileStem) {
  EXPECT_EQ(files_from_default_output(good_scene()),
            (std::vector<std::string>{"out/", "out/scene_ok_control.exr"}));
}

TEST(GoodRender, DefaultOutputOfSceneJsonIsNamedAfterItsFolder) {
  EXPECT_EQ(files_from_default_output((assets_dir() / "cornell-box" / "scene.json").string()),
            (std::vector<std::string>{"out/", "out/cornell-box.exr"}));
}

// ---------------------------------------------------------------------------
// Every command that builds an accelerator takes the same grid flags, checked
// by the same validator, and refuses a grid over --grid-max-bytes before
// writing anything.

/// `kappa COMMAND <scene> <flags>` with a cheap workload and every output in `tmp`.
std::vector<std::string> building_command(const std::string& command, const fs::path& tmp,
                                          std::vector<std::string> flags) {
  std::vector<std::string> args = {command};
  if (command == "render") args.insert(args.end(), {good_scene(), "--out", (tmp / "x.exr").string(), "--quiet"});
  if (command == "cast") args.insert(args.end(), {good_scene(), "--n", "100", "--report", (tmp / "x.json").string()});
  if (command == "bench")
    args.insert(args.end(), {good_scene(), "--n", "100", "--repeat", "1", "--threads", "1", "--accel", "grid",
                             "--json", (tmp / "x.json").string()});
  if (command == "calibrate")
    args.insert(args.end(), {(assets_dir() / "cornell-box" / "scene.json").string(), "--size", "32", "--spp", "2", "--repeat", "1",
                             "--density", "2,32", "--out", (tmp / "x.json").string()});
  args.insert(args.end(), flags.begin(), flags.end());
  return args;
}

TEST(GridFlags, EveryBuildingCommandRefusesAGridOverGridMaxBytes) {
  for (const char* command : {"render", "cast", "bench", "calibrate"}) {
    SCOPED_TRACE(command);
    TempDir tmp;
    const RunResult r = run_kappa(building_command(command, tmp.path(), {"--grid-max-bytes", "10"}), tmp.path());
    expect_one_line_refusal(r);
    EXPECT_NE(r.std_err.find("--grid-max-bytes (10 bytes)"), std::string::npos) << r.std_err;
    EXPECT_TRUE(tree(tmp.path()).empty()) << "a refused run writes nothing";
  }
}

TEST(GridFlags, EveryCommandWithGridResChecksItAlike) {
  std::string first_message;
  for (const char* command : {"render", "cast", "bench"}) {
    SCOPED_TRACE(command);
    TempDir tmp;
    const RunResult r = run_kappa(building_command(command, tmp.path(), {"--grid-res", "0x2"}), tmp.path());
    expect_one_line_refusal(r);
    if (first_message.empty()) first_message = r.std_err;
    EXPECT_EQ(r.std_err, first_message) << "one validator, one message";
    EXPECT_NE(r.std_err.find("--grid-res"), std::string::npos) << r.std_err;
  }
}

TEST(GridFlags, CalibrateBuildsWithinGridMaxBytesWhenItFits) {
  TempDir tmp;
  const RunResult r =
      run_kappa(building_command("calibrate", tmp.path(), {"--grid-max-bytes", "100000000"}), tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(fs::is_regular_file(tmp / "x.json"));
}

// What is not the input's fault is an internal error: exit 1, one line that
// says so. One triangle gives every ray set the same cells and references, so
// the calibration's measurements cannot determine T0, Ts and Th.
TEST(InternalError, ACalibrationFitItsMeasurementsDoNotDetermineExitsOne) {
  TempDir tmp;
  const RunResult r = run_kappa({"calibrate", good_scene(), "--no-generated", "--size", "32", "--repeat", "1", "--density", "2", "--out",
                                 (tmp / "cal.json").string()},
                                tmp.path());
  EXPECT_EQ(r.exit_code, 1) << r.std_err;
  ASSERT_FALSE(r.err_lines().empty());
  EXPECT_EQ(r.err_lines().back().rfind("kappa: internal error: calibration:", 0), 0u) << r.std_err;
  EXPECT_FALSE(fs::exists(tmp / "cal.json"));
}

TEST(NumberFlags, OtherCommandsRefuseNaNAndKeepTheLargestSeed) {
  const std::string scene = (assets_dir() / "cornell-box" / "scene.json").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"cast", scene, "--rays", "segments", "--n", "10", "--length", "nan"},
        {"bench", scene, "--n", "10", "--accel", "grid", "--threads", "1", "--repeat", "1", "--naive-budget", "nan"},
        {"calibrate", scene, "--size", "32", "--density", "inf"},
        {"cast", scene, "--n", "10", "--seed", "-1"}}) {
    SCOPED_TRACE(::testing::PrintToString(args));
    TempDir tmp;
    expect_one_line_refusal(run_kappa(args, tmp.path()));
  }
  TempDir tmp;
  const RunResult r = run_kappa({"render", good_scene(), "--spp", "1", "--seed", "9007199254740991", "--out",
                                 (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(read_file(tmp / "x.json").find("\"seed\": 9007199254740991"), std::string::npos);
}

}  // namespace
}  // namespace kappa::test
