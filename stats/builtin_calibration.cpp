#include "builtin_calibration.h"

#include <stdexcept>

namespace kappa {
namespace {

// Fitted by `build/kappa calibrate` (its defaults: the Cornell box, the
// low-res bunny and the generated soups and meshes) on a project machine on
// 2026-12-07 (load average 2.15), written in by tools/builtin_calibration.py:
// the calibration file's own constants, its measurements left out.
constexpr const char* kBuiltinConstants =
    R"({"format":7,"machine":"vm, 2 cores, 2 walking","clock":"tsc","samples":125,"machine_probe_s":0.00197)"
    R"(14205,"eq10":{"constants":{"T0_ns":135.89484750817988,"Ts_ns":5.999810704740427,"Th_ns":5.6129326423)"
    R"(37419},"rms_relative_error":0.28311359089005494},"extended":{"constants":{"T0_camera_ns":0.0,"T0_sha)"
    R"(dow_ns":37.257559658580185,"T0_bounce1_ns":57.26249697464153,"T0_bounce2_ns":77.85535959501983,"T0_b)"
    R"(ounce3+_ns":85.07811776007838,"Ts_ns":3.021963828426426,"Ts_occupied_ns":23.91224480924325,"Th_ns":5)"
    R"(.612381509955179,"T_hit_ns":38.941293722842936,"Ts_miss_camera_ns":1.1259302177983188,"Ts_miss_shado)"
    R"(w_ns":2.8009503659303987,"Ts_miss_bounce1_ns":4.048191321015477,"Ts_miss_bounce2_ns":4.8649764529340)"
    R"(95,"Ts_miss_bounce3+_ns":6.562310093879527,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":4.64488611955)"
    R"(2063,"Th_miss_bounce1_ns":1.5306939572292126,"Th_miss_bounce2_ns":5.9571933798781185,"Th_miss_bounce)"
    R"(3+_ns":5.868926601444562},"rms_relative_error":0.10001055850286523,"cache_bytes":1048576.0},"build":)"
    R"({"constants":{"per_triangle_ns":16.023820449041956,"per_reference_ns":118.74159147573258,"per_cell_n)"
    R"(s":0.0},"threads":2,"rms_relative_error":0.20034566203113285},"naive":{"constants":{"T0_ns":50.93050)"
    R"(8821244736,"Th_ns":5.451377409686408,"Th_occluded_ns":1.0104812862400476},"rms_relative_error":0.111)"
    R"(50369924882282},"grid2":{"traversal":{"constants":{"T0_camera_ns":3.878458929971516,"T0_shadow_ns":4)"
    R"(1.15744247972825,"T0_bounce1_ns":66.34333918788751,"T0_bounce2_ns":119.82102717911003,"T0_bounce3+_n)"
    R"(s":144.03734139540393,"Ts_ns":9.613861832658737,"Ts_occupied_ns":18.283253615669135,"Th_ns":6.710521)"
    R"(993254045,"T_hit_ns":0.0,"Ts_miss_camera_ns":2.2695255484569667,"Ts_miss_shadow_ns":4.07343577282171)"
    R"(05,"Ts_miss_bounce1_ns":5.854824565808577,"Ts_miss_bounce2_ns":7.895938324172733,"Ts_miss_bounce3+_n)"
    R"(s":10.914804096613015,"Th_miss_camera_ns":5.660522429997158,"Th_miss_shadow_ns":6.331130448301115,"T)"
    R"(h_miss_bounce1_ns":6.3532981800527075,"Th_miss_bounce2_ns":4.928498903127253,"Th_miss_bounce3+_ns":3)"
    R"(.9086468462642685},"rms_relative_error":0.131531636243372,"cache_bytes":1048576.0},"build":{"constan)"
    R"(ts":{"per_triangle_ns":424.96854370038005,"per_reference_ns":125.92046547442136,"per_cell_ns":0.0},")"
    R"(threads":2,"rms_relative_error":0.24949912826388262}},"coherent":{"grid":{"constants":{"T0_camera_ns)"
    R"(":0.0,"T0_shadow_ns":39.21425540492104,"T0_bounce1_ns":56.83347501461235,"T0_bounce2_ns":73.74389144)"
    R"(146507,"T0_bounce3+_ns":79.22978138208238,"Ts_ns":2.2809560681915673,"Ts_occupied_ns":23.68442230591)"
    R"(0505,"Th_ns":5.190180206132693,"T_hit_ns":45.23505052975738,"Ts_miss_camera_ns":0.8234784482281003,")"
    R"(Ts_miss_shadow_ns":3.219822710695512,"Ts_miss_bounce1_ns":4.311676241238672,"Ts_miss_bounce2_ns":5.4)"
    R"(35326356199829,"Ts_miss_bounce3+_ns":7.061722098202006,"Th_miss_camera_ns":0.0,"Th_miss_shadow_ns":2)"
    R"(.055286617814095,"Th_miss_bounce1_ns":0.0,"Th_miss_bounce2_ns":2.32305902012426,"Th_miss_bounce3+_ns)"
    R"(":2.579933327358876,"Ts_cold_ns":0.06070787362179167,"Th_cold_ns":8.265771545510555},"rms_relative_e)"
    R"(rror":0.08635301120597041,"cache_bytes":1048576.0},"grid2":{"constants":{"T0_camera_ns":15.603000488)"
    R"(394887,"T0_shadow_ns":59.72871737556318,"T0_bounce1_ns":76.46945946903354,"T0_bounce2_ns":115.298265)"
    R"(64475276,"T0_bounce3+_ns":134.72174125779256,"Ts_ns":6.261286135912464,"Ts_occupied_ns":14.758052894)"
    R"(03468,"Th_ns":6.546074833005847,"T_hit_ns":19.750415551873605,"Ts_miss_camera_ns":0.0,"Ts_miss_shado)"
    R"(w_ns":0.6260218623329109,"Ts_miss_bounce1_ns":1.8108098179408794,"Ts_miss_bounce2_ns":3.748537994570)"
    R"(3805,"Ts_miss_bounce3+_ns":6.59037786281655,"Th_miss_camera_ns":5.616194135262612,"Th_miss_shadow_ns)"
    R"(":2.619092602982303,"Th_miss_bounce1_ns":5.521597601089268,"Th_miss_bounce2_ns":3.315435469024823,"T)"
    R"(h_miss_bounce3+_ns":1.8512447789951119,"Ts_cold_ns":5.288536480171764,"Th_cold_ns":25.07942048744446)"
    R"(6},"rms_relative_error":0.12112342408316178,"cache_bytes":1048576.0}}})";

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
