#include "time_model.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kappa {
namespace {

/// The share of the working set beyond the cache: 0 while it fits.
double beyond_cache(double working_set_bytes, double cache_bytes) {
  return cache_bytes > 0 && working_set_bytes > cache_bytes ? 1.0 - cache_bytes / working_set_bytes : 0.0;
}

/// Least squares of A x = b over the columns in `passive` (the others 0), by
/// the normal equations with partial pivoting; false if they are singular.
/// The columns are scaled to unit length first (a per-ray term and a per-cell
/// term differ by 1e4 on the diagonal), so that "singular" means columns that
/// really are dependent, not ones of different units.
bool solve_passive(const std::vector<std::vector<double>>& ata, const std::vector<double>& atb,
                   const std::vector<int>& passive, std::vector<double>& x) {
  const std::size_t n = passive.size();
  std::vector<double> unit(n);
  for (std::size_t r = 0; r < n; ++r) {
    const double d = ata[passive[r]][passive[r]];
    if (!(d > 0)) return false;  // a column of zeros
    unit[r] = 1.0 / std::sqrt(d);
  }
  std::vector<std::vector<double>> m(n, std::vector<double>(n + 1));
  const double scale = 1.0;  // the scaled diagonal
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t c = 0; c < n; ++c) m[r][c] = ata[passive[r]][passive[c]] * unit[r] * unit[c];
    m[r][n] = atb[passive[r]] * unit[r];
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
  for (std::size_t r = 0; r < n; ++r) x[passive[r]] = m[r][n] / m[r][r] * unit[r];
  return true;
}

/// Non-negative least squares (Lawson and Hanson 1974, ch. 23) on the normal
/// equations: the active-set method, which ends at the optimum.
std::vector<double> nnls(const std::vector<std::vector<double>>& ata, const std::vector<double>& atb) {
  const std::size_t n = atb.size();
  std::vector<double> x(n, 0.0), z(n, 0.0);
  std::vector<bool> in_passive(n, false), dependent(n, false);
  const auto gradient = [&](std::size_t i) {  // A^T (b - A x), component i
    double g = atb[i];
    for (std::size_t j = 0; j < n; ++j) g -= ata[i][j] * x[j];
    return g;
  };
  double scale = 0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(atb[i]));
  for (int outer = 0; outer < 3 * int(n) + 10; ++outer) {
    std::size_t best = n;
    double best_g = 1e-12 * scale;
    for (std::size_t i = 0; i < n; ++i)
      if (!in_passive[i] && !dependent[i] && gradient(i) > best_g) best = i, best_g = gradient(i);
    if (best == n) break;  // Kuhn-Tucker conditions hold
    in_passive[best] = true;
    for (int inner = 0; inner < 3 * int(n) + 10; ++inner) {
      std::vector<int> passive;
      for (std::size_t i = 0; i < n; ++i)
        if (in_passive[i]) passive.push_back(int(i));
      if (!solve_passive(ata, atb, passive, z)) {  // a column dependent on the others: leave it out for good
        in_passive[best] = false;
        dependent[best] = true;
        break;
      }
      bool feasible = true;
      for (int i : passive) feasible = feasible && z[i] > 0;
      if (feasible) {
        x = z;
        break;
      }
      // Step from x towards z as far as stays feasible, and drop what hits 0.
      double alpha = 1;
      int limiting = -1;
      for (int i : passive)
        if (z[i] <= 0 && x[i] / (x[i] - z[i]) < alpha) alpha = x[i] / (x[i] - z[i]), limiting = i;
      for (std::size_t i = 0; i < n; ++i) x[i] += alpha * (z[i] - x[i]);
      if (limiting >= 0) x[limiting] = 0;  // exactly: rounding must not keep it passive
      for (int i : passive)
        if (x[i] <= 0) in_passive[i] = false, x[i] = 0;
    }
  }
  return x;
}

}  // namespace

double l2_cache_bytes() {
  const long l2 = ::sysconf(_SC_LEVEL2_CACHE_SIZE);
  return l2 > 0 ? double(l2) : double(1 << 20);
}

TimeModel eq10_model() {
  TimeModel m;
  m.form = ModelForm::eq10;
  m.name = "eq10";
  m.terms = {"T0", "Ts", "Th"};
  m.ns.assign(m.terms.size(), 0.0);
  return m;
}

TimeModel extended_model(double cache_bytes, bool nested) {
  TimeModel m;
  m.form = ModelForm::extended;
  m.name = "extended";
  for (const char* c : kRenderClassNames) m.terms.push_back(std::string("T0_") + c);
  for (const char* t : {"Ts", "Ts_occupied", "Th", "T_hit"}) m.terms.push_back(t);
  for (const char* c : kRenderClassNames) m.terms.push_back(std::string("Ts_miss_") + c);
  for (const char* c : kRenderClassNames) m.terms.push_back(std::string("Th_miss_") + c);
  m.nested = nested;
  if (nested) m.terms.push_back("T_descend");
  m.ns.assign(m.terms.size(), 0.0);
  m.cache_bytes = cache_bytes;
  return m;
}

TimeModel coherent_model(double cache_bytes, bool nested) {
  TimeModel m = extended_model(cache_bytes);
  m.form = ModelForm::coherent;
  m.name = "coherent";
  m.terms.push_back("Ts_cold");
  m.nested = nested;
  if (nested) m.terms.push_back("T_descend");
  m.ns.assign(m.terms.size(), 0.0);
  return m;
}

