// Writes that fail: a full disk (a file-size limit set in the child by
// prlimit, no mount or root needed) after rendering gives exit 1, and an
// unwritable folder (kappa run as an unprivileged user by setpriv: the tests
// run as root, for whom chmod proves nothing) is refused before rendering
// with exit 2. Either way one line names the output and the system's reason,
// no partial file is left and a previous file of that name is untouched.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "test_util.h"

namespace kappa {
namespace {

namespace fs = std::filesystem;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

TEST(FailingWrites, AFullDiskAfterRenderingExitsOneAndKeepsThePreviousFile) {
  if (std::system("command -v prlimit >/dev/null") != 0) GTEST_SKIP() << "prlimit (util-linux) is not installed";
  test::TempDir tmp;
  test::write_file(tmp / "x.exr", "the previous image");
  // 4 KiB: the report fits, the 64 x 64 EXR does not.
  const auto r = test::run_kappa_under({"prlimit", "--fsize=4096", "--"},
                                       {"render", cornell(), "--width", "64", "--height", "64", "--spp", "2",
                                        "--stats", "off", "--out", (tmp / "x.exr").string(), "-q"});
  EXPECT_EQ(r.exit_code, 1) << r.std_err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_NE(r.std_err.find((tmp / "x.exr").string() + ": cannot write EXR"), std::string::npos) << r.std_err;
  EXPECT_NE(r.std_err.find("File too large"), std::string::npos) << r.std_err;
  EXPECT_EQ(test::read_file(tmp / "x.exr"), "the previous image");
  EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"x.exr"}) << "a temporary was left behind";
}

TEST(FailingWrites, AReportPastTheLimitExitsOneAndLeavesNoPartialFile) {
  if (std::system("command -v prlimit >/dev/null") != 0) GTEST_SKIP() << "prlimit (util-linux) is not installed";
  test::TempDir tmp;
  // A 1 x 1 film: its EXR fits in 1.5 KiB, the report (several KiB with
  // statistics on) does not. The image, written first, must not land alone.
  const auto r = test::run_kappa_under({"prlimit", "--fsize=1536", "--"},
                                       {"render", cornell(), "--width", "1", "--height", "1", "--spp", "1",
                                        "--out", (tmp / "x.exr").string(), "--report", (tmp / "r.json").string(),
                                        "-q"});
  EXPECT_EQ(r.exit_code, 1) << r.std_err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_NE(r.std_err.find((tmp / "r.json").string() + ": cannot write: File too large"), std::string::npos)
      << r.std_err;
  EXPECT_TRUE(files_in(tmp.path()).empty()) << "no output may land when one of them failed";
}

TEST(FailingWrites, AnUnwritableFolderIsRefusedBeforeRendering) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to run kappa as another user (setpriv)";
  if (std::system("command -v setpriv >/dev/null") != 0) GTEST_SKIP() << "setpriv (util-linux) is not installed";
  test::TempDir tmp;
  fs::permissions(tmp.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                  fs::perms::others_read | fs::perms::others_exec);  // root's, readable by all
  test::write_file(tmp / "x.exr", "the previous image");
  const auto r = test::run_kappa_under({"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"},
                                       {"render", cornell(), "--width", "16", "--height", "16", "--spp", "1",
                                        "--out", (tmp / "x.exr").string(), "-q"});
  if (r.exit_code == 126 || r.exit_code == 127 || r.std_err.find("setpriv") != std::string::npos)
    GTEST_SKIP() << "kappa cannot run as user 65534 here: " << r.std_err;
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_NE(r.std_err.find((tmp / "x.exr").string() + ": cannot write"), std::string::npos) << r.std_err;
  EXPECT_NE(r.std_err.find("Permission denied"), std::string::npos) << r.std_err;
  EXPECT_EQ(test::read_file(tmp / "x.exr"), "the previous image");
  EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"x.exr"});
  // A folder it may not even look into (inside one closed to it) is
  // unwritable, not missing.
  fs::create_directories(tmp / "closed" / "sub");
  fs::permissions(tmp / "closed", fs::perms::owner_all);
  const auto closed = test::run_kappa_under({"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"},
                                            {"render", cornell(), "--width", "16", "--height", "16", "--spp", "1",
                                             "--out", (tmp / "closed" / "sub" / "x.exr").string(), "-q"});
  EXPECT_EQ(closed.exit_code, 2) << closed.std_err;
  EXPECT_NE(closed.std_err.find("sub': Permission denied"), std::string::npos) << closed.std_err;
}

}  // namespace
}  // namespace kappa
