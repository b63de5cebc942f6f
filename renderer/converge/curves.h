// Error-against-time curves (kappa converge) and their ranking at equal time:
// each setting's relMSE read off its curve at the longest time every curve
// reaches, interpolated log-log between the measured points.
#pragma once

#include <string>
#include <vector>

#include "renderer/converge/image_error.h"

namespace kappa {

struct ConvergePoint {
  int spp = 0;
  double time_s = 0;  ///< render time to this many samples per pixel
  ImageError error;
  /// 1 / (relMSE x time): how much accuracy a second buys.
  double efficiency() const { return error.relmse > 0 && time_s > 0 ? 1.0 / (error.relmse * time_s) : 0.0; }
};

struct ConvergeCurve {
  std::string name;   ///< "sampler=sobol", or "defaults"
  std::string key;    ///< the option varied ("" for the defaults)
  std::string value;
  std::string path_variant;  ///< the integrator that ran
  std::vector<ConvergePoint> points;  ///< ascending spp (and time, unless each was its own render)
};

/// The relMSE of `points` at time t: log-log interpolation between the points,
/// taken in order of time,
/// around t; before the first, the first point's relMSE scaled by its time / t
/// (relMSE falling as 1/time) and `extrapolated` set; past the last, the
/// last's the same way.
double relmse_at_time(const std::vector<ConvergePoint>& points, double t, bool* extrapolated = nullptr);

/// The longest time every curve reaches: the shortest of their longest times.
double equal_time(const std::vector<ConvergeCurve>& curves);

}  // namespace kappa
