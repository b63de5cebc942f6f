#include "calibration.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "accel/input_error.h"
#include "accel/input_file.h"

namespace kappa {
namespace {

/// Solves the normal equations restricted to the unknowns whose bits are set
/// in `free` (the others held at 0), by Gauss-Jordan elimination with
/// partial pivoting. False when a pivot is tiny relative to the matrix: the
/// measurements do not separate those unknowns.
bool solve_normal_equations(const double normal[3][4], unsigned free, double x[3]) {
  int index[3], n = 0;
  for (int i = 0; i < 3; ++i)
    if (free & (1u << (2 - i))) index[n++] = i;  // bit 2 = T0, 1 = Ts, 0 = Th
  double m[3][4] = {};
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) m[r][c] = normal[index[r]][index[c]];
    m[r][3] = normal[index[r]][3];
  }
  double scale = 0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(m[i][i]));
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
    if (!(std::abs(m[c][c]) > 1e-12 * scale)) return false;
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
    }
  }
  for (int i = 0; i < 3; ++i) x[i] = 0;
  for (int r = 0; r < n; ++r) x[index[r]] = m[r][3] / m[r][r];
  return true;
}

}  // namespace

Calibration fit_calibration(std::span<const CostSample> samples) {
  if (samples.size() < 3) throw std::runtime_error("calibration: at least 3 measurements are needed");
  for (const CostSample& s : samples)
    if (!(s.seconds_per_ray > 0) || !std::isfinite(s.seconds_per_ray) || !std::isfinite(s.cells_per_ray) ||
        !std::isfinite(s.refs_per_ray))
      throw std::runtime_error("calibration: measurement '" + s.label + "' is not a positive finite time");
  // Normal equations A^T W A x = A^T W b with rows (1, cells, refs), weights 1/b^2.
  double normal[3][4] = {};
  for (const CostSample& s : samples) {
    const double row[3] = {1.0, s.cells_per_ray, s.refs_per_ray};
    const double w = 1.0 / (s.seconds_per_ray * s.seconds_per_ray);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) normal[i][j] += w * row[i] * row[j];
      normal[i][3] += w * row[i] * s.seconds_per_ray;
    }
  }
  const auto weighted_residual = [&](const double x[3]) {
    double sum = 0;
    for (const CostSample& s : samples) {
      const double e = (x[0] + x[1] * s.cells_per_ray + x[2] * s.refs_per_ray) / s.seconds_per_ray - 1.0;
      sum += e * e;
    }
    return sum;
  };
  double x[3] = {};
  if (!solve_normal_equations(normal, 0b111, x))
    throw std::runtime_error("calibration: the measurements do not determine T0, Ts, Th");
  // A time cannot be negative: if the free fit makes a constant negative,
  // take the best fit with some constants held at 0 (the non-negative least
  // squares solution, found by trying every subset of the three).
  if (x[0] < 0 || x[1] < 0 || x[2] < 0) {
    double best = INFINITY;
    double best_x[3] = {};
    for (unsigned free = 0b110; free > 0; --free) {
      double y[3] = {};
      if (!solve_normal_equations(normal, free, y) || y[0] < 0 || y[1] < 0 || y[2] < 0) continue;
      if (const double r = weighted_residual(y); r < best) best = r, std::copy(y, y + 3, best_x);
    }
    if (!std::isfinite(best)) throw std::runtime_error("calibration: no fit with non-negative T0, Ts, Th");
    std::copy(best_x, best_x + 3, x);
  }
  Calibration cal;
  cal.T0_ns = x[0] * 1e9;
  cal.Ts_ns = x[1] * 1e9;
  cal.Th_ns = x[2] * 1e9;
  if (!std::isfinite(cal.T0_ns) || !std::isfinite(cal.Ts_ns) || !std::isfinite(cal.Th_ns))
    throw std::runtime_error("calibration: the fit is not finite");
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

std::filesystem::path default_calibration_path() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return (ec ? std::filesystem::path(".") : exe.parent_path()) / "kappa_calibration.json";
}

std::optional<Calibration> load_calibration(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  check_input_file(file, "a calibration file");  // never blocks on a FIFO
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
    if (std::isfinite(c.T0_ns) && std::isfinite(c.Ts_ns) && std::isfinite(c.Th_ns)) return c;
  } catch (const nlohmann::json::exception&) {
    // malformed JSON or a missing or mistyped key: refused below
  }
  throw InputError(file.string() + ": not a Kappa calibration (expected T0_ns, Ts_ns, Th_ns numbers)");
}

}  // namespace kappa
