// kappa-mpi (issue 48): a frame rendered by 1, 2 or 3 ranks of an MPI job on
// this machine is the image build/kappa renders, bitwise, with the same
// counts; bad input stops every rank with one line; only render runs on more
// than one rank. Skipped where kappa-mpi is not built (no MPI found).
#include <gtest/gtest.h>

#include <sched.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <thread>
#include <utility>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "image_files.h"
#include "test_util.h"

namespace kappa {
namespace {

#ifdef KAPPA_MPI_BINARY
/// mpirun -np `ranks` kappa-mpi `args`, as root where the sandbox is root,
/// under a timeout (a hang fails with 124).
test::RunResult run_mpi(int ranks, const std::vector<std::string>& args, const std::string& mpirun_flags = "") {
  test::TempDir tmp;
  std::string cmd =
      "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none "
      "OMPI_MCA_rmaps_base_oversubscribe=1 timeout 180 mpirun --oversubscribe " + mpirun_flags + " -np " +
      std::to_string(ranks) + " " + test::shell_quote(KAPPA_MPI_BINARY);
  for (const auto& a : args) cmd += " " + test::shell_quote(a);
  cmd += " </dev/null 2>" + test::shell_quote((tmp / "stderr").string()) + " >" +
         test::shell_quote((tmp / "stdout").string());
  const int status = std::system(cmd.c_str());
  test::RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.std_err = test::read_file(tmp / "stderr");
  r.std_out = test::read_file(tmp / "stdout");
  return r;
}

int kappa_lines(const std::string& text) {
  int n = 0;
  for (const auto& line : test::RunResult{0, text, ""}.err_lines()) n += line.rfind("kappa: error:", 0) == 0;
  return n;
}
#endif

/// build/kappa `args` into `dir`: the image and report kappa-mpi's are compared with.
std::pair<test::ExrFile, nlohmann::json> render_one_process(const std::filesystem::path& dir,
                                                            std::vector<std::string> args) {
  args.insert(args.end(), {"--out", (dir / "one.exr").string(), "--report", (dir / "one.json").string()});
  const test::RunResult one = test::run_kappa(args);
  EXPECT_EQ(one.exit_code, 0) << one.std_err;
  return {test::read_exr_file(dir / "one.exr"), nlohmann::json::parse(test::read_file(dir / "one.json"))};
}

/// A report's section without its times (which differ run to run), at any depth.
nlohmann::json counts_of(nlohmann::json section) {
  if (section.is_object()) {
    section.erase("time_s");
    for (auto& [name, value] : section.items()) value = counts_of(value);
  }
  return section;
}

TEST(MpiRender, OneTwoAndThreeRanksRenderTheOneProcessImageAndCountsBitwise) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  // 6 x 5 tiles, the last row and column cut; the default accelerator
  // (grid2, its occluder cache per tile). Statistics off with the geometric
  // AOVs; on, with the cost AOV, every path counted per cell (the Cornell
  // box's few cells) and 1 path in 4; on, with naive (counted per class only).
  const std::vector<std::vector<std::string>> settings = {
      {"--stats", "off", "--aov", "albedo,normal,depth"},
      {"--stats", "on", "--aov", "cost"},
      {"--stats", "on", "--cell-sample", "4"},
      {"--stats", "on", "--accel", "naive"}};  // per class only: an accelerator without cells
  for (const auto& setting : settings) {
    std::vector<std::string> common = {"render", scene, "--spp", "4", "--width", "96", "--height", "72", "-q"};
    common.insert(common.end(), setting.begin(), setting.end());
    const std::string what = setting[1] + " " + setting[3];
    const auto [reference, reference_report] = render_one_process(dir.path(), common);
    auto args = common;
    for (int ranks : {1, 2, 3}) {
      const std::string name = "ranks" + std::to_string(ranks);
      args = common;
      // One render thread a rank: the ranks, not the threads, share the tiles.
      args.insert(args.end(), {"--threads", "1", "--out", (dir / (name + ".exr")).string(), "--report",
                               (dir / (name + ".json")).string()});
      const test::RunResult r = run_mpi(ranks, args);
      ASSERT_EQ(r.exit_code, 0) << what << ", " << ranks << " ranks: " << r.std_err;
      const test::ExrFile image = test::read_exr_file(dir / (name + ".exr"));
      ASSERT_EQ(image.channels, reference.channels);
      EXPECT_TRUE(test::bitwise_equal(image.pixels, reference.pixels)) << what << ", " << ranks << " ranks";
      const auto report = nlohmann::json::parse(test::read_file(dir / (name + ".json")));
      EXPECT_EQ(report["render"]["rays"], reference_report["render"]["rays"]) << what << ", " << ranks << " ranks";
      EXPECT_EQ(report["render"]["nonfinite_samples"], reference_report["render"]["nonfinite_samples"]);
      // The frame's estimate sums every tile's, each gathered from its rank.
      EXPECT_EQ(report["render"]["relmse_estimate"], reference_report["render"]["relmse_estimate"]) << what;
      // Every count, kappa and p_tot of every class, summed over the ranks.
      const nlohmann::json none;
      EXPECT_EQ(counts_of(report.value("rays", none)), counts_of(reference_report.value("rays", none)))
          << what << ", " << ranks << " ranks";
      EXPECT_EQ(report.value("stats", none), reference_report.value("stats", none)) << what << ", " << ranks << " ranks";
      if (setting[1] == "on") {
        EXPECT_TRUE(report.value("rays", none).contains("camera")) << what;
      }
      // Who rendered what: every tile and ray once, one thread a rank.
      const nlohmann::json& mpi = report["mpi"];
      ASSERT_EQ(mpi["per_rank"].size(), std::size_t(ranks)) << report.dump(1);
      EXPECT_EQ(mpi["ranks"], ranks);
      EXPECT_EQ(mpi["threads_per_rank"], 1);
      std::uint64_t tiles = 0, rays = 0;
      for (int k = 0; k < ranks; ++k) {
        const nlohmann::json& share = mpi["per_rank"][std::size_t(k)];
        EXPECT_EQ(share["rank"], k);
        EXPECT_FALSE(share["host"].get<std::string>().empty());
        tiles += share["tiles"].get<std::uint64_t>();
        rays += share["rays"].get<std::uint64_t>();
        EXPECT_GT(share["time_s"].get<double>(), 0.0);
      }
      EXPECT_EQ(tiles, 30u);  // 96 x 72 in 16-pixel tiles: 6 x 5
      EXPECT_EQ(rays, report["render"]["rays"].get<std::uint64_t>());
      EXPECT_GE(mpi["imbalance"].get<double>(), 1.0);
      EXPECT_EQ(mpi["first_pass_order"], "tiles");  // no pilot ran
      EXPECT_TRUE(mpi["tile_predicted"].is_null());
    }
  }
#endif
}

TEST(MpiRender, AccelAutoAndGridResModelBuildWhatTheWritingRankChose) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  // Statistics on: every rank's per-cell counts are summed cell by cell, so
  // a rank that built another grid than rank 0 changes them (the images of
  // the exact accelerators are the same whichever runs).
  const std::vector<std::vector<std::string>> settings = {{"--accel", "auto"},
                                                          {"--accel", "grid", "--grid-res", "model"}};
  for (const auto& setting : settings) {
    std::vector<std::string> common = {"render", scene, "--spp", "2", "--width", "64", "--height", "48",
                                       "-q",     "--stats", "on", "--threads", "1"};
    common.insert(common.end(), setting.begin(), setting.end());
    const std::string what = setting.back();
    const auto [reference, reference_report] = render_one_process(dir.path(), common);
    auto args = common;
    for (int ranks : {2, 3}) {
      args = common;
      args.insert(args.end(), {"--out", (dir / "k.exr").string(), "--report", (dir / "k.json").string()});
      const test::RunResult r = run_mpi(ranks, args);
      ASSERT_EQ(r.exit_code, 0) << what << ", " << ranks << " ranks: " << r.std_err;
      EXPECT_TRUE(test::bitwise_equal(test::read_exr_file(dir / "k.exr").pixels, reference.pixels)) << what;
      const auto report = nlohmann::json::parse(test::read_file(dir / "k.json"));
      const nlohmann::json none;
      EXPECT_EQ(report["accel"], reference_report["accel"]) << what;
      EXPECT_EQ(report["render"]["settings"]["grid_res"], reference_report["render"]["settings"]["grid_res"]) << what;
      const auto chosen = [](const nlohmann::json& j) {
        return j.contains("accel_choice") && j["accel_choice"].is_object() ? j["accel_choice"]["chosen"] : nlohmann::json();
      };
      EXPECT_EQ(chosen(report), chosen(reference_report)) << what;
      EXPECT_EQ(counts_of(report.value("rays", none)), counts_of(reference_report.value("rays", none)))
          << what << ", " << ranks << " ranks";
      // The pilot orders the first pass's tiles: one cost a tile, 4 x 3.
      EXPECT_EQ(report["mpi"]["first_pass_order"], "pilot") << what;
      EXPECT_EQ(report["mpi"]["tile_predicted"].size(), 12u) << what;
    }
  }
#endif
}

