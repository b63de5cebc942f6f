#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-01 (load average 1.67, beside a helper's runs), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":5,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":140.7019428381671,"Ts_ns":6.697456612589541,"Th_ns":7.410906737828726},"rms_relative_error":0.27)"
    R"(87196711559516},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":15.108009691423609,"T0_bo)"
    R"(unce1_ns":43.09794945799932,"T0_bounce2_ns":64.20205126963084,"T0_bounce3+_ns":67.38001918699565,"Ts)"
    R"(_ns":2.7973806937784733,"Ts_occupied_ns":27.694788207912627,"Th_ns":7.425689619745463,"T_hit_ns":42.)"
    R"(590738012226936,"Ts_miss_camera_ns":1.7851256530700903,"Ts_miss_shadow_ns":3.914101101854556,"Ts_mis)"
    R"(s_bounce1_ns":5.667218115807399,"Ts_miss_bounce2_ns":6.919902201680939,"Ts_miss_bounce3+_ns":8.08027)"
    R"(6737985674,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":5.160295001456544,"Th_miss_bounce1_ns":1.9413)"
    R"(198843745305,"Th_miss_bounce2_ns":6.795072206782575,"Th_miss_bounce3+_ns":7.459184936730274},"rms_re)"
    R"(lative_error":0.11424384823926986,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns":7)"
    R"(6.8568459612004,"per_reference_ns":106.26666008395831,"per_cell_ns":0.0},"threads":2,"rms_relative_e)"
    R"(rror":0.2275604463647324},"naive":{"constants":{"T0_ns":47.26578437739261,"Th_ns":5.537086338243763,)"
    R"("Th_occluded_ns":1.0437787145940078},"rms_relative_error":0.10173872985333948}})";

Calibration parse_builtin() {
  const nlohmann::json j = nlohmann::json::parse(kBuiltinConstants);
  Calibration c;
  if (!from_json(j.at("eq10"), c.eq10) || !from_json(j.at("extended"), c.extended) || !from_json(j.at("build"), c.build) ||
      !from_json(j.at("naive"), c.naive))
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
