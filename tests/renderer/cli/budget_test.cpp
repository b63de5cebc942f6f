// Budgeted renders from the command line: what the report and the EXR say
// of the passes, and the Ctrl-C policy (docs/command-line.md, exit codes): the first
// SIGINT abandons the pass in progress and writes the completed passes
// (exit 130); before a pass is complete, or at a second SIGINT, nothing is
// written.
#include "image_files.h"
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "core/hash.h"
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
  const test::ExrFile image = test::read_exr_file(path);
  return {image.channels, image.int_attribute("kappa:spp", -1)};
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
  fs::path passes_file;  ///< where kappa says how many passes are complete (KAPPA_TEST_PASSES_FILE)
};

/// Starts a render writing into `dir`, with SIGINT at its default action
/// whatever the test runner's (a runner started with nohup ignores it).
Spawned spawn_render(const fs::path& dir, const fs::path& passes_file, std::vector<std::string> extra) {
  std::vector<std::string> args = {KAPPA_BINARY, "render", cornell(), "--out", (dir / "x.exr").string(),
                                   "--report", (dir / "x.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_strings = {"KAPPA_TEST_PASSES_FILE=" + passes_file.string()};
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("KAPPA_TEST_PASSES_FILE=", 0) != 0) env_strings.emplace_back(*e);
  std::vector<char*> env;
  for (auto& e : env_strings) env.push_back(e.data());
  env.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  Spawned s{0, passes_file};
  EXPECT_EQ(posix_spawn(&s.pid, KAPPA_BINARY, nullptr, &attr, argv.data(), env.data()), 0);
  posix_spawnattr_destroy(&attr);
  return s;
}

/// Waits until kappa says at least `passes` passes are complete (0: the
/// render has begun); false after 60 s.
bool wait_for_passes(const Spawned& s, int passes) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(s.passes_file);
    int n = -1;
    if (in >> n && n >= passes) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

/// The exit status, or SIGKILL and a failure after `seconds`: a render that
/// ignores its interrupt fails the test instead of hanging it.
int wait_or_kill(pid_t pid, int seconds) {
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      ADD_FAILURE() << "kappa still ran " << seconds << " s after the interrupt";
      return status;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return status;
}

/// Renders into `dir` with `extra` flags; once `passes` passes are complete
/// and `settle_ms` more have gone by, sends `sigints` SIGINTs 20 ms apart
/// (pending SIGINTs would merge into one) and returns the exit status.
int interrupt_after(const fs::path& dir, const fs::path& passes_file, std::vector<std::string> extra, int passes,
                    int sigints = 1, int settle_ms = 0) {
  const Spawned s = spawn_render(dir, passes_file, std::move(extra));
  if (!wait_for_passes(s, passes)) {
    ADD_FAILURE() << "kappa never completed " << passes << " passes";
    ::kill(s.pid, SIGKILL);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(settle_ms));
  for (int i = 0; i < sigints; ++i) {
    if (i > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(s.pid, SIGINT);
  }
  return wait_or_kill(s.pid, 60);
}

TEST(Budget, CtrlCAbandonsThePassAndWritesTheCompletedOnes) {
  test::TempDir tmp, side;
  // An hour's budget: after the first pass (1 spp) each pass is sized to
  // three minutes, so the SIGINT, half a second after the first pass, falls
  // inside the second once it traces rays (sent at once, it fell before them
  // under ASan, abandoning none).
  const int status = interrupt_after(tmp.path(), side / "passes",
                                     {"--width", "64", "--height", "64", "--time-budget", "1h"}, 1, 1, 500);
  ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 130);
  ASSERT_TRUE(fs::exists(tmp / "x.json"));
  const auto j = nlohmann::json::parse(test::read_file(tmp / "x.json")).at("render");
  EXPECT_EQ(j.at("interrupted"), true);
  EXPECT_EQ(j.at("stop_reason"), "interrupted");
  EXPECT_GE(j.at("passes").get<int>(), 1);
  EXPECT_GT(j.at("abandoned_rays").get<double>(), 0.0);
  EXPECT_EQ(exr_facts(tmp / "x.exr").second, j.at("spp").get<int>());
  EXPECT_EQ(entries(tmp.path()), 2u) << "the image and the report, no temporary";
}

TEST(Budget, CtrlCBeforeAPassIsCompleteWritesNothing) {
  // The first pass of a noise target is 8 spp: at 1024 x 1024, seconds long.
  test::TempDir tmp, side;
  const int status = interrupt_after(tmp.path(), side / "passes",
                                     {"--width", "1024", "--height", "1024", "--target-relmse", "1e-6"}, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(test::read_file(side / "passes"), "0\n") << "the first pass was not complete";
  EXPECT_EQ(entries(tmp.path()), 0u);
}

TEST(Budget, ASecondCtrlCWritesNothing) {
  // The first SIGINT abandons the second pass; the second arrives while the
  // first pass's 1024 x 1024 image is being compressed and written, and
  // keeps the policy of a render without a budget.
  test::TempDir tmp, side;
  const int status = interrupt_after(tmp.path(), side / "passes",
                                     {"--width", "1024", "--height", "1024", "--time-budget", "1h"}, 1, 2);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  EXPECT_EQ(entries(tmp.path()), 0u);
}

/// A report's section without its times (which differ run to run), at any depth.
nlohmann::json counts_of(nlohmann::json section) {
  if (section.is_object()) {
    section.erase("time_s");
    for (auto& [name, value] : section.items()) value = counts_of(value);
  }
  return section;
}

/// The Cornell box at 48 x 32, 1024 spp, statistics on, one thread: about a
/// second, in passes of about 20 ms with checkpoints. The occluder cache
/// off: with it, which shadow rays walk depends on the passes' tiles (their
/// cache begins with each), and a frame of one pass and one of many count
/// the same shadow rays split otherwise between walks and cache hits.
std::vector<std::string> checkpointed_frame() {
  return {"--width", "48", "--height", "32", "--spp", "1024", "--stats", "on", "--threads", "1",
          "--occluder-cache", "off"};
}

/// Leaves in `dir` the checkpoint of a render of checkpointed_frame()
/// stopped by Ctrl-C after 4 passes (and its image of those passes).
void leave_a_checkpoint(const fs::path& dir, const fs::path& passes_file,
                        std::vector<std::string> flags = checkpointed_frame(), int passes = 4) {
  flags.insert(flags.end(), {"--checkpoint-every", "20ms"});
  const int status = interrupt_after(dir, passes_file, flags, passes);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << "status " << status;
  ASSERT_TRUE(fs::exists(dir / "x.exr.checkpoint"));
}

TEST(Checkpoint, AResumedRenderEndsWithTheImageAndCountsOfARenderNotStopped) {
  // A render of --spp (the reference one pass), and one of a noise target
  // with --adaptive (13 passes; the checkpoint keeps the retired pixels).
  const std::vector<std::string> adaptive = {"--width", "48", "--height", "32", "--target-relmse", "0.0005", "--adaptive",
                                             "--stats", "on", "--threads", "1", "--occluder-cache", "off"};
  for (const auto& frame : {checkpointed_frame(), adaptive}) {
    SCOPED_TRACE(frame[5]);
    test::TempDir tmp, side, ref;
    auto args = std::vector<std::string>{"render", cornell(), "--out", (ref / "x.exr").string(), "--report",
                                         (ref / "x.json").string(), "--quiet"};
    args.insert(args.end(), frame.begin(), frame.end());
    const auto not_stopped = test::run_kappa(args);
    ASSERT_EQ(not_stopped.exit_code, 0) << not_stopped.std_err;
    leave_a_checkpoint(tmp.path(), side / "passes", frame);
    args = {"render", cornell(), "--out", (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(), "--quiet",
            "--resume"};
    args.insert(args.end(), frame.begin(), frame.end());
    const auto resumed = test::run_kappa(args);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.std_err;
    EXPECT_TRUE(test::bitwise_equal(test::read_exr_file(tmp / "x.exr").pixels, test::read_exr_file(ref / "x.exr").pixels));
    const auto a = nlohmann::json::parse(test::read_file(ref / "x.json"));
    const auto b = nlohmann::json::parse(test::read_file(tmp / "x.json"));
    EXPECT_GE(b["render"]["resumed_passes"].get<int>(), 1);
    EXPECT_GT(b["render"]["passes"].get<int>(), b["render"]["resumed_passes"].get<int>());
    for (const char* key : {"spp", "rays", "nonfinite_samples"}) EXPECT_EQ(b["render"][key], a["render"][key]) << key;
    EXPECT_EQ(counts_of(b["rays"]), counts_of(a["rays"]));
    EXPECT_EQ(b["stats"], a["stats"]);
    EXPECT_FALSE(fs::exists(tmp / "x.exr.checkpoint")) << "a finished render's checkpoint is removed";
  }
}

TEST(Checkpoint, ACheckpointOfOtherSettingsOrDamagedIsRefusedWithOneLine) {
  test::TempDir tmp, side;
  leave_a_checkpoint(tmp.path(), side / "passes");
  const fs::path checkpoint = tmp / "x.exr.checkpoint";
  const std::string saved = test::read_file(checkpoint);
  // Resumed with checkpointed_frame()'s flags, `flag` given `value` instead.
  std::string scene = cornell();
  const auto resume = [&](const std::string& flag = "", const std::string& value = "") {
    std::vector<std::string> args = {"render", scene, "--out", (tmp / "x.exr").string(), "--quiet", "--resume"};
    auto frame = checkpointed_frame();
    const auto it = std::find(frame.begin(), frame.end(), flag);
    if (it != frame.end()) *std::next(it) = value;
    else if (!flag.empty()) frame.insert(frame.end(), {flag, value});
    args.insert(args.end(), frame.begin(), frame.end());
    return test::run_kappa(args);
  };
  const auto refused = [&](const test::RunResult& r, const std::string& says) {
    EXPECT_EQ(r.exit_code, 2) << r.std_err;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
    EXPECT_NE(r.std_err.find(says), std::string::npos) << r.std_err;
  };
  // Each case's checkpoint, left as it was by the refusal.
  const auto refused_with = [&](const std::string& bytes, const test::RunResult& r, const std::string& says) {
    refused(r, says);
    EXPECT_TRUE(test::read_file(checkpoint) == bytes) << "a refused checkpoint is left as it was (" << says << ")";
  };
  refused_with(saved, resume("--spp", "512"), "its spp is 1024, here 512");
  refused_with(saved, resume("--seed", "7"), "its seed is");
  refused_with(saved, resume("--width", "40"), "its width is");
  refused_with(saved, resume("--occluder-cache", "on"), "its occluder_cache is \"off\", here \"on\"");
  // Another scene: the Cornell box with a comment more in its OBJ, the same
  // geometry but other inputs.
  fs::copy(test::assets_dir() / "cornell-box", side / "other", fs::copy_options::recursive);
  test::write_file(side / "other" / "cornell_box.obj",
                   test::read_file(side / "other" / "cornell_box.obj") + "# another scene's\n");
  scene = (side / "other" / "scene.json").string();
  refused_with(saved, resume(), "its input_hash is");
  scene = cornell();
  // Cut short, and one byte changed.
  const std::string cut = saved.substr(0, saved.size() / 2);
  test::write_file(checkpoint, cut);
  refused_with(cut, resume(), "a damaged checkpoint");
  std::string changed = saved;
  changed[changed.size() / 2] ^= 1;
  test::write_file(checkpoint, changed);
  refused_with(changed, resume(), "a damaged checkpoint");
  // Another Kappa's, its hash made again.
  std::string other = saved;
  const std::size_t at = other.find("\"kappa_version\":\"") + 17;
  other.replace(at, other.find('"', at) - at, "0123456789ab");
  other.resize(other.size() - 17);
  char hash[18];
  std::snprintf(hash, sizeof hash, "%016llx\n", static_cast<unsigned long long>(fnv1a64(other)));
  test::write_file(checkpoint, other + hash);
  refused_with(other + hash, resume(), "a checkpoint of Kappa 0123456789ab");
  test::write_file(checkpoint, saved);
  // None at all; and a checkpoint cannot be kept beside standard output.
  fs::remove(checkpoint);
  const auto none = resume();
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.std_err.find("--resume: cannot read"), std::string::npos) << none.std_err;
  const auto dash = test::run_kappa({"render", cornell(), "--out", "-", "--checkpoint-every", "1s", "--quiet"});
  EXPECT_EQ(dash.exit_code, 2);
  EXPECT_NE(dash.std_err.find("needs the image to be a file"), std::string::npos) << dash.std_err;
  // A new render where a stopped one left its checkpoint: refused, not written over.
  test::write_file(checkpoint, saved);
  std::vector<std::string> anew = {"render", cornell(), "--out", (tmp / "x.exr").string(), "--quiet",
                                   "--checkpoint-every", "20ms"};
  const auto frame = checkpointed_frame();
  anew.insert(anew.end(), frame.begin(), frame.end());
  refused_with(saved, test::run_kappa(anew), "the checkpoint of a render stopped before: --resume to go on from it");
  // Anything but a plain file where the checkpoint goes: neither written
  // through, nor read, nor removed.
  fs::remove(checkpoint);
  fs::create_directory(checkpoint);
  refused(resume(), "not a plain file");
  refused(test::run_kappa(anew), "not a plain file");
  EXPECT_TRUE(fs::is_directory(checkpoint));
  fs::remove(checkpoint);
  test::write_file(side / "elsewhere", saved);
  fs::create_symlink(side / "elsewhere", checkpoint);
  refused(resume(), "not a plain file");
  EXPECT_TRUE(fs::is_symlink(checkpoint));
  EXPECT_TRUE(test::read_file(side / "elsewhere") == saved);
}

TEST(Checkpoint, AResumedRenderThatAddsNoPassKeepsItsCheckpoint) {
  // A time budget's checkpoint resumed without the budget: the render's
  // --spp, 64 by default, is reached already. Each pass adds a sample at
  // least, and a checkpoint is saved every pass or two (passes of at most
  // 20 ms, saved every 20 ms), so 100 passes are past 64 spp on any
  // machine (40 were not under ASan: 1 spp a pass). Its image is written, and the checkpoint, whose
  // passes another --time-budget would go on from, is kept.
  test::TempDir tmp, side;
  const std::vector<std::string> budgeted = {"--width", "48", "--height", "32", "--time-budget", "10m",
                                             "--threads", "1", "--occluder-cache", "off"};
  leave_a_checkpoint(tmp.path(), side / "passes", budgeted, 100);
  const fs::path checkpoint = tmp / "x.exr.checkpoint";
  const std::string saved = test::read_file(checkpoint);
  const auto r = test::run_kappa({"render", cornell(), "--out", (tmp / "x.exr").string(), "--report",
                                  (tmp / "x.json").string(), "--quiet", "--resume", "--width", "48", "--height",
                                  "32", "--threads", "1", "--occluder-cache", "off"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.std_err.find("the resumed render added no pass"), std::string::npos) << r.std_err;
  const auto report = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  EXPECT_EQ(report["render"]["passes"], report["render"]["resumed_passes"]);
  EXPECT_GE(report["render"]["spp"].get<int>(), 64);
  ASSERT_TRUE(fs::exists(checkpoint));
  EXPECT_TRUE(test::read_file(checkpoint) == saved);
}

}  // namespace
}  // namespace kappa
