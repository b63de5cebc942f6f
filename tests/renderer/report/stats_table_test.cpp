// The per-class table render and cast print: read from the report, units in
// the heads, undefined values as "-".
#include "renderer/report/stats_table.h"

#include <gtest/gtest.h>

#include <sstream>
#include <vector>

namespace kappa {
namespace {

using json = nlohmann::ordered_json;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

json grid_class(double cells, double predicted) {
  return {{"count", 1000},      {"cells_per_ray", cells}, {"cells_per_ray_predicted", predicted},
          {"tests_per_ray", 3.25}, {"refs_per_ray", 7.5},  {"p_tot", cells},
          {"r", nullptr},        {"kappa", 0.875},        {"kappa_eq25", 0.9375}};
}

TEST(StatsTable, GridClassesShowTheirCountsUnderHeadsWithUnits) {
  json report;
  report["rays"] = {{"camera", grid_class(6.5, 7.25)}};
  report["cost"] = nullptr;
  const auto lines = lines_of(stats_table(report));
  ASSERT_EQ(lines.size(), 2u);
  for (const char* head : {"rays", "cells/ray", "predicted cells/ray", "tests/ray", "refs/ray", "p_tot (cells)", "kappa eq 25"})
    EXPECT_NE(lines[0].find(head), std::string::npos) << head;
  EXPECT_EQ(lines[1].rfind("camera", 0), 0u);
  for (const char* value : {" 1000", " 6.50", " 7.25", " 3.25", " 7.50", " 0.875", " 0.938", " -"})
    EXPECT_NE(lines[1].find(value), std::string::npos) << value << " in " << lines[1];
}

TEST(StatsTable, UniformLinesArePredictedByEq22) {
  json c = grid_class(10, 11);
  c["p_tot_predicted"] = 9.75;
  json report;
  report["rays"] = {{"lines", c}};
  const auto lines = lines_of(stats_table(report));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[1].find(" 9.75"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[1].find("11.00"), std::string::npos) << lines[1];
}

TEST(StatsTable, OtherAcceleratorsShowRaysHitsAndTime) {
  json report;
  report["rays"] = {{"camera", {{"count", 64}, {"hit_fraction", 0.5}, {"time_s", 0.25}}},
                    {"shadow", {{"count", 0}, {"hit_fraction", nullptr}, {"time_s", 0.0}}}};
  const auto lines = lines_of(stats_table(report));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[0].find("hit fraction"), std::string::npos);
  EXPECT_NE(lines[0].find("time (s)"), std::string::npos);
  EXPECT_EQ(lines[0].find("cells/ray"), std::string::npos);
  EXPECT_NE(lines[1].find("0.500"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(" -"), std::string::npos) << lines[2];
}

TEST(StatsTable, CostLineComesFirstWhenTheReportHasAPrediction) {
  json report;
  report["rays"] = {{"camera", grid_class(6, 6)}};
  report["cost"] = {{"measured_s", 2.0},
                    {"eq10",
                     {{"T0_ns", 10.0}, {"Ts_ns", 3.0}, {"Th_ns", 5.0}, {"predicted_s", 1.5}, {"relative_error", -0.25}}},
                    {"extended", {{"predicted_s", 2.1}, {"relative_error", 0.05}}}};
  auto lines = lines_of(stats_table(report));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("cost (thread-seconds of traversal): measured 2.000 s; eq 10 1.500 s (error -0.250", 0), 0u)
      << lines[0];
  EXPECT_NE(lines[0].find("extended 2.100 s (error +0.050)"), std::string::npos) << lines[0];
  // Measured without a calibration: no prediction, no line.
  report["cost"]["eq10"] = nullptr;
  report["cost"]["extended"] = nullptr;
  lines = lines_of(stats_table(report));
  EXPECT_EQ(lines.size(), 2u);
}

TEST(StatsTable, GridLineGivesOccupancyBesideEqs19And21) {
  const json grid = {{"res", {4, 5, 6}}, {"N_c", 120},         {"N", 32},
                     {"theta_tot", 97}, {"theta_tot_eq19", 101.4}, {"theta_tot_eq21", nullptr},
                     {"empty_fraction", 0.25}};
  EXPECT_EQ(grid_occupancy_line(grid), "grid 4 x 5 x 6: N_c 120, N 32, theta_tot 97 (eq19 101, eq21 -), empty 0.250\n");
}

TEST(StatsTable, NothingWithoutRays) {
  EXPECT_EQ(stats_table(json::object()), "");
  EXPECT_EQ(stats_table(json{{"rays", json::object()}}), "");
}

}  // namespace
}  // namespace kappa
