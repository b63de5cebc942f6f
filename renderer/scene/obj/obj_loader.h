// OBJ + MTL loading through tinyobjloader, behind a line-numbered pre-scan that
// refuses (InputError naming file:line) or repairs with a warning what
// tinyobjloader would otherwise accept silently. The policy per case is the
// table in docs/bad-input.md ("Bad input").
#pragma once

#include <filesystem>

#include "core/error.h"
#include "core/task_progress.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// Appends the triangles and materials of `obj` to `scene`. Zero-area triangles
/// are dropped (with a warning). Throws InputError on refused input.
void load_obj(const std::filesystem::path& obj, Scene& scene, Warnings& warnings, TaskProgress* progress = nullptr);

}  // namespace kappa
