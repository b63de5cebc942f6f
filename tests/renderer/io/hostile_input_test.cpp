// Hostile input, as docs/bad-input.md's policy table classes it: an output never
// replaces an input or another output; a device, FIFO or descriptor is
// written to directly, never replaced (an image made whole first); a link is
// written through or refused, never replaced; reading never hangs on
// a FIFO or a device, nor reads an oversized file. No test here uses the
// machine's own /dev/stdout: they make their own links to /proc/self/fd/N.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#include "renderer/io/exr_input.h"
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

/// A link in `dir` to /proc/self/fd/N: what /dev/stdout is for N = 1, made
/// here so that no test touches the machine's own /dev/stdout.
fs::path descriptor_link(const TempDir& dir, int descriptor) {
  const fs::path link = dir / ("fd" + std::to_string(descriptor));
  fs::create_symlink("/proc/self/fd/" + std::to_string(descriptor), link);
  return link;
}

/// Runs `script` with bash, in `dir` as its working directory, and returns
/// its exit code (-1 if killed).
int run_bash(const TempDir& dir, const std::string& script) {
  write_file(dir / "run.sh", script + "\n");
  const int status = std::system(("cd '" + dir.path().string() + "' && bash run.sh").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

/// The shell command of a 64x64, 4-spp render of `scene` into `out`.
std::string render_command(const fs::path& scene, const fs::path& out) {
  return std::string(KAPPA_BINARY) + " render " + quoted(scene) + " --spp 4 --width 64 --height 64 -q --out " +
         quoted(out);
}

// Class: a device, FIFO or descriptor is written in place, never replaced.
TEST(HostileInput, TextOutputsGoStraightToDevicesAndFifos) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const fs::path stdout_link = descriptor_link(tmp, 1);
  // Standard output through a link, as /dev/stdout is: the report lands in
  // the file the harness captures stdout in, and the link stays a link.
  const RunResult r = run_kappa(cheap_render(scene, tmp / "x.exr", {"--report", stdout_link.string()}), tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.std_out.find("\"schema_version\""), std::string::npos) << r.std_out;
  EXPECT_TRUE(fs::is_symlink(stdout_link));
  // "-" is standard output too.
  const RunResult dash = run_kappa(cheap_render(scene, tmp / "x.exr", {"--report", "-"}), tmp.path());
  EXPECT_EQ(dash.exit_code, 0) << dash.std_err;
  EXPECT_NE(dash.std_out.find("\"schema_version\""), std::string::npos) << dash.std_out;
  EXPECT_FALSE(fs::exists(tmp / "-"));
  // Through a pipe (a FIFO): written in place.
  ASSERT_EQ(run_bash(tmp, render_command(scene, tmp / "p.exr") + " --report " + quoted(stdout_link) +
                              " | grep -c schema_version > " + quoted(tmp / "count")),
            0);
  EXPECT_EQ(read_file(tmp / "count"), "1\n");
  EXPECT_TRUE(fs::is_symlink(stdout_link));

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

// Standard output appended to a log: the report is appended to the same file
// (same inode, the log's first line kept), not renamed over it.
TEST(HostileInput, AReportIntoStdoutAppendedToALogKeepsTheLog) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const fs::path stdout_link = descriptor_link(tmp, 1);
  write_file(tmp / "log", "the log's first line\n");
  struct stat before {};
  ASSERT_EQ(::stat((tmp / "log").c_str(), &before), 0);
  ASSERT_EQ(run_bash(tmp, render_command(scene, tmp / "x.exr") + " --report " + quoted(stdout_link) + " >> " +
                              quoted(tmp / "log")),
            0);
  struct stat after {};
  ASSERT_EQ(::stat((tmp / "log").c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino) << "the log was replaced";
  const std::string log = read_file(tmp / "log");
  EXPECT_EQ(log.rfind("the log's first line\n{", 0), 0u) << log.substr(0, 200);
  EXPECT_NE(log.find("\"schema_version\""), std::string::npos);
}

// A link that leads nowhere (a closed descriptor behind it, a loop) is
// refused before the render, with one line, and stays as it was; one that
// leads to a file not made yet is written through.
TEST(HostileInput, AnOutputLinkThatLeadsNowhereIsRefusedBeforeRendering) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  const fs::path stdout_link = descriptor_link(tmp, 1);
  const fs::path fd7_link = descriptor_link(tmp, 7);
  fs::create_symlink("nothing.json", tmp / "dangling.json");
  fs::create_symlink("loop_b", tmp / "loop_a");
  fs::create_symlink("loop_a", tmp / "loop_b");
  struct Case {
    std::string redirect;  // of kappa's standard output
    fs::path report;
    std::string says;
  };
  const std::vector<Case> cases = {
      {">&-", stdout_link, "fd1: cannot write: it leads to standard output, which is closed"},
      {">&-", "-", "-: cannot write: it leads to standard output, which is closed"},
      {"", fd7_link, "fd7: cannot write: it leads to descriptor 7, which is closed"},
      {"", tmp / "loop_a", "a loop of symbolic links"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.report);
    const int code = run_bash(tmp, render_command(scene, tmp / "x.exr") + " --report " + quoted(c.report) + " " +
                                       c.redirect + " 2> " + quoted(tmp / "err"));
    const std::string err = read_file(tmp / "err");
    EXPECT_EQ(code, 2) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(c.says), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp / "x.exr")) << "refused after rendering";
  }
  EXPECT_TRUE(fs::is_symlink(stdout_link));
  EXPECT_TRUE(fs::is_symlink(tmp / "loop_a"));
  // A link to a file not made yet is written through, as the shell's `>`
  // and oiiotool do: the file appears where it leads, and the link stays.
  fs::create_symlink("made.exr", tmp / "dangling.exr");
  const RunResult report = run_kappa(cheap_render(scene, tmp / "x.exr", {"--report", (tmp / "dangling.json").string()}),
                                     tmp.path());
  EXPECT_EQ(report.exit_code, 0) << report.std_err;
  const RunResult image = run_kappa(cheap_render(scene, tmp / "dangling.exr"), tmp.path());
  EXPECT_EQ(image.exit_code, 0) << image.std_err;
  EXPECT_EQ(fs::read_symlink(tmp / "dangling.json"), "nothing.json");
  EXPECT_EQ(fs::read_symlink(tmp / "dangling.exr"), "made.exr");
  EXPECT_NE(read_file(tmp / "nothing.json").find("\"schema_version\""), std::string::npos);
  EXPECT_EQ(read_file(tmp / "made.exr").substr(0, 4), "v/1\x01");
}

