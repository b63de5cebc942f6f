// kappa-mpi (issue 48): a frame rendered by 1, 2 or 3 ranks of an MPI job on
// this machine is the image build/kappa renders, bitwise, with the same
// counts; bad input stops every rank with one line; only render runs on more
// than one rank. Skipped where kappa-mpi is not built (no MPI found).
#include <gtest/gtest.h>

#include <sys/wait.h>

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
test::RunResult run_mpi(int ranks, const std::vector<std::string>& args) {
  test::TempDir tmp;
  std::string cmd =
      "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none "
      "OMPI_MCA_rmaps_base_oversubscribe=1 timeout 180 mpirun --oversubscribe -np " +
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
  // box's few cells) and 1 path in 4.
  const std::vector<std::vector<std::string>> settings = {
      {"--stats", "off", "--aov", "albedo,normal,depth"},
      {"--stats", "on", "--aov", "cost"},
      {"--stats", "on", "--cell-sample", "4"}};
  for (const auto& setting : settings) {
    std::vector<std::string> common = {"render", scene, "--spp", "4", "--width", "96", "--height", "72", "-q"};
    common.insert(common.end(), setting.begin(), setting.end());
    const std::string what = setting[1] + " " + setting[3];
    auto args = common;
    args.insert(args.end(), {"--out", (dir / "one.exr").string(), "--report", (dir / "one.json").string()});
    const test::RunResult one = test::run_kappa(args);
    ASSERT_EQ(one.exit_code, 0) << one.std_err;
    const test::ExrFile reference = test::read_exr_file(dir / "one.exr");
    const auto reference_report = nlohmann::json::parse(test::read_file(dir / "one.json"));
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
      if (setting[1] == "on") EXPECT_TRUE(report.value("rays", none).contains("camera")) << what;
    }
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
  // What a frame shared by ranks cannot do yet is refused before loading.
  const test::RunResult budget = run_mpi(2, {"render", scene, "--stats", "off", "--time-budget", "1s",
                                             "--out", (dir / "b.exr").string()});
  EXPECT_EQ(budget.exit_code, 2);
  EXPECT_EQ(kappa_lines(budget.std_err), 1) << budget.std_err;
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