/// Pearson's correlation of two equally long series.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

TEST(MpiRender, ThePilotPredictsWhichTilesCostMore) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  // The bunny on its ground against an empty sky: the predicted costs
  // against each tile's cells and triangle tests in the frame (the cost
  // AOVs, counted, so the test does not depend on the machine's speed):
  // correlation 0.82 (-0.43 with the pilot's rows upside down). Against the
  // tiles' seconds at 256 x 256, 8 spp, 2 ranks: 0.90 (and at 512 x 512 on
  // Sponza 0.72-0.84, the dragon 0.86).
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "bunny-lowres" / "scene_lowres.json").string();
  const test::RunResult r =
      run_mpi(2, {"render", scene, "--spp", "4", "--width", "128", "--height", "128", "--grid-res", "model", "--aov",
                  "cost", "--threads", "1", "-q", "--out", (dir / "b.exr").string(), "--report",
                  (dir / "b.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto report = nlohmann::json::parse(test::read_file(dir / "b.json"));
  ASSERT_EQ(report["mpi"]["first_pass_order"], "pilot");
  const std::vector<double> predicted = report["mpi"]["tile_predicted"].get<std::vector<double>>();
  ASSERT_EQ(predicted.size(), 64u);  // 8 x 8 tiles
  const test::ExrFile image = test::read_exr_file(dir / "b.exr");
  const std::vector<float> cells = image.values("cost.cells"), tests = image.values("cost.tests");
  std::vector<double> counted(64, 0.0);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const std::size_t p = std::size_t(y) * 128 + std::size_t(x);
      counted[std::size_t(y / 16) * 8 + std::size_t(x / 16)] += double(cells[p]) + double(tests[p]);
    }
  EXPECT_GT(correlation(predicted, counted), 0.7) << report["mpi"].dump();
#endif
}

TEST(MpiRender, ABudgetedRenderIsTheOneProcessRenderBitwiseAndEveryRankTakesTheSamePasses) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  // A noise target decides its passes from the frame's estimate alone: the
  // same on any number of ranks, each keeping every pixel's sums. Adaptive:
  // the pixels below the target stop sampling, on every rank alike.
  const std::vector<std::string> common = {"render", scene, "--width", "64", "--height", "48", "-q",
                                           "--target-relmse", "0.005", "--adaptive", "--adaptive-min-spp", "8",
                                           "--spp", "64", "--aov", "spp,albedo", "--threads", "1"};
  auto args = common;
  args.insert(args.end(), {"--stats", "on", "--out", (dir / "one.exr").string(), "--report", (dir / "one.json").string()});
  const test::RunResult one = test::run_kappa(args);
  ASSERT_EQ(one.exit_code, 0) << one.std_err;
  const test::ExrFile reference = test::read_exr_file(dir / "one.exr");
  const auto reference_report = nlohmann::json::parse(test::read_file(dir / "one.json"));
  ASSERT_GT(reference_report["render"]["passes"].get<int>(), 2);
  EXPECT_LT(reference_report["render"]["spp_min"].get<int>(), reference_report["render"]["spp_max"].get<int>());
  for (int ranks : {2, 3}) {
    args = common;
    args.insert(args.end(), {"--stats", "on", "--out", (dir / "k.exr").string(), "--report", (dir / "k.json").string()});
    const test::RunResult r = run_mpi(ranks, args);
    ASSERT_EQ(r.exit_code, 0) << ranks << " ranks: " << r.std_err;
    EXPECT_TRUE(test::bitwise_equal(test::read_exr_file(dir / "k.exr").pixels, reference.pixels)) << ranks << " ranks";
    const auto report = nlohmann::json::parse(test::read_file(dir / "k.json"));
    for (const char* key : {"passes", "spp", "spp_min", "spp_max", "spp_mean", "relmse_estimate", "stop_reason", "rays"})
      EXPECT_EQ(report["render"][key], reference_report["render"][key]) << key << ", " << ranks << " ranks";
    const nlohmann::json none;
    EXPECT_EQ(counts_of(report.value("rays", none)), counts_of(reference_report.value("rays", none))) << ranks;
    std::uint64_t tiles = 0;
    for (const auto& share : report["mpi"]["per_rank"]) tiles += share["tiles"].get<std::uint64_t>();
    EXPECT_EQ(tiles, 12u * report["render"]["passes"].get<std::uint64_t>());  // 4 x 3 tiles a pass
  }
  // A time budget: passes sized by rank 0's clock, taken by every rank. Every
  // pixel has the frame's samples (the spp AOV), whichever rank drew them.
  args = common;
  args.erase(args.begin() + 7, args.begin() + 14);  // no noise target, no cap of 64
  args.insert(args.end(), {"--time-budget", "2s", "--spp", "100000", "--stats", "off", "--out", (dir / "t.exr").string(),
                           "--report", (dir / "t.json").string()});
  const test::RunResult timed = run_mpi(2, args);
  ASSERT_EQ(timed.exit_code, 0) << timed.std_err;
  const auto report = nlohmann::json::parse(test::read_file(dir / "t.json"));
  const int spp = report["render"]["spp"].get<int>();
  EXPECT_GT(report["render"]["passes"].get<int>(), 1);
  EXPECT_EQ(report["render"]["stop_reason"], "time-budget");
  EXPECT_EQ(report["render"]["spp_min"], spp);
  EXPECT_EQ(report["render"]["spp_max"], spp);
  const test::ExrFile image = test::read_exr_file(dir / "t.exr");
  const std::vector<float> samples = image.values("spp");
  ASSERT_EQ(samples.size(), std::size_t(64 * 48));
  for (std::size_t p = 0; p < samples.size(); ++p) ASSERT_EQ(samples[p], float(spp)) << "pixel " << p;
#endif
}

