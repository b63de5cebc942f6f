// Hostile input, as the README's policy table classes it: an output never
// replaces an input or another output; a device or FIFO gets a text output
// written to it directly, never replaced, and never an image; reading never
// hangs on a FIFO or a device, nor reads an oversized file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

/// A copy of the Cornell box (scene.json, OBJ, MTL) in `dir`.
fs::path copy_cornell(const fs::path& dir) {
  fs::copy(assets_dir() / "cornell-box", dir / "cornell", fs::copy_options::recursive);
  return dir / "cornell" / "scene.json";
}

/// A render of 8x8 pixels at 1 spp into `out`, with `more` flags after.
std::vector<std::string> cheap_render(const fs::path& scene, const fs::path& out, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"render", scene.string(), "--spp", "1", "--width", "8", "--height", "8", "-q",
                                   "--out", out.string()};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

void expect_refused_and_untouched(const RunResult& r, const fs::path& input, const std::string& before) {
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_NE(r.std_err.find("refusing to overwrite an input"), std::string::npos) << r.std_err;
  EXPECT_EQ(read_file(input), before) << input << " was changed";
}

// Class: outputs never destroy inputs (by path, symlink, hard link, "..").
TEST(HostileInput, NoOutputReplacesAnInputOfTheRun) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const fs::path obj = scene.parent_path() / "cornell_box.obj", mtl = scene.parent_path() / "cornell_box.mtl";
  fs::create_symlink(scene, tmp / "link.json");
  fs::create_hard_link(obj, tmp / "hard.obj");
  const std::string scene_text = read_file(scene), obj_text = read_file(obj), mtl_text = read_file(mtl);
  const fs::path out = tmp / "x.exr";
  struct Case {
    std::vector<std::string> args;
    fs::path input;
    std::string before;
  };
  std::vector<Case> cases = {
      {cheap_render(scene, out), scene, scene_text},
      {cheap_render(scene, out), obj, obj_text},
      {cheap_render(scene, out), mtl, mtl_text},
      {cheap_render(scene, out), scene, scene_text},
      {cheap_render(scene, out), obj, obj_text},
      {{"cast", scene.string(), "--n", "100", "--report", obj.string()}, obj, obj_text},
      {{"bench", scene.string(), "--n", "100", "--accel", "grid", "--threads", "1", "--repeat", "1", "--json",
        mtl.string()},
       mtl, mtl_text},
      {{"calibrate", scene.string(), "--size", "32", "--repeat", "1", "--out", scene.string()}, scene, scene_text},
  };
  // render: --report onto the scene, the MTL through "..", the scene through
  // a symlink and the OBJ through a hard link.
  cases[0].args.insert(cases[0].args.end(), {"--report", scene.string()});
  cases[1].args.insert(cases[1].args.end(), {"--report", (scene.parent_path() / ".." / "cornell" / "cornell_box.obj").string()});
  cases[2].args.insert(cases[2].args.end(), {"--report", mtl.string()});
  cases[3].args.insert(cases[3].args.end(), {"--report", (tmp / "link.json").string()});
  cases[4].args.insert(cases[4].args.end(), {"--report", (tmp / "hard.obj").string()});
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::PrintToString(c.args));
    expect_refused_and_untouched(run_kappa(c.args, tmp.path()), c.input, c.before);
  }
  // The calibration file a render reads is an input too.
  write_file(tmp / "cal.json", R"({"format": 5, "eq10": {"constants": {"T0_ns": 20, "Ts_ns": 3, "Th_ns": 7}}})");
  std::vector<std::string> args = cheap_render(scene, out);
  args.insert(args.end(), {"--calibration", (tmp / "cal.json").string(), "--report", (tmp / "cal.json").string()});
  expect_refused_and_untouched(run_kappa(args, tmp.path()), tmp / "cal.json", read_file(tmp / "cal.json"));
  EXPECT_FALSE(fs::exists(out)) << "refused before rendering";
}

TEST(HostileInput, NoTwoOutputsOfARunShareAFile) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const std::vector<std::string> args = cheap_render(scene, tmp / "x.exr", {"--report", (tmp / "x.exr").string()});
  const RunResult r = run_kappa(args, tmp.path());
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  EXPECT_NE(r.std_err.find("is also another output of this run"), std::string::npos) << r.std_err;
  EXPECT_FALSE(fs::exists(tmp / "x.exr"));
}

