// Provenance from the bytes that were rendered: the report's input_hash and
// inputs come from the files as they were read, and no input is opened again
// after loading, so an input edited, deleted or replaced by a FIFO during the
// render changes nothing of the run.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_util.h"

extern char** environ;

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

struct Change {
  const char* what;
  void (*apply)(const fs::path& scene_dir);
};

TEST(Provenance, AnInputChangedDuringTheRenderChangesNothingOfTheRun) {
  TempDir tmp;
  fs::copy(assets_dir() / "cornell-box", tmp / "scene", fs::copy_options::recursive);
  fs::create_directory(tmp / "out");
  const RunResult first = run_kappa({"render", (tmp / "scene" / "scene.json").string(), "--spp", "1", "--width", "16",
                                     "--height", "16", "-q", "--out", (tmp / "a.exr").string(), "--report",
                                     (tmp / "a.json").string()});
  ASSERT_EQ(first.exit_code, 0) << first.std_err;
  const nlohmann::json before = nlohmann::json::parse(read_file(tmp / "a.json"));
  ASSERT_EQ(before["inputs"].size(), 3u);  // scene.json, the OBJ, the MTL
  for (const auto& input : before["inputs"]) EXPECT_EQ(input["bytes"], fs::file_size(input["file"].get<std::string>()));

  const std::vector<Change> changes = {
      {"the MTL rewritten", [](const fs::path& d) { write_file(d / "cornell_box.mtl", "newmtl white\nKd 1 0 0\n"); }},
      {"the OBJ deleted", [](const fs::path& d) { fs::remove(d / "cornell_box.obj"); }},
      {"the OBJ replaced by a FIFO",
       [](const fs::path& d) {
         fs::remove(d / "cornell_box.obj");
         ::mkfifo((d / "cornell_box.obj").c_str(), 0600);
       }},
  };
  for (const Change& change : changes) {
    SCOPED_TRACE(change.what);
    fs::remove_all(tmp / "scene");
    fs::copy(assets_dir() / "cornell-box", tmp / "scene", fs::copy_options::recursive);
    std::vector<std::string> args = {KAPPA_BINARY, "render", (tmp / "scene" / "scene.json").string(),
                                     "--width", "16", "--height", "16", "-q", "--time-budget", "1500ms",
                                     "--out", (tmp / "out" / "b.exr").string(), "--report", (tmp / "out" / "b.json").string()};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, KAPPA_BINARY, nullptr, nullptr, argv.data(), environ), 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!makes_a_file_in(pid, tmp / "out") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const bool loaded = makes_a_file_in(pid, tmp / "out");
    const auto changed = std::chrono::steady_clock::now();
    change.apply(tmp / "scene");
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    const auto ended = std::chrono::steady_clock::now();
    ASSERT_TRUE(loaded) << "the render never claimed its outputs";
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    // The change came while the render ran, not after it.
    EXPECT_GT(std::chrono::duration<double>(ended - changed).count(), 0.5);
    ASSERT_TRUE(fs::is_regular_file(tmp / "out" / "b.exr"));
    const nlohmann::json after = nlohmann::json::parse(read_file(tmp / "out" / "b.json"));
    // The same bytes were read, whatever became of the files since.
    EXPECT_EQ(after["render"]["settings"]["input_hash"], before["render"]["settings"]["input_hash"]);
    ASSERT_EQ(after["inputs"].size(), before["inputs"].size());
    for (std::size_t i = 0; i < after["inputs"].size(); ++i) {
      EXPECT_EQ(after["inputs"][i]["bytes"], before["inputs"][i]["bytes"]);
      EXPECT_EQ(after["inputs"][i]["hash"], before["inputs"][i]["hash"]);
    }
  }
}

}  // namespace
}  // namespace kappa::test
