// Loads a scene from a scene.json (meshes, camera, environment, film) or from a
// bare OBJ (camera framing its bounding box, environment 1).
#pragma once

#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/task_progress.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// Throws InputError naming the file (and line) for refused input; warnings
/// are appended to `warnings` only when loading succeeds in the end.
Scene load_scene(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress = nullptr);

/// The view a command's options ask for, applied to a loaded scene:
/// `camera` ("" or one of Scene::cameras by name or file index: refused with
/// InputError otherwise), the film of its aspect ratio unless `width` and
/// `height` (0: not given) say otherwise (one given: the other from the
/// aspect), and the framing camera framed again for the final film.
void apply_view(Scene& scene, const std::string& camera, int width, int height);

/// The default output name: the folder name for "scene.json", else the file stem.
std::string scene_name(const std::filesystem::path& file);

}  // namespace kappa
