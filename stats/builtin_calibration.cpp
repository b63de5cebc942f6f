#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-07 (load average 2.15), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":7,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"eq10":{"constants":{"T0_)"
    R"(ns":135.89484750817988,"Ts_ns":5.999810704740427,"Th_ns":5.612932642337419},"rms_relative_error":0.2)"
    R"(8311359089005494},"extended":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":37.257559658580185,"T0_)"
    R"(bounce1_ns":57.26249697464153,"T0_bounce2_ns":77.85535959501983,"T0_bounce3+_ns":85.07811776007838,")"
    R"(Ts_ns":3.021963828426426,"Ts_occupied_ns":23.91224480924325,"Th_ns":5.612381509955179,"T_hit_ns":38.)"
    R"(941293722842936,"Ts_miss_camera_ns":1.1259302177983188,"Ts_miss_shadow_ns":2.8009503659303987,"Ts_mi)"
    R"(ss_bounce1_ns":4.048191321015477,"Ts_miss_bounce2_ns":4.864976452934095,"Ts_miss_bounce3+_ns":6.5623)"
    R"(10093879527,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":4.644886119552063,"Th_miss_bounce1_ns":1.530)"
    R"(6939572292126,"Th_miss_bounce2_ns":5.9571933798781185,"Th_miss_bounce3+_ns":5.868926601444562},"rms_)"
    R"(relative_error":0.10001055850286523,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns")"
    R"(:16.023820449041956,"per_reference_ns":118.74159147573258,"per_cell_ns":0.0},"threads":2,"rms_relati)"
    R"(ve_error":0.20034566203113285},"naive":{"constants":{"T0_ns":50.930508821244736,"Th_ns":5.4513774096)"
    R"(86408,"Th_occluded_ns":1.0104812862400476},"rms_relative_error":0.11150369924882282},"grid2":{"trave)"
    R"(rsal":{"constants":{"T0_camera_ns":3.878458929971516,"T0_shadow_ns":41.15744247972825,"T0_bounce1_ns)"
    R"(":66.34333918788751,"T0_bounce2_ns":119.82102717911003,"T0_bounce3+_ns":144.03734139540393,"Ts_ns":9)"
    R"(.613861832658737,"Ts_occupied_ns":18.283253615669135,"Th_ns":6.710521993254045,"T_hit_ns":0.0,"Ts_mi)"
    R"(ss_camera_ns":2.2695255484569667,"Ts_miss_shadow_ns":4.0734357728217105,"Ts_miss_bounce1_ns":5.85482)"
    R"(4565808577,"Ts_miss_bounce2_ns":7.895938324172733,"Ts_miss_bounce3+_ns":10.914804096613015,"Th_miss_)"
    R"(camera_ns":5.660522429997158,"Th_miss_shadow_ns":6.331130448301115,"Th_miss_bounce1_ns":6.3532981800)"
    R"(527075,"Th_miss_bounce2_ns":4.928498903127253,"Th_miss_bounce3+_ns":3.9086468462642685},"rms_relativ)"
    R"(e_error":0.131531636243372,"cache_bytes":1048576.0},"build":{"constants":{"per_triangle_ns":424.9685)"
    R"(4370038005,"per_reference_ns":125.92046547442136,"per_cell_ns":0.0},"threads":2,"rms_relative_error")"
    R"(:0.24949912826388262}},"coherent":{"grid":{"constants":{"T0_camera_ns":0.0,"T0_shadow_ns":39.2142554)"
    R"(0492104,"T0_bounce1_ns":56.83347501461235,"T0_bounce2_ns":73.74389144146507,"T0_bounce3+_ns":79.2297)"
    R"(8138208238,"Ts_ns":2.2809560681915673,"Ts_occupied_ns":23.684422305910505,"Th_ns":5.190180206132693,)"
    R"("T_hit_ns":45.23505052975738,"Ts_miss_camera_ns":0.8234784482281003,"Ts_miss_shadow_ns":3.2198227106)"
    R"(95512,"Ts_miss_bounce1_ns":4.311676241238672,"Ts_miss_bounce2_ns":5.435326356199829,"Ts_miss_bounce3)"
    R"(+_ns":7.061722098202006,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":2.055286617814095,"Th_miss_bounc)"
    R"(e1_ns":0.0,"Th_miss_bounce2_ns":2.32305902012426,"Th_miss_bounce3+_ns":2.579933327358876,"Ts_cold_ns)"
    R"(":0.06070787362179167,"Th_cold_ns":8.265771545510555},"rms_relative_error":0.08635301120597041,"cach)"
    R"(e_bytes":1048576.0},"grid2":{"constants":{"T0_camera_ns":15.603000488394887,"T0_shadow_ns":59.728717)"
    R"(37556318,"T0_bounce1_ns":76.46945946903354,"T0_bounce2_ns":115.29826564475276,"T0_bounce3+_ns":134.7)"
    R"(2174125779256,"Ts_ns":6.261286135912464,"Ts_occupied_ns":14.75805289403468,"Th_ns":6.546074833005847)"
    R"(,"T_hit_ns":19.750415551873605,"Ts_miss_camera_ns":0.0,"Ts_miss_shadow_ns":0.6260218623329109,"Ts_mi)"
    R"(ss_bounce1_ns":1.8108098179408794,"Ts_miss_bounce2_ns":3.7485379945703805,"Ts_miss_bounce3+_ns":6.59)"
    R"(037786281655,"Th_miss_camera_ns":5.616194135262612,"Th_miss_shadow_ns":2.619092602982303,"Th_miss_bo)"
    R"(unce1_ns":5.521597601089268,"Th_miss_bounce2_ns":3.315435469024823,"Th_miss_bounce3+_ns":1.851244778)"
    R"(9951119,"Ts_cold_ns":5.288536480171764,"Th_cold_ns":25.079420487444466},"rms_relative_error":0.12112)"
    R"(342408316178,"cache_bytes":1048576.0}}})";

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
      TimeModel model = coherent_model(l2_cache_bytes());
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