TEST(MpiRender, ThreadsDefaultToTheHostsCoresSharedByItsRanks) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  cpu_set_t set;
  ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  const int cores = CPU_COUNT(&set);
  // Unbound, each rank takes its share of the cores.
  for (int ranks : {1, 2, 3}) {
    const auto report_path = dir / ("r" + std::to_string(ranks) + ".json");
    const test::RunResult r = run_mpi(ranks,
                                      {"render", scene, "--spp", "1", "--width", "32", "--height", "32", "-q",
                                       "--stats", "off", "--out", (dir / "a.exr").string(), "--report",
                                       report_path.string()},
                                      "--bind-to none");
    ASSERT_EQ(r.exit_code, 0) << r.std_err;
    const auto report = nlohmann::json::parse(test::read_file(report_path));
    EXPECT_EQ(report["mpi"]["threads_per_rank"], std::max(1, cores / ranks)) << ranks << " ranks on " << cores << " cores";
    EXPECT_EQ(report["render"]["threads"], std::max(1, cores / ranks));
    EXPECT_EQ(r.std_err.find("--bind-to none"), std::string::npos) << r.std_err;
  }
  // Bound to one core (mpirun's default for one or two ranks), a rank alone
  // on a host of more runs one thread and says how to give it its share.
  if (cores > 1) {
    const test::RunResult bound = run_mpi(1, {"render", scene, "--spp", "1", "--width", "32", "--height", "32", "-q",
                                              "--stats", "off", "--out", (dir / "a.exr").string(), "--report",
                                              (dir / "bound.json").string()},
                                          "--bind-to core");
    ASSERT_EQ(bound.exit_code, 0) << bound.std_err;
    EXPECT_EQ(nlohmann::json::parse(test::read_file(dir / "bound.json"))["mpi"]["threads_per_rank"], 1);
    EXPECT_NE(bound.std_err.find("--bind-to none"), std::string::npos) << bound.std_err;
  }
