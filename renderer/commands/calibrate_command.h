// `kappa calibrate`: measures T0, Ts, Th (eq 10) on this machine.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace kappa {

struct CalibrateOptions {
  std::vector<std::string> scenes;  ///< default: the Cornell box and the low-resolution bunny in assets/
  std::vector<double> densities = {2, 8, 32, 128, 512};
  std::size_t n = 100000;  ///< rays per class and grid
  int repeat = 3;
  int threads = 0;  ///< threads walking at once (0 = all cores, as a render runs)
  std::string out;  ///< default: default_calibration_path()
};

/// kappa_calibration.json beside the kappa executable (build/ for a build tree).
std::filesystem::path default_calibration_path();

int run_calibrate(const CalibrateOptions& options);

}  // namespace kappa
