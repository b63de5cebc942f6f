#include "renderer/cli/sweep_range.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/error.h"

namespace kappa {
namespace {

bool parse_positive(std::string_view text, double& v) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(v) && v > 0;
}

}  // namespace

SweepRange parse_sweep_range(const std::string& text, const std::string& flag) {
  const std::size_t colon = text.find(':');
  SweepRange r;
  if (colon == std::string::npos || !parse_positive(std::string_view(text).substr(0, colon), r.from) ||
      !parse_positive(std::string_view(text).substr(colon + 1), r.to) || r.from > r.to)
    throw InputError(flag + ": '" + text + "' is not a range A:B of numbers with 0 < A <= B");
  return r;
}

std::vector<GridResolution> sweep_resolutions(const Vec3d& extent, double from_cells, double to_cells, int steps) {
  std::vector<GridResolution> out;
  for (int k = 0; k < steps; ++k) {
    const double f = steps > 1 ? double(k) / double(steps - 1) : 0.0;
    const double target = from_cells * std::pow(to_cells / from_cells, f);
    const GridResolution r = choose_resolution(extent, std::max(1.0, target));
    if (std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  }
  return out;
}

}  // namespace kappa