#endif
}

#ifdef KAPPA_MPI_BINARY
/// The pid of the kappa-mpi process of rank `rank` whose command line holds
/// `marker`, or 0.
pid_t rank_process(int rank, const std::string& marker) {
  const std::string rank_entry = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = test::read_file(entry.path() / "cmdline"), environ = test::read_file(entry.path() / "environ");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    environ.push_back('\0');
    if (cmdline.find("kappa-mpi") == std::string::npos || cmdline.find(marker) == std::string::npos) continue;
    if (environ.find(rank_entry + '\0') != std::string::npos) return pid_t(std::stoi(name));
  }
  return 0;
}
#endif

TEST(MpiRender, ARankKilledWhileRenderingEndsTheJobWithNothingWritten) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto out = dir / "killed.exr", report = dir / "killed.json";
  // Long enough to be killed in the middle (about a minute on one thread a rank).
  test::RunResult r;
  std::thread job([&] {
    r = run_mpi(2, {"render", scene, "--spp", "4096", "--width", "256", "--height", "256", "-q", "--stats", "off",
                    "--threads", "1", "--out", out.string(), "--report", report.string()});
  });
  // Rank 1 is killed two seconds after it is found: loaded, built and
  // rendering (the Cornell box loads and builds in milliseconds).
  pid_t victim = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline && (victim = rank_process(1, out.string())) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  if (victim != 0) {
    std::this_thread::sleep_for(std::chrono::seconds(2));
    EXPECT_EQ(kill(victim, SIGKILL), 0);
  }
  job.join();
  ASSERT_NE(victim, 0) << "rank 1 was not found rendering: " << r.std_err;
  EXPECT_NE(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.exit_code, 124) << "the job did not end: " << r.std_err;  // timeout's
  // No image, no report, no temporary of either.
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) left.push_back(entry.path().filename().string());
  EXPECT_TRUE(left.empty()) << left.size() << " files left, the first " << (left.empty() ? "" : left[0]) << "\n" << r.std_err;
