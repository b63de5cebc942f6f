// `kappa bench`: Mrays/s per accelerator x ray class x thread count, on the
// same rays, in one run, with statistics off.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kappa {

struct BenchOptions {
  std::string scene;
  std::vector<std::string> accels = {"naive", "grid", "embree"};
  std::vector<std::string> rays = {"camera", "bounce", "shadow", "lines"};
  std::vector<int> threads = {1, 2};
  int repeat = 5;
  std::size_t n = std::size_t(1) << 20;  ///< rays per class
  std::uint64_t seed = 0;
  std::string json;        ///< write the figures here too
  std::string grid_res = "auto";
  double grid_density = 0;
  double naive_budget_s = 60;  ///< skip naive when its estimated time exceeds this
};

/// Throws InputError / std::invalid_argument for bad input; returns the exit code.
int run_bench(const BenchOptions& options);

}  // namespace kappa
