#include "calibration.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace kappa {

Calibration fit_calibration(std::span<const CostSample> samples) {
  if (samples.size() < 3) throw std::invalid_argument("calibration: at least 3 measurements are needed");
  for (const CostSample& s : samples)
    if (!(s.seconds_per_ray > 0) || !std::isfinite(s.seconds_per_ray) || !std::isfinite(s.cells_per_ray) ||
        !std::isfinite(s.refs_per_ray))
      throw std::invalid_argument("calibration: measurement '" + s.label + "' is not a positive finite time");
  // Normal equations A^T W A x = A^T W b with rows (1, cells, refs), weights 1/b^2.
  double m[3][4] = {};
  for (const CostSample& s : samples) {
    const double row[3] = {1.0, s.cells_per_ray, s.refs_per_ray};
    const double w = 1.0 / (s.seconds_per_ray * s.seconds_per_ray);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) m[i][j] += w * row[i] * row[j];
      m[i][3] += w * row[i] * s.seconds_per_ray;
    }
  }
  // Gauss-Jordan elimination with partial pivoting; a pivot tiny relative to
  // the matrix means the measurements do not separate the three constants.
  double scale = 0;
  for (int i = 0; i < 3; ++i) scale = std::max(scale, std::abs(m[i][i]));
  for (int c = 0; c < 3; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
    if (!(std::abs(m[c][c]) > 1e-12 * scale))
      throw std::invalid_argument("calibration: the measurements do not determine T0, Ts, Th");
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
    }
  }
  Calibration cal;
  cal.T0_ns = m[0][3] / m[0][0] * 1e9;
  cal.Ts_ns = m[1][3] / m[1][1] * 1e9;
  cal.Th_ns = m[2][3] / m[2][2] * 1e9;
  if (!std::isfinite(cal.T0_ns) || !std::isfinite(cal.Ts_ns) || !std::isfinite(cal.Th_ns))
    throw std::invalid_argument("calibration: the fit is not finite");
  cal.samples = samples.size();
  double sum = 0;
  for (const CostSample& s : samples) {
    const double e = cal.seconds_per_ray(s.cells_per_ray, s.refs_per_ray) / s.seconds_per_ray - 1.0;
    sum += e * e;
  }
  cal.rms_relative_error = std::sqrt(sum / double(samples.size()));
  return cal;
}

nlohmann::ordered_json to_json(const Calibration& c, std::span<const CostSample> samples) {
  nlohmann::ordered_json j;
  j["T0_ns"] = c.T0_ns;
  j["Ts_ns"] = c.Ts_ns;
  j["Th_ns"] = c.Th_ns;
  j["samples"] = c.samples;
  j["rms_relative_error"] = c.rms_relative_error;
  j["machine"] = c.machine;
  if (!samples.empty()) {
    j["measurements"] = nlohmann::ordered_json::array();
    for (const CostSample& s : samples)
      j["measurements"].push_back({{"label", s.label},
                                   {"ns_per_ray", s.seconds_per_ray * 1e9},
                                   {"cells_per_ray", s.cells_per_ray},
                                   {"refs_per_ray", s.refs_per_ray}});
  }
  return j;
}

std::optional<Calibration> load_calibration(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  std::ifstream in(file);
  try {
    const auto j = nlohmann::json::parse(in);
    Calibration c;
    c.T0_ns = j.at("T0_ns").get<double>();
    c.Ts_ns = j.at("Ts_ns").get<double>();
    c.Th_ns = j.at("Th_ns").get<double>();
    c.samples = j.value("samples", std::size_t(0));
    c.rms_relative_error = j.value("rms_relative_error", 0.0);
    c.machine = j.value("machine", std::string());
    if (!std::isfinite(c.T0_ns) || !std::isfinite(c.Ts_ns) || !std::isfinite(c.Th_ns)) throw std::invalid_argument("");
    return c;
  } catch (const std::exception&) {
    throw std::invalid_argument(file.string() + ": not a Kappa calibration (expected T0_ns, Ts_ns, Th_ns numbers)");
  }
}

}  // namespace kappa