#endif
}

TEST(MpiRender, AJobWhoseRankDiedResumesOnAnyNumberOfRanksToTheImageOfARenderNotStopped) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir, ref;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  // The occluder cache off: with it, which shadow rays walk depends on the
  // passes' tiles (budget_test.cpp's checkpointed_frame says why).
  const std::vector<std::string> frame = {"--width", "32",      "--height", "32",  "--spp", "2048", "-q",
                                          "--stats", "on",      "--threads", "1",  "--occluder-cache", "off"};
  auto args = std::vector<std::string>{"render", scene, "--out", (ref / "x.exr").string(), "--report",
                                       (ref / "x.json").string()};
  args.insert(args.end(), frame.begin(), frame.end());
  const test::RunResult one_pass = test::run_kappa(args);
  ASSERT_EQ(one_pass.exit_code, 0) << one_pass.std_err;
  const auto out = dir / "x.exr", checkpoint = dir / "x.exr.checkpoint";
  args = {"render", scene, "--out", out.string(), "--report", (dir / "x.json").string()};
  args.insert(args.end(), frame.begin(), frame.end());
  // 2 ranks saving every 50 ms; rank 1 killed once rank 0 has saved one.
  auto checkpointed = args;
  checkpointed.insert(checkpointed.end(), {"--checkpoint-every", "50ms"});
  test::RunResult killed;
  std::thread job([&] { killed = run_mpi(2, checkpointed); });
  pid_t victim = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline && (victim == 0 || !std::filesystem::exists(checkpoint))) {
    if (victim == 0) victim = rank_process(1, out.string());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (victim != 0) kill(victim, SIGKILL);
  job.join();
  ASSERT_NE(victim, 0) << killed.std_err;
  ASSERT_NE(killed.exit_code, 0) << "the job finished before rank 1 was killed: " << killed.std_err;
  ASSERT_TRUE(std::filesystem::exists(checkpoint)) << killed.std_err;
  EXPECT_FALSE(std::filesystem::exists(out));
  const std::string saved = test::read_file(checkpoint);
  // Resumed on 3 ranks, and on one process (build/kappa): the one-pass image,
  // and every count.
  const auto reference = test::read_exr_file(ref / "x.exr").pixels;
  const auto reference_report = nlohmann::json::parse(test::read_file(ref / "x.json"));
  auto resume = args;
  resume.push_back("--resume");
  for (int ranks : {3, 0}) {
    test::write_file(checkpoint, saved);
    const test::RunResult r = ranks ? run_mpi(ranks, resume) : test::run_kappa(resume);
    ASSERT_EQ(r.exit_code, 0) << ranks << " ranks: " << r.std_err;
    EXPECT_TRUE(test::bitwise_equal(test::read_exr_file(out).pixels, reference)) << ranks << " ranks";
    const auto report = nlohmann::json::parse(test::read_file(dir / "x.json"));
    EXPECT_GE(report["render"]["resumed_passes"].get<int>(), 1);
    EXPECT_EQ(report["render"]["rays"], reference_report["render"]["rays"]) << ranks << " ranks";
    EXPECT_EQ(counts_of(report["rays"]), counts_of(reference_report["rays"])) << ranks << " ranks";
    EXPECT_FALSE(std::filesystem::exists(checkpoint));
  }
#endif
}