// The issue's own command, on the path /dev/stdout itself: in a private mount
// namespace whose /dev is this test's folder, so the machine's /dev/stdout is
// never at risk. Skipped where mount namespaces are refused.
TEST(HostileInput, TheIssuesCommandLeavesDevStdoutALink) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  if (run_bash(tmp, "unshare -m true 2>/dev/null") != 0) GTEST_SKIP() << "unshare -m is refused here";
  const fs::path dev = tmp / "dev";
  fs::create_directory(dev);
  std::string script = "set -e\n";
  for (const char* node : {"null", "zero", "urandom", "random"})
    script += "touch " + quoted(dev / node) + "; mount --bind /dev/" + node + " " + quoted(dev / node) + "\n";
  script += "ln -s /proc/self/fd/1 " + quoted(dev / "stdout") + "\n";
  script += "mount --bind " + quoted(dev) + " /dev\n";
  script += "set +e\n";
  script += render_command(scene, tmp / "y.exr") + " --report /dev/stdout >&- 2> " + quoted(tmp / "err") + "\n";
  script += "echo $? > " + quoted(tmp / "code") + "\n";
  script += "ls -la /dev/stdout > " + quoted(tmp / "ls") + "\n";
  write_file(tmp / "inside.sh", script);
  ASSERT_EQ(run_bash(tmp, "unshare -m bash " + quoted(tmp / "inside.sh")), 0) << read_file(tmp / "err");
  const std::string err = read_file(tmp / "err");
  EXPECT_EQ(read_file(tmp / "code"), "2\n") << err;
  EXPECT_EQ(err, "kappa: error: /dev/stdout: cannot write: it leads to standard output, which is closed\n");
  EXPECT_NE(read_file(tmp / "ls").find("/dev/stdout -> /proc/self/fd/1"), std::string::npos) << read_file(tmp / "ls");
  EXPECT_TRUE(fs::is_symlink(dev / "stdout"));
  EXPECT_FALSE(fs::exists(tmp / "y.exr"));
}

TEST(HostileInput, ImagesGoToDevicesAndPipesWholeAndNothingIsReplaced) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  fs::create_symlink("/dev/null", tmp / "null.exr");
  const RunResult r = run_kappa(cheap_render(scene, tmp / "null.exr"), tmp.path());
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(fs::is_symlink(tmp / "null.exr"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // `--out -`: the EXR on standard output, the same bytes as in a file.
  ASSERT_EQ(run_bash(tmp, render_command(scene, tmp / "file.exr")), 0);
  ASSERT_EQ(run_bash(tmp, render_command(scene, "-") + " > " + quoted(tmp / "piped.exr")), 0);
  const ReferenceImage piped = read_reference(tmp / "piped.exr"), file = read_reference(tmp / "file.exr");
  EXPECT_EQ(piped.width, 64);
  EXPECT_EQ(piped.rgb, file.rgb);
  EXPECT_FALSE(fs::exists(tmp / "-"));
  // A full device: the write fails, exit 1 (not the input's fault), one
  // line, and the device is still a device.
  for (const auto& args : {cheap_render(scene, tmp / "x.exr", {"--report", "/dev/full"}), cheap_render(scene, "/dev/full")}) {
    const RunResult full = run_kappa(args, tmp.path());
    EXPECT_EQ(full.exit_code, 1) << full.std_err;
    EXPECT_EQ(full.std_err, "kappa: error: /dev/full: cannot write: No space left on device\n");
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(HostileInput, AReportIntoAClosedPipeExitsOneInsteadOfDying) {
  TempDir tmp;
  const fs::path scene = copy_cornell(tmp.path());
  // `true` exits at once: the report's write meets a closed pipe.
  const int code = run_bash(tmp, render_command(scene, tmp / "x.exr") + " --report " +
                                     quoted(descriptor_link(tmp, 1)) + " 2>" + quoted(tmp / "err") +
                                     " | true; exit ${PIPESTATUS[0]}");
  EXPECT_EQ(code, 1) << read_file(tmp / "err");
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
      {cheap_render(tmp / "huge_lib" / "cornell_box.obj", tmp / "x.exr"), "larger than Kappa's input limit of"},
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
