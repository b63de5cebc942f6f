// Budgeted renders from the command line: what the report and the EXR say
// of the passes, and the Ctrl-C policy (README, exit codes): the first
// SIGINT abandons the pass in progress and writes the completed passes
// (exit 130); before a pass is complete, or at a second SIGINT, nothing is
// written.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "test_util.h"

extern char** environ;

namespace kappa {
namespace {

namespace fs = std::filesystem;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

/// The EXR's channel names and kappa:spp.
std::pair<std::vector<std::string>, int> exr_facts(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  return {spec.channelnames, spec.get_int_attribute("kappa:spp", -1)};
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(Budget, ANoiseTargetStopsBelowItAndWritesTheVarianceAndSppChannels) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"render", cornell(), "--width", "32", "--height", "32", "--target-relmse", "0.01",
                                  "--adaptive", "--adaptive-min-spp", "8", "--out", (tmp / "x.exr").string(), "--report",
                                  (tmp / "x.json").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json")).at("render");
  EXPECT_EQ(j.at("target_relmse").get<double>(), 0.01);
  EXPECT_TRUE(j.at("time_budget_s").is_null());
  const std::string reason = j.at("stop_reason");
  EXPECT_TRUE(reason == "target-relmse" || reason == "converged") << reason;
  EXPECT_LT(j.at("relmse_estimate").get<double>(), 0.01);
  EXPECT_GE(j.at("passes").get<int>(), 2);
  EXPECT_GE(j.at("spp_min").get<int>(), 8);
  EXPECT_EQ(j.at("spp_max").get<int>(), j.at("spp").get<int>());
  EXPECT_EQ(j.at("settings").at("spp"), j.at("spp"));
  EXPECT_EQ(j.at("settings").at("adaptive"), true);
  EXPECT_EQ(j.at("nonfinite_samples"), 0);
  EXPECT_EQ(j.at("interrupted"), false);
  const auto [channels, spp] = exr_facts(tmp / "x.exr");
  for (const char* c : {"variance.R", "variance.G", "variance.B", "spp"}) EXPECT_TRUE(has(channels, c)) << c;
  EXPECT_EQ(spp, j.at("spp").get<int>());
}

TEST(Budget, ATimeBudgetIsReportedAndAnSppCapStopsItFirst) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"render", cornell(), "--width", "16", "--height", "16", "--time-budget", "1h", "--spp",
                                  "5", "--out", (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(),
                                  "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json")).at("render");
  EXPECT_EQ(j.at("time_budget_s").get<double>(), 3600.0);
  EXPECT_EQ(j.at("spp"), 5);
  EXPECT_EQ(j.at("stop_reason"), "spp");
  EXPECT_EQ(j.at("settings").at("time_budget"), "1h");
  EXPECT_FALSE(has(exr_facts(tmp / "x.exr").first, "variance.R")) << "no noise target, no variance unless asked";
}

struct Spawned {
  pid_t pid = 0;
  std::chrono::steady_clock::time_point start;
};

Spawned spawn_render(const fs::path& dir, std::vector<std::string> extra) {
  std::vector<std::string> args = {KAPPA_BINARY, "render", cornell(), "--out", (dir / "x.exr").string(),
                                   "--report", (dir / "x.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Spawned s;
  EXPECT_EQ(posix_spawn(&s.pid, KAPPA_BINARY, nullptr, nullptr, argv.data(), environ), 0);
  // The two temporaries exist: the outputs are claimed, the render about to start.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (entries(dir) < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(entries(dir), 2u);
  s.start = std::chrono::steady_clock::now();
  return s;
}

int wait_for(pid_t pid, int& status) {
  EXPECT_EQ(::waitpid(pid, &status, 0), pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Budget, CtrlCAbandonsThePassAndWritesTheCompletedOnes) {
  test::TempDir tmp;
  // An hour's budget: after the first pass (1 spp) each pass is sized to
  // three minutes, so the SIGINT falls inside one.
  const Spawned s = spawn_render(tmp.path(), {"--width", "64", "--height", "64", "--time-budget", "1h"});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const auto sent = std::chrono::steady_clock::now();
  ::kill(s.pid, SIGINT);
  int status = 0;
  EXPECT_EQ(wait_for(s.pid, status), 130) << "status " << status;
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  EXPECT_LT(took, 5.0) << "the pass in progress is abandoned, not finished";
  ASSERT_TRUE(fs::exists(tmp / "x.json"));
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json")).at("render");
  EXPECT_EQ(j.at("interrupted"), true);
  EXPECT_EQ(j.at("stop_reason"), "interrupted");
  EXPECT_GE(j.at("passes").get<int>(), 1);
  EXPECT_GT(j.at("abandoned_rays").get<double>(), 0.0);
  EXPECT_EQ(exr_facts(tmp / "x.exr").second, j.at("spp").get<int>());
  EXPECT_EQ(entries(tmp.path()), 2u) << "the image and the report, no temporary";
}

TEST(Budget, CtrlCBeforeAPassIsCompleteOrTwiceWritesNothing) {
  {
    // The first pass of a noise target is 8 spp: at 1024 x 1024, seconds long.
    test::TempDir tmp;
    const Spawned s = spawn_render(tmp.path(), {"--width", "1024", "--height", "1024", "--target-relmse", "1e-6"});
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(s.pid, SIGINT);
    int status = 0;
    const int code = wait_for(s.pid, status);
    EXPECT_TRUE(code == 130 || (WIFSIGNALED(status) && WTERMSIG(status) == SIGINT)) << "status " << status;
    EXPECT_EQ(entries(tmp.path()), 0u);
  }
  {
    // Two SIGINTs: the second keeps the policy of a render without a budget.
    test::TempDir tmp;
    // The first pass (1 spp) is about a second; the second is sized to three
    // minutes. The second SIGINT follows once the first has surely been
    // delivered (signals of one kind pending together merge), and before a
    // 1024 x 1024 image could be compressed and written.
    const Spawned s = spawn_render(tmp.path(), {"--width", "1024", "--height", "1024", "--time-budget", "1h"});
    std::this_thread::sleep_for(std::chrono::milliseconds(3000));
    ::kill(s.pid, SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(s.pid, SIGINT);
    int status = 0;
    wait_for(s.pid, status);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
    EXPECT_EQ(entries(tmp.path()), 0u);
  }
}

}  // namespace
}  // namespace kappa
