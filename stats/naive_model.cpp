#include "naive_model.h"

#include <stdexcept>

#include "time_model.h"

namespace kappa {

std::vector<double> NaiveModel::features_per_ray(const NaiveLoad& load) {
  const double occluded = load.ray_class == kShadow && load.rays > 0 ? load.hits / load.rays : 0.0;
  return {1.0, load.triangles * (1 - occluded), load.triangles * occluded};
}

double NaiveModel::seconds(const NaiveLoad& load) const {
  const std::vector<double> f = features_per_ray(load);
  double ns_per_ray = 0;
  for (std::size_t i = 0; i < f.size(); ++i) ns_per_ray += ns[i] * f[i];
  return ns_per_ray * load.rays * 1e-9;
}

void fit(NaiveModel& model, std::span<const TimedNaiveLoad> measurements) {
  if (measurements.size() < 3) throw std::runtime_error("calibration: at least 3 naive measurements are needed");
  std::vector<std::vector<double>> features;
  std::vector<double> ns_per_ray;
  std::vector<std::string> labels;
  for (const TimedNaiveLoad& m : measurements) {
    features.push_back(NaiveModel::features_per_ray(m.load));
    ns_per_ray.push_back(m.seconds / m.load.rays * 1e9);
    labels.push_back(m.label);
  }
  model.ns = fit_relative(features, ns_per_ray, labels, "naive model's", model.rms_relative_error);
}

nlohmann::ordered_json to_json(const NaiveModel& model) {
  return {{"constants", constants_json(model.terms, model.ns)}, {"rms_relative_error", model.rms_relative_error}};
}

bool from_json(const nlohmann::json& j, NaiveModel& model) {
  if (!constants_from_json(j, model.terms, model.ns)) return false;
  model.rms_relative_error = j.value("rms_relative_error", 0.0);
  return true;
}

}  // namespace kappa
