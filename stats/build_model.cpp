#include "build_model.h"

#include <algorithm>
#include <cmath>

#include "time_model.h"

namespace kappa {

double BuildModel::seconds(double N, double theta_tot, double cells, int run_threads) const {
  const double ns_total = ns[0] * N + ns[1] * theta_tot + ns[2] * cells;
  return ns_total * 1e-9 * double(std::max(1, threads)) / double(std::max(1, run_threads));
}

void fit(BuildModel& model, std::span<const TimedBuild> builds, int threads) {
  std::vector<std::vector<double>> features;
  std::vector<double> ns;
  std::vector<std::string> labels;
  for (const TimedBuild& b : builds) {
    features.push_back({b.N, b.theta_tot, b.cells});
    ns.push_back(b.seconds * 1e9);
    labels.push_back(b.label);
  }
  if (builds.size() < 3) throw std::runtime_error("calibration: at least 3 grid builds are needed");
  model.ns = fit_relative(features, ns, labels, "grid build model's", model.rms_relative_error);
  model.threads = threads;
}

nlohmann::ordered_json to_json(const BuildModel& model) {
  return {{"constants", constants_json(model.terms, model.ns)},
          {"threads", model.threads},
          {"rms_relative_error", model.rms_relative_error}};
}

bool from_json(const nlohmann::json& j, BuildModel& model) {
  if (!constants_from_json(j, model.terms, model.ns)) return false;
  const auto threads = j.find("threads");
  if (threads == j.end() || !threads->is_number_integer() || threads->get<int>() < 1) return false;
  model.threads = threads->get<int>();
  model.rms_relative_error = j.value("rms_relative_error", 0.0);
  return true;
}

}  // namespace kappa
