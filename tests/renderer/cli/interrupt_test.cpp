// Ctrl-C (SIGINT) and SIGTERM during a render leave neither a partial EXR nor
// a stray temporary, and an existing output file stays as it was.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "test_util.h"

extern char** environ;

namespace kappa {
namespace {

std::size_t entries(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

void interrupt_render(int sig) {
  test::TempDir dir;
  const auto out = dir / "image.exr";
  test::write_file(out, "an older render");
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  std::vector<std::string> args = {KAPPA_BINARY, "render", scene, "--spp", "100000", "--out", out.string(), "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, KAPPA_BINARY, nullptr, nullptr, argv.data(), environ), 0);

  // Wait until the output is being made (an unnamed file in the folder,
  // open in the process): the render has started.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!test::makes_a_file_in(pid, dir.path()) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const bool started = test::makes_a_file_in(pid, dir.path());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(pid, sig);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(started) << "the render never began its output";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig);
  EXPECT_EQ(entries(dir.path()), 1u);  // only the old file
  EXPECT_EQ(test::read_file(out), "an older render");
}

TEST(Interrupt, SigintLeavesNoPartialOrTemporaryFile) { interrupt_render(SIGINT); }

TEST(Interrupt, SigtermLeavesNoPartialOrTemporaryFile) { interrupt_render(SIGTERM); }

}  // namespace
}  // namespace kappa
