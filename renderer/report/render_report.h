// The per-frame report of `kappa render` (keys in stats/README.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "accel/accel.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"
#include "stats/calibration.h"

namespace kappa {

struct FrameFacts {
  int width = 0, height = 0, spp = 0, threads = 0;  ///< spp: what the render took
  std::uint64_t seed = 0;
  double time_budget_s = 0;  ///< 0: none
  double target_relmse = 0;  ///< 0: none
};

/// The report; `cost` (cost_section.h) when counters ran: the measured
/// traversal time (thread-seconds) beside eq 10's and the extended model's.
nlohmann::ordered_json render_report(const Scene& scene, const Accelerator& accel, const FrameFacts& frame,
                                     const RenderResult& result, const std::optional<Calibration>& calibration = {},
                                     const nlohmann::ordered_json& settings = nullptr);

}  // namespace kappa
