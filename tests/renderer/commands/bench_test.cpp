// `kappa bench`: runs every accelerator on the same rays and writes the
// figures with the documented JSON keys.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

TEST(Bench, WritesEveryFigureForEveryAcceleratorClassAndThreadCount) {
  test::TempDir tmp;
  const auto json_path = tmp / "bench.json";
  const auto r = run_kappa({"bench", cornell(), "--n", "3000", "--repeat", "2", "--threads", "1,2", "--json",
                            json_path.string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(json_path));
  EXPECT_EQ(j.at("n"), 3000);
  EXPECT_EQ(j.at("repeat"), 2);
  EXPECT_NE(j.at("scene").get<std::string>().find("cornell-box"), std::string::npos);
  for (const char* accel : {"naive", "grid", "grid2", "embree", "embree-fast"}) {  // the default list
    EXPECT_GT(j.at("accels").at(accel).at("build_s").get<double>(), 0.0) << accel;  // a measured time
    EXPECT_LT(j.at("accels").at(accel).at("build_s").get<double>(), 10.0) << accel;
    EXPECT_TRUE(j.at("accels").at(accel).contains("bytes")) << accel;
  }
  EXPECT_GT(j.at("accels").at("grid").at("bytes").get<double>(), 0.0);
  EXPECT_GT(j.at("accels").at("grid2").at("bytes").get<double>(), 0.0);
  EXPECT_GT(j.at("accels").at("embree").at("bytes").get<double>(), 0.0);
  EXPECT_GT(j.at("accels").at("embree-fast").at("bytes").get<double>(), 0.0);
  // 5 accelerators x 4 ray classes x 2 thread counts.
  ASSERT_EQ(j.at("results").size(), 40u);
  std::map<std::string, double> embree_median, fast_median;  // by "rays threads"
  for (const auto& row : j.at("results")) {
    const std::string key = row.at("rays").get<std::string>() + " " + row.at("threads").dump();
    if (row.at("accel") == "embree") embree_median[key] = row.at("mrays_per_s_median");
    if (row.at("accel") == "embree-fast") fast_median[key] = row.at("mrays_per_s_median");
  }
  ASSERT_EQ(embree_median.size(), 8u);
  ASSERT_EQ(fast_median.size(), 8u);
  for (const auto& row : j.at("results")) {
    for (const char* key : {"accel", "rays", "threads", "mrays_per_s_median", "mrays_per_s_min", "mrays_per_s_max",
                            "ratio_to_embree", "ratio_to_embree_fast"})
      ASSERT_TRUE(row.contains(key)) << key;
    const double median = row.at("mrays_per_s_median");
    EXPECT_GT(median, 0.0);
    // The ratios are this row's median over each Embree's on the same rays and threads.
    const std::string key = row.at("rays").get<std::string>() + " " + row.at("threads").dump();
    const double embree = embree_median.at(key), fast = fast_median.at(key);
    EXPECT_NEAR(row.at("ratio_to_embree").get<double>(), median / embree, 1e-12 * median / embree) << row.dump();
    EXPECT_NEAR(row.at("ratio_to_embree_fast").get<double>(), median / fast, 1e-12 * median / fast) << row.dump();
  }
  // The table names both peers.
  EXPECT_NE(r.std_out.find("vs embree-fast"), std::string::npos) << r.std_out;
  EXPECT_TRUE(r.std_err.empty()) << r.std_err;  // the table goes to stdout
}

TEST(Bench, ExactAcceleratorsFindTheSameHitsOnTheSameRays) {
  test::TempDir tmp;
  const auto r = run_kappa({"bench", cornell(), "--accel", "naive,grid", "--n", "2000", "--repeat", "1", "--threads", "1",
                            "--json", (tmp / "b.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "b.json"));
  std::map<std::string, std::uint64_t> naive_hits, grid_hits;
  for (const auto& row : j.at("results"))
    (row.at("accel") == "naive" ? naive_hits : grid_hits)[row.at("rays").get<std::string>()] = row.at("hits");
  ASSERT_EQ(naive_hits.size(), 4u);
  EXPECT_EQ(naive_hits, grid_hits);
  EXPECT_GT(naive_hits["camera"], 1000u);  // the Cornell box fills most of the view
}

TEST(Bench, NaiveIsSkippedWithANoteWhenItWouldTakeTooLong) {
  test::TempDir tmp;
  const auto r = run_kappa({"bench", cornell(), "--accel", "naive,grid,embree", "--n", "1000", "--repeat", "1",
                            "--threads", "1", "--naive-budget", "0", "--json", (tmp / "b.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.std_out.find("note: naive skipped: 32 triangles x 1000 rays would take about"), std::string::npos)
      << r.std_out;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "b.json"));
  EXPECT_FALSE(j.at("accels").contains("naive"));
  EXPECT_TRUE(j.at("accels").contains("grid"));
  EXPECT_TRUE(j.at("accels").contains("embree"));
  for (const auto& row : j.at("results")) EXPECT_NE(row.at("accel"), "naive");
  EXPECT_EQ(j.at("results").size(), 8u);  // grid and Embree x 4 classes

  // Without Embree there is nothing to compare with: every ratio is null.
  const auto r2 = run_kappa({"bench", cornell(), "--accel", "grid", "--n", "500", "--repeat", "1", "--threads", "1",
                             "--json", (tmp / "c.json").string()});
  ASSERT_EQ(r2.exit_code, 0) << r2.std_err;
  // The parsed report outlives the loop (a range over a temporary's member dangles: ASan found it).
  const nlohmann::json grid_only = nlohmann::json::parse(test::read_file(tmp / "c.json"));
  for (const auto& row : grid_only.at("results")) {
    EXPECT_TRUE(row.at("ratio_to_embree").is_null());
    EXPECT_TRUE(row.at("ratio_to_embree_fast").is_null());
  }
}

TEST(Bench, BadOptionsAreRefused) {
  test::TempDir tmp;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bench", cornell(), "--rays", "bogus"}, {"bench", cornell(), "--accel", "bvh"},
        {"bench", cornell(), "--threads", "0"}, {"bench", cornell(), "--n", "0"},
        {"bench", (tmp / "missing.json").string()}}) {
    const auto r = run_kappa(args);
    EXPECT_EQ(r.exit_code, 2) << args[2];
    EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
  }
}

}  // namespace
}  // namespace kappa
