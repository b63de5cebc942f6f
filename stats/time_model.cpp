#include "time_model.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kappa {
namespace {

/// log2 of the working set over the cache, 0 while it fits.
double memory_level(double working_set_bytes, double cache_bytes) {
  return cache_bytes > 0 && working_set_bytes > cache_bytes ? std::log2(working_set_bytes / cache_bytes) : 0.0;
}

/// Solves the normal equations restricted to the unknowns in `free` (the
/// others held at 0) by Gauss-Jordan elimination with partial pivoting.
/// False when a pivot is tiny against the diagonal: the measurements do not
/// separate those unknowns.
bool solve_subset(const std::vector<std::vector<double>>& normal, const std::vector<double>& rhs,
                  const std::vector<int>& free, std::vector<double>& x) {
  const std::size_t n = free.size();
  std::vector<std::vector<double>> m(n, std::vector<double>(n + 1));
  double scale = 0;
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t c = 0; c < n; ++c) m[r][c] = normal[free[r]][free[c]];
    m[r][n] = rhs[free[r]];
    scale = std::max(scale, std::abs(m[r][r]));
  }
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    std::swap(m[c], m[pivot]);
    if (!(std::abs(m[c][c]) > 1e-12 * scale)) return false;
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (std::size_t k = c; k <= n; ++k) m[r][k] -= f * m[c][k];
    }
  }
  std::fill(x.begin(), x.end(), 0.0);
  for (std::size_t r = 0; r < n; ++r) x[free[r]] = m[r][n] / m[r][r];
  return true;
}

}  // namespace

double l2_cache_bytes() {
  const long l2 = ::sysconf(_SC_LEVEL2_CACHE_SIZE);
  return l2 > 0 ? double(l2) : double(1 << 20);
}

TimeModel eq10_model() {
  TimeModel m;
  m.name = "eq10";
  m.terms = {"T0", "Ts", "Th"};
  m.ns.assign(m.terms.size(), 0.0);
  return m;
}

TimeModel extended_model(double cache_bytes) {
  TimeModel m;
  m.name = "extended";
  m.terms = {"T0_camera", "T0_closest", "T0_any", "Ts_empty", "Ts_occupied", "Ts_memory",
             "Th",        "Th_memory",  "T_skip", "T_hit"};
  m.ns.assign(m.terms.size(), 0.0);
  m.cache_bytes = cache_bytes;
  return m;
}

std::vector<double> TimeModel::features_per_ray(const QueryLoad& load) const {
  const double r = load.rays > 0 ? load.rays : 1.0;
  const double cells = load.cells / r, occupied = load.occupied / r, tests = load.tests / r;
  if (name == "eq10") return {1.0, cells, tests};
  const double level = memory_level(load.working_set_bytes, cache_bytes);
  return {load.kind == QueryKind::camera ? 1.0 : 0.0,
          load.kind == QueryKind::closest ? 1.0 : 0.0,
          load.kind == QueryKind::any ? 1.0 : 0.0,
          cells - occupied,
          occupied,
          occupied * level,
          tests,
          tests * level,
          load.skips / r,
          load.hits / r};
}

double TimeModel::seconds(const QueryLoad& load) const {
  if (!(load.rays > 0)) return 0.0;
  const std::vector<double> f = features_per_ray(load);
  double ns_per_ray = 0;
  for (std::size_t i = 0; i < f.size(); ++i) ns_per_ray += ns[i] * f[i];
  return ns_per_ray * 1e-9 * load.rays;
}

void fit(TimeModel& model, std::span<const TimedLoad> measurements) {
  if (measurements.size() < 3) throw std::runtime_error("calibration: at least 3 measurements are needed");
  const std::size_t n = model.terms.size();
  // Normal equations of the relative error: rows f/t (per ray), target 1.
  std::vector<std::vector<double>> normal(n, std::vector<double>(n, 0.0));
  std::vector<double> rhs(n, 0.0);
  std::vector<std::vector<double>> rows;
  for (const TimedLoad& m : measurements) {
    const double t_ns = m.seconds / m.load.rays * 1e9;
    if (!(t_ns > 0) || !std::isfinite(t_ns))
      throw std::runtime_error("calibration: measurement '" + m.label + "' is not a positive finite time");
    std::vector<double> row = model.features_per_ray(m.load);
    for (double& v : row) {
      if (!std::isfinite(v)) throw std::runtime_error("calibration: measurement '" + m.label + "' has a non-finite count");
      v /= t_ns;
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) normal[i][j] += row[i] * row[j];
      rhs[i] += row[i];
    }
    rows.push_back(std::move(row));
  }
  const auto residual = [&](const std::vector<double>& x) {
    double sum = 0;
    for (const auto& row : rows) {
      double e = -1.0;
      for (std::size_t i = 0; i < n; ++i) e += row[i] * x[i];
      sum += e * e;
    }
    return sum;
  };
  // Every constant must be determined by the measurements (a term no ray set
  // varies apart from the others would take an arbitrary share).
  std::vector<int> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = int(i);
  std::vector<double> x(n, 0.0);
  if (!solve_subset(normal, rhs, all, x))
    throw std::runtime_error("calibration: the measurements do not determine the " + model.name + " model's constants");
  // Non-negative least squares by trying every subset of free constants:
  // the optimum is the unconstrained fit on its own support, so the best
  // feasible subset is it. 2^n solves of at most n x n: nothing for n <= 12.
  double best = INFINITY;
  std::vector<double> best_x(n, 0.0);
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> free;
    for (std::size_t i = 0; i < n; ++i)
      if (mask & (1u << i)) free.push_back(int(i));
    if (!solve_subset(normal, rhs, free, x)) continue;
    if (std::any_of(x.begin(), x.end(), [](double v) { return v < 0 || !std::isfinite(v); })) continue;
    if (const double r = residual(x); r < best) best = r, best_x = x;
  }
  if (!std::isfinite(best)) throw std::runtime_error("calibration: no fit of " + model.name + " with non-negative constants");
  model.ns = best_x;
  model.rms_relative_error = std::sqrt(best / double(rows.size()));
}

nlohmann::ordered_json to_json(const TimeModel& model) {
  nlohmann::ordered_json constants;
  for (std::size_t i = 0; i < model.terms.size(); ++i) constants[model.terms[i] + "_ns"] = model.ns[i];
  nlohmann::ordered_json j = {{"constants", constants}, {"rms_relative_error", model.rms_relative_error}};
  if (model.name == "extended") j["cache_bytes"] = model.cache_bytes;
  return j;
}

bool from_json(const nlohmann::json& j, TimeModel& model) {
  if (!j.is_object() || !j.contains("constants") || !j["constants"].is_object()) return false;
  for (std::size_t i = 0; i < model.terms.size(); ++i) {
    const auto it = j["constants"].find(model.terms[i] + "_ns");
    if (it == j["constants"].end() || !it->is_number()) return false;
    model.ns[i] = it->get<double>();
    if (!std::isfinite(model.ns[i]) || model.ns[i] < 0) return false;
  }
  model.rms_relative_error = j.value("rms_relative_error", 0.0);
  if (model.name == "extended") {
    if (!j.contains("cache_bytes") || !j["cache_bytes"].is_number()) return false;
    model.cache_bytes = j["cache_bytes"].get<double>();
    if (!(model.cache_bytes > 0) || !std::isfinite(model.cache_bytes)) return false;
  }
  return true;
}

}  // namespace kappa