std::vector<double> TimeModel::features_per_ray(const QueryLoad& load) const {
  const double r = load.rays > 0 ? load.rays : 1.0;
  const double cells = load.cells / r, occupied = load.occupied / r, tests = load.tests / r;
  if (form == ModelForm::eq10) return {1.0, cells, tests};
  // A step reads the cell records, a test the references and triangles.
  const double step_miss = beyond_cache(load.working_set_bytes - load.list_bytes, cache_bytes);
  const double test_miss = beyond_cache(load.list_bytes, cache_bytes);
  std::vector<double> f(terms.size(), 0.0);
  const std::size_t k = load.ray_class;
  f[k] = 1.0;
  f[kRenderClasses + 0] = cells;
  f[kRenderClasses + 1] = occupied;
  f[kRenderClasses + 2] = tests;
  f[kRenderClasses + 3] = load.hits / r;
  f[kRenderClasses + 4 + k] = cells * step_miss;
  f[2 * kRenderClasses + 4 + k] = tests * test_miss;
  if (form == ModelForm::coherent) f[3 * kRenderClasses + 4] = load.cold_cells / r;
  if (nested) f.back() = load.descents / r;
  return f;
}

double TimeModel::seconds(const QueryLoad& load) const {
  if (!(load.rays > 0)) return 0.0;
  const std::vector<double> f = features_per_ray(load);
  double ns_per_ray = 0;
  for (std::size_t i = 0; i < f.size(); ++i) ns_per_ray += ns[i] * f[i];
  return ns_per_ray * 1e-9 * load.rays;
}

std::vector<double> fit_relative(const std::vector<std::vector<double>>& features, const std::vector<double>& values,
                                 const std::vector<std::string>& labels, const std::string& what, double& rms) {
  if (features.size() < 3) throw std::runtime_error("calibration: at least 3 measurements are needed");
  const std::size_t n = features.front().size();
  // Normal equations of the relative error: rows f/t, target 1.
  std::vector<std::vector<double>> normal(n, std::vector<double>(n, 0.0));
  std::vector<double> rhs(n, 0.0);
  std::vector<std::vector<double>> rows;
  for (std::size_t m = 0; m < features.size(); ++m) {
    const double t = values[m];
    if (!(t > 0) || !std::isfinite(t))
      throw std::runtime_error("calibration: measurement '" + labels[m] + "' is not a positive finite time");
    std::vector<double> row = features[m];
    for (double& v : row) {
      if (!std::isfinite(v)) throw std::runtime_error("calibration: measurement '" + labels[m] + "' has a non-finite count");
      v /= t;
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
  // Every constant must be determined by the measurements (a term no
  // measurement varies apart from the others would take an arbitrary share).
  std::vector<int> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = int(i);
  std::vector<double> x(n, 0.0);
  if (!solve_passive(normal, rhs, all, x))
    throw std::runtime_error("calibration: the measurements do not determine the " + what + " constants");
  const std::vector<double> best_x = nnls(normal, rhs);
  rms = std::sqrt(residual(best_x) / double(rows.size()));
  return best_x;
}

void fit(TimeModel& model, std::span<const TimedLoad> measurements) {
  std::vector<std::vector<double>> features;
  std::vector<double> ns_per_ray;
  std::vector<std::string> labels;
  for (const TimedLoad& m : measurements) {
    features.push_back(model.features_per_ray(m.load));
    ns_per_ray.push_back(m.seconds / m.load.rays * 1e9);
    labels.push_back(m.label);
  }
  if (measurements.size() < 3) throw std::runtime_error("calibration: at least 3 measurements are needed");
  model.ns = fit_relative(features, ns_per_ray, labels, model.name + " model's", model.rms_relative_error);
}

nlohmann::ordered_json constants_json(const std::vector<std::string>& terms, const std::vector<double>& ns) {
  nlohmann::ordered_json constants;
  for (std::size_t i = 0; i < terms.size(); ++i) constants[terms[i] + "_ns"] = ns[i];
  return constants;
}

bool constants_from_json(const nlohmann::json& j, const std::vector<std::string>& terms, std::vector<double>& ns) {
  if (!j.is_object() || !j.contains("constants") || !j["constants"].is_object()) return false;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const auto it = j["constants"].find(terms[i] + "_ns");
    if (it == j["constants"].end() || !it->is_number()) return false;
    ns[i] = it->get<double>();
    if (!std::isfinite(ns[i]) || ns[i] < 0) return false;
  }
  return true;
}

nlohmann::ordered_json to_json(const TimeModel& model) {
  nlohmann::ordered_json j = {{"constants", constants_json(model.terms, model.ns)},
                              {"rms_relative_error", model.rms_relative_error}};
  if (model.form != ModelForm::eq10) j["cache_bytes"] = model.cache_bytes;
  return j;
}

bool from_json(const nlohmann::json& j, TimeModel& model) {
  if (!constants_from_json(j, model.terms, model.ns)) return false;
  model.rms_relative_error = j.value("rms_relative_error", 0.0);
  if (model.form != ModelForm::eq10) {
    if (!j.contains("cache_bytes") || !j["cache_bytes"].is_number()) return false;
    model.cache_bytes = j["cache_bytes"].get<double>();
    if (!(model.cache_bytes > 0) || !std::isfinite(model.cache_bytes)) return false;
  }
  return true;
}

}  // namespace kappa
