#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-01 (load average 2.0): the calibration file's own constants, its
// measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":3,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":131.07927851339713,"Ts_ns":6.277677434053445,"Th_ns":5.764804539503684},"rms_relative_error":0.2)"
    R"(9052468467942616},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":22.0079212707729,"T0_bo)"
    R"(unce1_ns":52.12274552879179,"T0_bounce2_ns":73.43734217265484,"T0_bounce3+_ns":70.6184587905902,"Ts_)"
    R"(ns":2.570200353250761,"Ts_occupied_ns":25.12246167288812,"Th_ns":5.787953952430362,"T_hit_ns":39.385)"
    R"(04713395303,"Ts_miss_camera_ns":1.7788999977773232,"Ts_miss_shadow_ns":3.796661465157556,"Ts_miss_bo)"
    R"(unce1_ns":5.366843240820699,"Ts_miss_bounce2_ns":6.1836674471210795,"Ts_miss_bounce3+_ns":7.24967998)"
    R"(6680606,"Th_miss_camera_ns":0.03292205661501361,"Th_miss_shadow_ns":4.707181378616512,"Th_miss_bounc)"
    R"(e1_ns":1.5072876582444248,"Th_miss_bounce2_ns":6.179097684344332,"Th_miss_bounce3+_ns":7.15993480949)"
    R"(1339},"rms_relative_error":0.11900617233489806,"cache_bytes":1048576.0}})";

Calibration parse_builtin() {
  const nlohmann::json j = nlohmann::json::parse(kBuiltinConstants);
  Calibration c;
  if (!from_json(j.at("eq10"), c.eq10) || !from_json(j.at("extended"), c.extended))
    throw std::logic_error("the built-in calibration is not a calibration");
  c.samples = j.value("samples", std::size_t(0));
  c.machine = j.value("machine", std::string());
  c.clock = j.value("clock", std::string());
  return c;
}

}  // namespace

const Calibration& builtin_calibration() {
  static const Calibration c = parse_builtin();
  return c;
}

}  // namespace kappa
