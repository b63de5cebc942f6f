// Progress on a terminal while loading, building and rendering, and none
// anywhere else: kappa runs with stderr on a pseudo-terminal, as a user
// would see it, and with stderr on a pipe, as a script would.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "test_util.h"

extern char** environ;

namespace kappa {
namespace {

struct TerminalRun {
  int exit_code = -1;
  std::string terminal;  ///< what kappa wrote to stderr, as the terminal got it
};

/// Runs kappa with stderr on a new pseudo-terminal and stdout on /dev/null.
TerminalRun run_on_terminal(std::vector<std::string> args) {
  TerminalRun run;
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    ADD_FAILURE() << "no pseudo-terminal: " << std::strerror(errno);
    return run;
  }
  const std::string slave_name = ::ptsname(master);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, slave_name.c_str(), O_RDWR | O_NOCTTY, 0);
  posix_spawn_file_actions_addclose(&files, master);
  args.insert(args.begin(), KAPPA_BINARY);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, KAPPA_BINARY, &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) {
    ADD_FAILURE() << "cannot start kappa: " << std::strerror(spawned);
    ::close(master);
    return run;
  }
  // Read until the child's end of the terminal closes (EIO), then reap it.
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(master, buffer, sizeof buffer);
    if (n > 0) run.terminal.append(buffer, std::size_t(n));
    else if (n < 0 && errno == EINTR) continue;
    else break;
  }
  ::close(master);
  int status = 0;
  ::waitpid(pid, &status, 0);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Progress, ATerminalSeesEveryPhaseOfLoadingBuildingAndRendering) {
  test::TempDir dir;
  const TerminalRun run = run_on_terminal({"render", cornell(), "--accel", "grid", "--spp", "1", "--width", "32",
                                           "--height", "32", "--out", (dir / "c.exr").string()});
  ASSERT_EQ(run.exit_code, 0) << run.terminal;
  for (const char* phase : {"reading cornell_box.obj", "checking cornell_box.obj", "parsing cornell_box.obj",
                            ": counting cells", ": filling cells", "rendering ["})
    EXPECT_TRUE(contains(run.terminal, phase)) << "no '" << phase << "' in:\n" << run.terminal;
  // Loading and building are erased before the next line is written.
  const std::size_t summary = run.terminal.find("kappa: grid ");
  ASSERT_NE(summary, std::string::npos) << run.terminal;
  const std::size_t last_build = run.terminal.rfind("filling cells", summary);
  ASSERT_NE(last_build, std::string::npos);
  EXPECT_TRUE(contains(run.terminal.substr(last_build, summary - last_build), "\r\033[K"));
}

TEST(Progress, ABudgetedRenderShowsItsSamplesAndEstimate) {
  test::TempDir dir;
  const TerminalRun run = run_on_terminal({"render", cornell(), "--width", "32", "--height", "32", "--target-relmse",
                                           "0.01", "--out", (dir / "c.exr").string()});
  ASSERT_EQ(run.exit_code, 0) << run.terminal;
  EXPECT_TRUE(contains(run.terminal, "rendering, pass ")) << run.terminal;
  EXPECT_TRUE(contains(run.terminal, " spp, relMSE 0.00")) << run.terminal;
}

TEST(Progress, TheBuildOfEveryAcceleratorWithOneIsShown) {
  const TerminalRun run = run_on_terminal({"cast", cornell(), "--accel", "embree", "--n", "100"});
  ASSERT_EQ(run.exit_code, 0) << run.terminal;
  EXPECT_TRUE(contains(run.terminal, "embree: building the BVH")) << run.terminal;
  EXPECT_TRUE(contains(run.terminal, "parsing cornell_box.obj")) << run.terminal;
}

TEST(Progress, AnErrorStartsOnAClearedLine) {
  test::TempDir dir;
  test::write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv nan 0 0\n");
  const TerminalRun run = run_on_terminal({"render", (dir / "bad.obj").string(), "--out", (dir / "b.exr").string()});
  EXPECT_EQ(run.exit_code, 2) << run.terminal;
  const std::size_t error = run.terminal.find("bad.obj:5");
  ASSERT_NE(error, std::string::npos) << run.terminal;
  EXPECT_TRUE(contains(run.terminal, "checking bad.obj")) << run.terminal;
  EXPECT_EQ(run.terminal.rfind("\r\033[K", error), run.terminal.rfind('\r', error)) << run.terminal;
}

TEST(Progress, QuietOrNotATerminalDrawsNothing) {
  test::TempDir dir;
  const TerminalRun quiet = run_on_terminal(
      {"render", cornell(), "--spp", "1", "--width", "16", "--height", "16", "--out", (dir / "q.exr").string(), "--quiet"});
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.terminal, "");
  const test::RunResult piped =
      test::run_kappa({"render", cornell(), "--spp", "1", "--width", "16", "--height", "16", "--out", (dir / "p.exr").string()});
  EXPECT_EQ(piped.exit_code, 0) << piped.std_err;
  EXPECT_FALSE(contains(piped.std_err, "\r")) << piped.std_err;
  EXPECT_FALSE(contains(piped.std_err, "checking")) << piped.std_err;
}

}  // namespace
}  // namespace kappa
