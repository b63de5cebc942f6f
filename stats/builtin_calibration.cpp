#include "builtin_calibration.h"

#include <stdexcept>
#include <string_view>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate --repeat 9` (its default scenes: the
// Cornell box, the low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-07 (load average 1.28), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":8,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":165.4794159259295,"Ts_ns":7.428458744745061,"Th_ns":7.0106999316336065},"rms_relative_error":0.2)"
    R"(531823475939506},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":40.777298194423295,"T0_b)"
    R"(ounce1_ns":61.308141734158426,"T0_bounce2_ns":82.46919889796075,"T0_bounce3+_ns":87.68225762135837,")"
    R"(Ts_ns":5.136094800688337,"Ts_occupied_ns":27.963104562632186,"Th_ns":7.0430367601755215,"T_hit_ns":3)"
    R"(8.49728775777546,"Ts_miss_camera_ns":0.0,"Ts_miss_shadow_ns":1.641624842918887,"Ts_miss_bounce1_ns":)"
    R"(3.0809579734742876,"Ts_miss_bounce2_ns":4.175096242785688,"Ts_miss_bounce3+_ns":6.023543299380473,"T)"
    R"(h_miss_camera_ns":2.2317567057156236,"Th_miss_shadow_ns":9.767966206312625,"Th_miss_bounce1_ns":4.74)"
    R"(8335370408449,"Th_miss_bounce2_ns":12.352158301251167,"Th_miss_bounce3+_ns":12.887265398305288},"rms)"
    R"(_relative_error":0.07743249220705778,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns)"
    R"(":8.485330837211578,"per_reference_ns":127.61951387322523,"per_cell_ns":0.0},"threads":2,"rms_relati)"
    R"(ve_error":0.19913521774375342},"naive":{"constants":{"T0_ns":49.502506110890906,"Th_ns":5.6292909052)"
    R"(59993,"Th_occluded_ns":1.0505333668650019},"rms_relative_error":0.10715393070587362},"grid2":{"trave)"
    R"(rsal":{"constants":{"T0_camera_ns":15.042405438804664,"T0_shadow_ns":63.34558682561008,"T0_bounce1_n)"
    R"(s":94.34948681249347,"T0_bounce2_ns":160.76970535673436,"T0_bounce3+_ns":178.90839843257078,"Ts_ns":)"
    R"(8.790328937402714,"Ts_occupied_ns":12.174713447530328,"Th_ns":8.623603355379597,"T_hit_ns":0.0,"Ts_m)"
    R"(iss_camera_ns":3.774980937522544,"Ts_miss_shadow_ns":7.548099057651807,"Ts_miss_bounce1_ns":8.109110)"
    R"(35816064,"Ts_miss_bounce2_ns":12.636425215807062,"Ts_miss_bounce3+_ns":16.632229609915896,"Th_miss_c)"
    R"(amera_ns":7.0864923556816075,"Th_miss_shadow_ns":8.307302508157392,"Th_miss_bounce1_ns":7.6181337870)"
    R"(99799,"Th_miss_bounce2_ns":5.894604794464539,"Th_miss_bounce3+_ns":5.425770788620354,"T_descend_ns":)"
    R"(43.95494864597547},"rms_relative_error":0.09415954887011195,"cache_bytes":1048576.0},"build":{"const)"
    R"(ants":{"per_triangle_ns":410.0762217344224,"per_reference_ns":137.6883227641675,"per_cell_ns":0.0},")"
    R"(threads":2,"rms_relative_error":0.25533078112643126}},"coherent":{"grid":{"constants":{"T0_camera_ns)"
    R"(":0.0,"T0_shadow_ns":39.24647083407044,"T0_bounce1_ns":55.70765631898943,"T0_bounce2_ns":70.58561635)"
    R"(597928,"T0_bounce3+_ns":73.64761625868965,"Ts_ns":3.6561634395628873,"Ts_occupied_ns":28.55698917402)"
    R"(6157,"Th_ns":6.687861330985026,"T_hit_ns":51.40618092689608,"Ts_miss_camera_ns":0.0,"Ts_miss_shadow_)"
    R"(ns":2.063351908188185,"Ts_miss_bounce1_ns":3.4177295313659237,"Ts_miss_bounce2_ns":4.587611168598387)"
    R"(,"Ts_miss_bounce3+_ns":6.3614585318540495,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":5.528714849054)"
    R"(041,"Th_miss_bounce1_ns":2.13745772812254,"Th_miss_bounce2_ns":8.31666992887076,"Th_miss_bounce3+_ns)"
    R"(":9.147393371728977,"Ts_cold_ns":0.9007434081032137,"Th_cold_ns":8.22336291597388},"rms_relative_err)"
    R"(or":0.06800854808195257,"cache_bytes":1048576.0},"grid2":{"constants":{"T0_camera_ns":76.47607565931)"
    R"(726,"T0_shadow_ns":119.92478395087488,"T0_bounce1_ns":149.90654688819154,"T0_bounce2_ns":196.5717663)"
    R"(3275617,"T0_bounce3+_ns":210.79989604836467,"Ts_ns":4.663517422397764,"Ts_occupied_ns":1.58189432187)"
    R"(14354,"Th_ns":8.096887628555898,"T_hit_ns":0.0,"Ts_miss_camera_ns":1.0665544300614274,"Ts_miss_shado)"
    R"(w_ns":5.533867222794654,"Ts_miss_bounce1_ns":5.701866676170327,"Ts_miss_bounce2_ns":10.5963397766170)"
    R"(77,"Ts_miss_bounce3+_ns":14.464462987468359,"Th_miss_camera_ns":6.85201844631367,"Th_miss_shadow_ns")"
    R"(:3.4057847454900863,"Th_miss_bounce1_ns":5.710395504083296,"Th_miss_bounce2_ns":3.444196309182227,"T)"
    R"(h_miss_bounce3+_ns":2.1794239211674467,"Ts_cold_ns":3.2636516881917106,"Th_cold_ns":37.2987723634516)"
    R"(6,"T_descend_ns":40.775085804421806},"rms_relative_error":0.07568924524072053,"cache_bytes":1048576.)"
    R"(0}}})";

Calibration parse_builtin() {
  const nlohmann::json j = nlohmann::json::parse(kBuiltinConstants);
  Calibration c;
  if (!from_json(j.at("eq10"), c.eq10) || !from_json(j.at("extended"), c.extended) || !from_json(j.at("build"), c.build) ||
      !from_json(j.at("naive"), c.naive) || !from_json(j.at("grid2"), c.grid2))
    throw std::logic_error("the built-in calibration is not a calibration");
  // The coherent models (each null where calibrate could not fit it), as a
  // calibration file holds them. No machine probe: the constants are used on
  // any machine, whose speed the project machine's probe says nothing of.
  if (const auto coherent = j.find("coherent"); coherent != j.end() && coherent->is_object()) {
    const auto read = [&](const char* key, std::optional<TimeModel>& out) {
      const nlohmann::json m = coherent->value(key, nlohmann::json());
      if (m.is_null()) return;
      TimeModel model = coherent_model(l2_cache_bytes(), std::string_view(key) == "grid2");
      if (!from_json(m, model)) throw std::logic_error("the built-in calibration's coherent model is not one");
      out = model;
    };
    read("grid", c.coherent);
    read("grid2", c.grid2_coherent);
  }
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
