// `kappa cast`: one of the paper's ray distributions (or the renderer's own)
// cast through the accelerator with statistics on, and its report.
#pragma once

#include <cstdint>
#include <string>

namespace kappa {

struct CastOptions {
  std::string scene;
  std::string rays = "lines";  ///< lines | segments | camera | bounce | shadow
  std::size_t n = 1000000;
  std::string accel = "grid";
  std::string grid_res = "auto";
  double grid_density = 0;
  std::uint64_t grid_max_bytes = 0;  ///< grid plus per-cell counters (0 = a quarter of RAM)
  std::uint64_t seed = 0;
  double length = 0;  ///< segment length; 0 = two mean cell widths
  int threads = 0;
  std::string report;  ///< JSON report path
  bool quiet = false;
};

int run_cast(const CastOptions& options);

}  // namespace kappa