// Class: a device or FIFO is written in place (text) or refused (images), never replaced.
TEST(HostileInput, TextOutputsGoStraightToDevicesAndFifos) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  // /dev/stdout is a link: written through (here to the file the harness
  // captures stdout in), the link itself never replaced.
  const RunResult r = run_kappa(cheap_render(scene, tmp / "x.exr", {"--report", "/dev/stdout"}), tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.std_out.find("\"schema_version\""), std::string::npos) << r.std_out;
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
  // Through a pipe (a FIFO): written in place.
  const std::string cmd = std::string(KAPPA_BINARY) + " render '" + scene.string() +
                          "' --spp 1 --width 8 --height 8 -q --out '" + (tmp / "p.exr").string() +
                          "' --report /dev/stdout | grep -c schema_version > '" + (tmp / "count").string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(read_file(tmp / "count"), "1\n");
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));

  // A FIFO with a reader: the report arrives through it, and it stays a FIFO.
  ASSERT_EQ(::mkfifo((tmp / "report.fifo").c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_file(tmp / "report.fifo"); });
  const RunResult f =
      run_kappa(cheap_render(scene, tmp / "y.exr", {"--report", (tmp / "report.fifo").string()}), tmp.path(), 60);
  reader.join();
  EXPECT_EQ(f.exit_code, 0) << f.std_err;
  EXPECT_NE(received.find("\"schema_version\""), std::string::npos);
  EXPECT_TRUE(fs::is_fifo(tmp / "report.fifo"));
}

TEST(HostileInput, ImagesAreNeverWrittenToDevicesAndNothingIsReplaced) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  fs::create_symlink("/dev/null", tmp / "null.exr");
  const RunResult r = run_kappa(cheap_render(scene, tmp / "null.exr"), tmp.path());
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  EXPECT_NE(r.std_err.find("device or FIFO"), std::string::npos) << r.std_err;
  EXPECT_TRUE(fs::is_symlink(tmp / "null.exr"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A full device: the report's write fails, exit 1 (not the input's fault),
  // and the device is still a device.
  const RunResult full = run_kappa(cheap_render(scene, tmp / "x.exr", {"--report", "/dev/full"}), tmp.path());
  EXPECT_EQ(full.exit_code, 1) << full.std_err;
  EXPECT_NE(full.std_err.find("kappa: internal error: /dev/full: cannot write"), std::string::npos) << full.std_err;
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(HostileInput, AReportIntoAClosedPipeExitsOneInsteadOfDying) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  // `true` exits at once: the report's write meets a closed pipe.
  const std::string cmd = std::string(KAPPA_BINARY) + " render '" + scene.string() +
                          "' --spp 4 --width 64 --height 64 -q --out '" + (tmp / "x.exr").string() +
                          "' --report /dev/stdout 2>'" + (tmp / "err").string() + "' | true; exit ${PIPESTATUS[0]}";
  write_file(tmp / "run.sh", cmd + "\n");
  const int status = std::system(("bash '" + (tmp / "run.sh").string() + "'").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1) << read_file(tmp / "err");
  EXPECT_NE(read_file(tmp / "err").find("Broken pipe"), std::string::npos) << read_file(tmp / "err");
}

// Class: reading never hangs, and every path read passes one check.
TEST(HostileInput, ReadingRefusesFifosDevicesAndHugeFilesAtOnce) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const fs::path obj = scene.parent_path() / "cornell_box.obj";
  ASSERT_EQ(::mkfifo((tmp / "fifo.obj").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", tmp / "zero.obj");
  // An OBJ whose material library is a FIFO, and one whose library links to /dev/zero.
  for (const char* name : {"fifo_lib", "zero_lib", "huge_lib"}) {
    fs::create_directory(tmp / name);
    fs::copy_file(obj, tmp / name / "cornell_box.obj");
  }
  ASSERT_EQ(::mkfifo((tmp / "fifo_lib" / "cornell_box.mtl").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", tmp / "zero_lib" / "cornell_box.mtl");
  { std::ofstream(tmp / "huge_lib" / "cornell_box.mtl"); }
  fs::resize_file(tmp / "huge_lib" / "cornell_box.mtl", std::uintmax_t(17) << 30);  // sparse: no disk used
  ASSERT_EQ(::mkfifo((tmp / "cal.fifo").c_str(), 0600), 0);
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  std::vector<std::string> with_cal = cheap_render(scene, tmp / "x.exr");
  with_cal.insert(with_cal.end(), {"--calibration", (tmp / "cal.fifo").string()});
  const std::vector<Case> cases = {
      {cheap_render(tmp / "fifo.obj", tmp / "x.exr"), "fifo.obj: is not a regular file"},
      {cheap_render(tmp / "zero.obj", tmp / "x.exr"), "zero.obj: is not a regular file"},
      {cheap_render(tmp / "fifo_lib" / "cornell_box.obj", tmp / "x.exr"), "cornell_box.mtl: is not a regular file"},
      {cheap_render(tmp / "zero_lib" / "cornell_box.obj", tmp / "x.exr"), "cornell_box.mtl: is not a regular file"},
      {cheap_render(tmp / "huge_lib" / "cornell_box.obj", tmp / "x.exr"), "is larger than Kappa's input limit of 16 GiB"},
      {with_cal, "cal.fifo: is not a regular file"},
      {cheap_render(tmp.path(), tmp / "x.exr"), "is a directory"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::PrintToString(c.args));
    const RunResult r = run_kappa(c.args, tmp.path(), 30);
    EXPECT_EQ(r.exit_code, 2) << r.std_err;  // 124 would be a hang cut by the timeout
    EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
    EXPECT_NE(r.std_err.find(c.says), std::string::npos) << r.std_err;
  }
  EXPECT_FALSE(fs::exists(tmp / "x.exr"));
}

}  // namespace
}  // namespace kappa::test
