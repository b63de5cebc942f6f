#include "builtin_calibration.h"

#include <stdexcept>
#include <string_view>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate --repeat 9` (its default scenes: the
// Cornell box, the low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-07 (load average 1.91), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":9,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":186.98218372649742,"Ts_ns":7.119696175638973,"Th_ns":8.066947360417211},"rms_relative_error":0.2)"
    R"(3411365203729062},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":48.72028272764872,"T0_b)"
    R"(ounce1_ns":81.77289202044898,"T0_bounce2_ns":103.1661887802089,"T0_bounce3+_ns":106.02627058195209,")"
    R"(Ts_ns":4.972811512090037,"Ts_occupied_ns":26.247624067556657,"Th_ns":8.142555122796656,"T_hit_ns":57)"
    R"(.58667704945608,"Ts_miss_camera_ns":0.0,"Ts_miss_shadow_ns":1.8249524673114597,"Ts_miss_bounce1_ns":)"
    R"(3.056166119253136,"Ts_miss_bounce2_ns":4.2619954204856745,"Ts_miss_bounce3+_ns":5.603231153632939,"T)"
    R"(h_miss_camera_ns":1.9110928860999332,"Th_miss_shadow_ns":7.535765514903796,"Th_miss_bounce1_ns":4.62)"
    R"(590764373385,"Th_miss_bounce2_ns":8.82996998940322,"Th_miss_bounce3+_ns":9.333996915403501},"rms_rel)"
    R"(ative_error":0.06106658321923556,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns":12)"
    R"(1.28591002071418,"per_reference_ns":134.59198469048215,"per_cell_ns":2.2072708299010846},"threads":2)"
    R"(,"rms_relative_error":0.2045189306819611},"naive":{"constants":{"T0_ns":48.261095997500185,"Th_ns":7)"
    R"(.3257833694517345,"Th_occluded_ns":1.4006279635355234},"rms_relative_error":0.0987328274275968},"gri)"
    R"(d2":{"traversal":{"constants":{"T0_camera_ns":4.376514945367801,"T0_shadow_ns":43.179790952664916,"T)"
    R"(0_bounce1_ns":78.30372431790398,"T0_bounce2_ns":149.83395325974055,"T0_bounce3+_ns":167.587839399095)"
    R"(,"Ts_ns":9.361473796171861,"Ts_occupied_ns":14.528805560355734,"Th_ns":10.192220619505795,"T_hit_ns")"
    R"(:0.0,"Ts_miss_camera_ns":3.135388169412103,"Ts_miss_shadow_ns":5.950845267970169,"Ts_miss_bounce1_ns)"
    R"(":7.573348401873447,"Ts_miss_bounce2_ns":9.902426621836508,"Ts_miss_bounce3+_ns":12.663582941344501,)"
    R"("Th_miss_camera_ns":5.475257502702799,"Th_miss_shadow_ns":7.296407028152369,"Th_miss_bounce1_ns":6.1)"
    R"(21130602260455,"Th_miss_bounce2_ns":4.158123427046505,"Th_miss_bounce3+_ns":3.850124039863744,"T_des)"
    R"(cend_ns":46.099113496361056},"rms_relative_error":0.08876156345534937,"cache_bytes":1048576.0},"buil)"
    R"(d":{"constants":{"per_triangle_ns":658.0029876936491,"per_reference_ns":143.7149335522298,"per_cell_)"
    R"(ns":13.988544393961428},"threads":2,"rms_relative_error":0.2212076596190863}},"coherent":{"grid":{"c)"
    R"(onstants":{"T0_camera_ns":0.0,"T0_shadow_ns":48.06047749367479,"T0_bounce1_ns":79.04792275517524,"T0)"
    R"(_bounce2_ns":98.10359289916094,"T0_bounce3+_ns":100.44330661575603,"Ts_ns":4.0248661323884685,"Ts_oc)"
    R"(cupied_ns":26.841959067037568,"Th_ns":8.193747866519294,"T_hit_ns":63.942593860898256,"Ts_miss_camer)"
    R"(a_ns":0.0,"Ts_miss_shadow_ns":1.6058229390058267,"Ts_miss_bounce1_ns":2.8199131412982243,"Ts_miss_bo)"
    R"(unce2_ns":4.018230037517761,"Ts_miss_bounce3+_ns":5.352569902201555,"Th_miss_camera_ns":1.7848764202)"
    R"(033096,"Th_miss_shadow_ns":7.028672568563042,"Th_miss_bounce1_ns":4.484669433315969,"Th_miss_bounce2)"
    R"(_ns":8.62572759022029,"Th_miss_bounce3+_ns":9.163400700139267,"Ts_cold_ns":1.1926250618917256},"rms_)"
    R"(relative_error":0.05995326161568574,"cache_bytes":1048576.0},"grid2":{"constants":{"T0_camera_ns":28)"
    R"(.411043502887246,"T0_shadow_ns":54.09400564367895,"T0_bounce1_ns":89.47705589879115,"T0_bounce2_ns":)"
    R"(151.4457368614749,"T0_bounce3+_ns":168.62774841809374,"Ts_ns":4.982213577675185,"Ts_occupied_ns":15.)"
    R"(528219185626146,"Th_ns":10.033173931000638,"T_hit_ns":0.0,"Ts_miss_camera_ns":2.3079276991427693,"Ts)"
    R"(_miss_shadow_ns":0.998198583307839,"Ts_miss_bounce1_ns":2.0999153442499985,"Ts_miss_bounce2_ns":4.08)"
    R"(8322053665076,"Ts_miss_bounce3+_ns":6.700826455782762,"Th_miss_camera_ns":5.160601039392769,"Th_miss)"
    R"(_shadow_ns":7.625296206888124,"Th_miss_bounce1_ns":7.0572567883068045,"Th_miss_bounce2_ns":5.2766789)"
    R"(231874,"Th_miss_bounce3+_ns":4.856284202426271,"Ts_cold_ns":10.286427050883702,"T_descend_ns":50.371)"
    R"(864893735044},"rms_relative_error":0.08119166019943551,"cache_bytes":1048576.0}}})";

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
