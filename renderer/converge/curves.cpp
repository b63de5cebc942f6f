#include "renderer/converge/curves.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kappa {

double relmse_at_time(const std::vector<ConvergePoint>& unsorted, double t, bool* extrapolated) {
  if (extrapolated) *extrapolated = false;
  // A sampler that needs the total renders each sample count on its own, so
  // on a busy machine a larger count can take less time than a smaller one.
  std::vector<ConvergePoint> points = unsorted;
  std::stable_sort(points.begin(), points.end(),
                   [](const ConvergePoint& a, const ConvergePoint& b) { return a.time_s < b.time_s; });
  if (points.empty() || !(t > 0)) return std::numeric_limits<double>::quiet_NaN();
  const auto scaled = [&](const ConvergePoint& p) {
    if (extrapolated) *extrapolated = true;
    return p.time_s > 0 ? p.error.relmse * p.time_s / t : p.error.relmse;
  };
  if (t < points.front().time_s) return scaled(points.front());
  for (std::size_t i = 1; i < points.size(); ++i) {
    const ConvergePoint &a = points[i - 1], &b = points[i];
    if (t > b.time_s) continue;
    if (!(a.time_s > 0) || !(b.time_s > a.time_s) || !(a.error.relmse > 0) || !(b.error.relmse > 0))
      return b.error.relmse;
    const double w = std::log(t / a.time_s) / std::log(b.time_s / a.time_s);
    return std::exp((1 - w) * std::log(a.error.relmse) + w * std::log(b.error.relmse));
  }
  if (t == points.back().time_s) return points.back().error.relmse;
  return scaled(points.back());
}

double equal_time(const std::vector<ConvergeCurve>& curves) {
  double t = std::numeric_limits<double>::infinity();
  for (const ConvergeCurve& c : curves)
    if (!c.points.empty())
      t = std::min(t, std::max_element(c.points.begin(), c.points.end(), [](const auto& a, const auto& b) {
                        return a.time_s < b.time_s;
                      })->time_s);
  return std::isfinite(t) ? t : 0.0;
}

}  // namespace kappa
