#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-01 (load average 0.4): the calibration file's own constants, its
// measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":4,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":124.52381137718979,"Ts_ns":6.008876744510351,"Th_ns":5.672307548332501},"rms_relative_error":0.2)"
    R"(8756537845985347},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":21.56433248905226,"T0_b)"
    R"(ounce1_ns":47.7268351791019,"T0_bounce2_ns":68.96152814621479,"T0_bounce3+_ns":67.47406035985078,"Ts)"
    R"(_ns":2.596323714560344,"Ts_occupied_ns":23.969280644742348,"Th_ns":5.711854902331635,"T_hit_ns":34.8)"
    R"(6970944496735,"Ts_miss_camera_ns":1.5447268941147596,"Ts_miss_shadow_ns":3.5935802048121035,"Ts_miss)"
    R"(_bounce1_ns":5.1955646938964195,"Ts_miss_bounce2_ns":5.881305131129698,"Ts_miss_bounce3+_ns":6.89254)"
    R"(3237105635,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":3.7872461603585736,"Th_miss_bounce1_ns":1.092)"
    R"(7420873643547,"Th_miss_bounce2_ns":4.928610419642543,"Th_miss_bounce3+_ns":6.25696409872555},"rms_re)"
    R"(lative_error":0.12287735047856953,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns":1)"
    R"(4.127052519882076,"per_reference_ns":132.13044401835802,"per_cell_ns":1.5587604288198547},"threads":)"
    R"(2,"rms_relative_error":0.25965222886853945}})";

Calibration parse_builtin() {
  const nlohmann::json j = nlohmann::json::parse(kBuiltinConstants);
  Calibration c;
  if (!from_json(j.at("eq10"), c.eq10) || !from_json(j.at("extended"), c.extended) || !from_json(j.at("build"), c.build))
    throw std::logic_error("the built-in calibration is not a calibration");
  c.samples = j.value("samples", std::size_t(0));
  c.machine = j.value("machine", std::string());
  c.clock = j.value("clock", std::string());
  c.source = "built-in";
  return c;
}

}  // namespace

const Calibration& builtin_calibration() {
  static const Calibration c = parse_builtin();
  return c;
}

}  // namespace kappa
