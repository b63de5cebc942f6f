#include "renderer/scene/mesh_file.h"

#include <cctype>

#include "renderer/scene/gltf/gltf_loader.h"
#include "renderer/scene/obj/obj_loader.h"

namespace kappa {

bool is_gltf_file(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

void load_mesh_file(const std::filesystem::path& mesh, Scene& scene, Warnings& warnings, TaskProgress* progress) {
  if (is_gltf_file(mesh)) {
    load_gltf(mesh, scene, warnings);
    return;
  }
  load_obj(mesh, scene, warnings, progress);
}

}  // namespace kappa
