// The report's "cost": the measured traversal time of every class (every
// query on the QueryClock) beside eq 10's and the extended model's
// predictions from the frame's own counts and the calibration's constants.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "accel/accel.h"
#include "renderer/render/frame.h"
#include "stats/calibration.h"

namespace kappa {

/// null without counters (statistics off). The models are the uniform
/// grid's (kappa calibrate times its walk): null for another accelerator or
/// without a calibration, as is every relative error then.
nlohmann::ordered_json cost_section(const Accelerator& accel, std::size_t triangles, const RenderResult& result,
                                    const std::optional<Calibration>& calibration);

}  // namespace kappa
