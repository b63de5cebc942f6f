#include "renderer/scene/mesh_file.h"

#include "renderer/scene/obj/obj_loader.h"

namespace kappa {

void load_mesh_file(const std::filesystem::path& mesh, Scene& scene, Warnings& warnings, TaskProgress* progress) {
  // One format so far: every mesh is read as OBJ.
  load_obj(mesh, scene, warnings, progress);
}

}  // namespace kappa
