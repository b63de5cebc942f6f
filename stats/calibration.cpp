#include "calibration.h"

#include <cmath>
#include <stdexcept>
#include <string_view>

#include "core/input_error.h"
#include "core/input_file.h"

namespace kappa {

Calibration fit_calibration(std::span<const TimedLoad> measurements) {
  Calibration c;
  fit(c.eq10, measurements);
  fit(c.extended, measurements);
  c.coherent = fit_coherent(measurements);
  c.samples = measurements.size();
  return c;
}

std::optional<TimeModel> fit_coherent(std::span<const TimedLoad> measurements, bool nested) {
  bool counted = false;
  for (const TimedLoad& m : measurements) counted = counted || m.load.cold_cells > 0;
  if (!counted) return std::nullopt;
  TimeModel model = coherent_model(l2_cache_bytes(), nested);
  try {
    fit(model, measurements);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // the cold steps do not vary apart from the other terms
  }
  return model;
}

namespace {

nlohmann::ordered_json load_rows(std::span<const TimedLoad> measurements, const TimeModel* eq10, const TimeModel& extended,
                                 const std::optional<TimeModel>& coherent) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const TimedLoad& m : measurements) {
    const double r = m.load.rays;
    nlohmann::ordered_json row = {{"label", m.label},
                                  {"class", kRenderClassNames[m.load.ray_class]},
                                  {"rays", r},
                                  {"ns_per_ray", m.seconds / r * 1e9},
                                  {"cells_per_ray", m.load.cells / r},
                                  {"occupied_per_ray", m.load.occupied / r},
                                  {"tests_per_ray", m.load.tests / r},
                                  {"skips_per_ray", m.load.skips / r},
                                  {"hit_fraction", m.load.hits / r},
                                  {"working_set_bytes", m.load.working_set_bytes},
                                  {"list_bytes", m.load.list_bytes},
                                  {"descents_per_ray", m.load.descents / r},
                                  {"cold_cells_per_ray", m.load.cold_cells / r},
                                  {"cold_tests_per_ray", m.load.cold_tests / r}};
    if (eq10) row["eq10_ns_per_ray"] = eq10->seconds(m.load) / r * 1e9;
    row["extended_ns_per_ray"] = extended.seconds(m.load) / r * 1e9;
    if (coherent) row["coherent_ns_per_ray"] = coherent->seconds(m.load) / r * 1e9;
    rows.push_back(std::move(row));
  }
  return rows;
}

nlohmann::ordered_json build_rows(std::span<const TimedBuild> builds, const BuildModel& model) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const TimedBuild& b : builds)
    rows.push_back({{"label", b.label},
                    {"N", b.N},
                    {"theta_tot", b.theta_tot},
                    {"N_c", b.cells},
                    {"seconds", b.seconds},
                    {"predicted_s", model.seconds(b.N, b.theta_tot, b.cells, model.threads)}});
  return rows;
}

}  // namespace

nlohmann::ordered_json to_json(const Calibration& c, const CalibrationMeasurements& measured) {
  nlohmann::ordered_json j;
  j["format"] = kCalibrationFormat;
  j["machine"] = c.machine;
  j["clock"] = c.clock;
  j["samples"] = c.samples;
  if (c.probe_s > 0) j["machine_probe_s"] = c.probe_s;
  j["eq10"] = to_json(c.eq10);
  j["extended"] = to_json(c.extended);
  j["build"] = to_json(c.build);
  j["naive"] = to_json(c.naive);
  j["grid2"] = to_json(c.grid2);
  if (c.coherent || c.grid2_coherent)
    j["coherent"] = {{"grid", c.coherent ? to_json(*c.coherent) : nlohmann::ordered_json()},
                     {"grid2", c.grid2_coherent ? to_json(*c.grid2_coherent) : nlohmann::ordered_json()}};
  if (!measured.grid.empty()) j["measurements"] = load_rows(measured.grid, &c.eq10, c.extended, c.coherent);
  if (!measured.builds.empty()) j["builds"] = build_rows(measured.builds, c.build);
  if (!measured.naive.empty()) {
    j["naive_measurements"] = nlohmann::ordered_json::array();
    for (const TimedNaiveLoad& m : measured.naive)
      j["naive_measurements"].push_back({{"label", m.label},
                                         {"class", kRenderClassNames[m.load.ray_class]},
                                         {"rays", m.load.rays},
                                         {"N", m.load.triangles},
                                         {"hit_fraction", m.load.hits / m.load.rays},
                                         {"ns_per_ray", m.seconds / m.load.rays * 1e9},
                                         {"predicted_ns_per_ray", c.naive.seconds(m.load) / m.load.rays * 1e9}});
  }
  if (!measured.grid2.empty()) j["grid2_measurements"] = load_rows(measured.grid2, nullptr, c.grid2.traversal, c.grid2_coherent);
  if (!measured.grid2_builds.empty()) j["grid2_builds"] = build_rows(measured.grid2_builds, c.grid2.build);
  return j;
}