TEST(MpiRender, BadInputStopsEveryRankWithOneLine) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  test::TempDir dir;
  const test::RunResult missing = run_mpi(3, {"render", (dir / "absent.json").string(), "--stats", "off",
                                              "--out", (dir / "a.exr").string()});
  EXPECT_EQ(missing.exit_code, 2) << missing.std_err;
  EXPECT_EQ(kappa_lines(missing.std_err), 1) << missing.std_err;
  EXPECT_NE(missing.std_err.find("absent.json"), std::string::npos) << missing.std_err;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const test::RunResult option = run_mpi(2, {"render", scene, "--no-such-option"});
  EXPECT_EQ(option.exit_code, 2);
  EXPECT_EQ(kappa_lines(option.std_err), 1) << option.std_err;
  // A bad value every rank reads alike, refused before loading.
  const test::RunResult aov = run_mpi(2, {"render", scene, "--stats", "off", "--aov", "colour",
                                          "--out", (dir / "b.exr").string()});
  EXPECT_EQ(aov.exit_code, 2);
  EXPECT_EQ(kappa_lines(aov.std_err), 1) << aov.std_err;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "b.exr"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
#endif
}

TEST(MpiRender, OnlyRenderRunsOnMoreThanOneRank) {
#ifndef KAPPA_MPI_BINARY
  GTEST_SKIP() << "kappa-mpi is not built (CMake found no MPI)";
#else
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const test::RunResult bench = run_mpi(2, {"bench", scene, "--n", "64"});
  EXPECT_EQ(bench.exit_code, 2);
  EXPECT_EQ(kappa_lines(bench.std_err), 1) << bench.std_err;
  const test::RunResult alone = run_mpi(1, {"bench", scene, "--n", "64", "--repeat", "1", "--accel", "grid"});
  EXPECT_EQ(alone.exit_code, 0) << alone.std_err;
  EXPECT_NE(alone.std_out.find("Mrays/s"), std::string::npos);
#endif
}

}  // namespace
}  // namespace kappa
