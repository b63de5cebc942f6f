// The one entry point for mesh files, whatever their format: picks the
// format's loader (obj/, gltf/) by the file's extension.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "core/task_progress.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// A .gltf or .glb name (any case).
bool is_gltf_file(const std::filesystem::path& file);

/// Appends the triangles, vertex attributes and materials of `mesh` to
/// `scene`. A name whose extension names no other format is read as OBJ, as
/// Kappa always has. Throws InputError on refused input.
void load_mesh_file(const std::filesystem::path& mesh, Scene& scene, Warnings& warnings,
                    TaskProgress* progress = nullptr);

}  // namespace kappa
