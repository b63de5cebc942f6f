// Unidirectional path tracing with next-event estimation (emissive triangles
// and the constant environment, chosen by power), multiple importance sampling
// with the power heuristic, and Russian roulette: the frame's entry point.
#pragma once

#include "accel/accel.h"
#include "renderer/render/film.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// Renders `scene` through `accel` (built over scene.triangles) into `film`.
/// Pixels depend only on the scene, the settings' spp/max_depth/rr_depth/seed
/// and which exact accelerator answers: never on thread count or scheduling.
/// Runs on as many threads as the caller's ThreadLimit allows.
RenderResult render(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                    const ProgressCallback& progress = {});

}  // namespace kappa