std::filesystem::path executable_path() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe;
}

std::filesystem::path default_calibration_path() {
  const auto exe = executable_path();
  return (exe.empty() ? std::filesystem::path(".") : exe.parent_path()) / "kappa_calibration.json";
}

bool calibration_of_another_format(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_input_file(file, "a calibration file", InputContent::utf8));
    if (!j.is_object()) return false;
    const auto format = j.find("format");
    // The first format had no "format" key, only eq 10's three constants.
    if (format == j.end()) return j.contains("T0_ns");
    return !format->is_number_integer() || format->get<int>() != kCalibrationFormat;
  } catch (const std::exception&) {
    return false;  // malformed: load_calibration says so, with the file's name
  }
}

std::optional<Calibration> load_calibration(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  const std::string text = read_input_file(file, "a calibration file", InputContent::utf8);  // never blocks on a FIFO
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    throw InputError(file.string() + ": not a Kappa calibration (not JSON)");
  }
  if (!j.is_object() || j.value("format", 0) != kCalibrationFormat)
    throw InputError(file.string() + ": a calibration of another format (made by another Kappa): run kappa calibrate again");
  Calibration c;
  if (!from_json(j.value("eq10", nlohmann::json()), c.eq10) || !from_json(j.value("extended", nlohmann::json()), c.extended) ||
      !from_json(j.value("build", nlohmann::json()), c.build) || !from_json(j.value("naive", nlohmann::json()), c.naive) ||
      !from_json(j.value("grid2", nlohmann::json()), c.grid2))
    throw InputError(file.string() +
                     ": not a Kappa calibration (expected eq10, extended, build, naive and grid2 constants, each a number "
                     ">= 0)");
  c.samples = j.value("samples", std::size_t(0));
  c.machine = j.value("machine", std::string());
  c.clock = j.value("clock", std::string());
  // Optional (a calibration before it has none): what the machine probe took
  // as this file was measured.
  if (const auto probe = j.find("machine_probe_s"); probe != j.end()) {
    if (!probe->is_number() || !std::isfinite(probe->get<double>()) || !(probe->get<double>() > 0))
      throw InputError(file.string() + ": machine_probe_s is not a positive number of seconds");
    c.probe_s = probe->get<double>();
  }
  // Optional too (schema 17): the coherent models, each null where
  // the calibration could not fit it.
  if (const auto coherent = j.find("coherent"); coherent != j.end() && !coherent->is_null()) {
    if (!coherent->is_object())
      throw InputError(file.string() + ": coherent is not an object of the grid's and grid2's coherent models");
    const auto read = [&](const char* key, std::optional<TimeModel>& out) {
      const nlohmann::json m = coherent->value(key, nlohmann::json());
      if (m.is_null() && coherent->contains(key)) return;  // calibrate could not fit it
      TimeModel model = coherent_model(l2_cache_bytes(), std::string_view(key) == "grid2");
      if (!from_json(m, model))
        throw InputError(file.string() + ": coherent." + key + " is not a coherent model (constants " +
                         "each a number >= 0, and cache_bytes)");
      out = std::move(model);
    };
    read("grid", c.coherent);
    read("grid2", c.grid2_coherent);
  }
  c.source = file.string();
  return c;
}

}  // namespace kappa
