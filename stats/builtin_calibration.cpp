#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-02 (load average 2.13), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":7,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":168.95752809870592,"Ts_ns":6.803502676851406,"Th_ns":9.34676143244364},"rms_relative_error":0.25)"
    R"(14187741132908},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":0.0,"T0_bounce1_ns":43.21)"
    R"(864945757352,"T0_bounce2_ns":63.55415555344686,"T0_bounce3+_ns":64.71081053241804,"Ts_ns":3.08989343)"
    R"(1529088,"Ts_occupied_ns":31.50884277201429,"Th_ns":9.504528144684862,"T_hit_ns":58.15113045148664,"T)"
    R"(s_miss_camera_ns":1.520808140414029,"Ts_miss_shadow_ns":3.3806881324246354,"Ts_miss_bounce1_ns":5.09)"
    R"(9716578124552,"Ts_miss_bounce2_ns":5.950554327061827,"Ts_miss_bounce3+_ns":7.939560851322486,"Th_mis)"
    R"(s_camera_ns":0.0,"Th_miss_shadow_ns":4.930701575176127,"Th_miss_bounce1_ns":0.5914692580910534,"Th_m)"
    R"(iss_bounce2_ns":8.684774959663761,"Th_miss_bounce3+_ns":10.328130025893746},"rms_relative_error":0.0)"
    R"(8610232229735147,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns":67.82662965824757,)"
    R"("per_reference_ns":137.01658963879188,"per_cell_ns":0.0},"threads":2,"rms_relative_error":0.23966160)"
    R"(78497673},"naive":{"constants":{"T0_ns":49.64158643573157,"Th_ns":7.509511348390501,"Th_occluded_ns")"
    R"(:1.4720810695224584},"rms_relative_error":0.09817313326676531},"grid2":{"traversal":{"constants":{"T)"
    R"(0_camera_ns":0.0,"T0_shadow_ns":19.43123291277215,"T0_bounce1_ns":48.09664639328867,"T0_bounce2_ns":)"
    R"(130.36200365944336,"T0_bounce3+_ns":153.35903006538655,"Ts_ns":15.315243364773444,"Ts_occupied_ns":2)"
    R"(1.56379561659436,"Th_ns":10.780239179762958,"T_hit_ns":0.0,"Ts_miss_camera_ns":0.0,"Ts_miss_shadow_n)"
    R"(s":4.3792634733505675,"Ts_miss_bounce1_ns":5.293979295616998,"Ts_miss_bounce2_ns":9.767647072922385,)"
    R"("Ts_miss_bounce3+_ns":14.55291724539329,"Th_miss_camera_ns":5.4276967306785675,"Th_miss_shadow_ns":8)"
    R"(.77951843529823,"Th_miss_bounce1_ns":6.265149568140445,"Th_miss_bounce2_ns":4.355687870346922,"Th_mi)"
    R"(ss_bounce3+_ns":3.890328287394028},"rms_relative_error":0.16299160824402772,"cache_bytes":1048576.0})"
    R"(,"build":{"constants":{"per_triangle_ns":864.6358080109086,"per_reference_ns":132.90807288591282,"pe)"
    R"(r_cell_ns":0.0},"threads":2,"rms_relative_error":0.24817075626706073}}})";

Calibration parse_builtin() {
  const nlohmann::json j = nlohmann::json::parse(kBuiltinConstants);
  Calibration c;
  if (!from_json(j.at("eq10"), c.eq10) || !from_json(j.at("extended"), c.extended) || !from_json(j.at("build"), c.build) ||
      !from_json(j.at("naive"), c.naive) || !from_json(j.at("grid2"), c.grid2))
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
