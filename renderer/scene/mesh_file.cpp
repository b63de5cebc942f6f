#include "renderer/scene/mesh_file.h"

#include <cctype>

#include "core/input_error.h"
#include "core/memory_need.h"
#include "renderer/scene/gltf/gltf_loader.h"
#include "renderer/scene/obj/obj_loader.h"

namespace kappa {

bool is_gltf_file(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

namespace {

/// A mesh in a format Kappa does not read is named as such, rather than
/// read as an OBJ and found to hold no triangles.
void refuse_other_mesh_formats(const std::filesystem::path& mesh) {
  std::string ext = mesh.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  static const char* const kOthers[][2] = {
      {".ply", "PLY"},       {".stl", "STL"},        {".fbx", "FBX"},   {".dae", "COLLADA"},
      {".3ds", "3DS"},       {".blend", "Blender"},  {".abc", "Alembic"}, {".usd", "USD"},
      {".usda", "USD"},      {".usdc", "USD"},       {".usdz", "USD"},  {".off", "OFF"},
      {".x3d", "X3D"},       {".wrl", "VRML"},       {".vtk", "VTK"},   {".pbrt", "pbrt-v4"},
  };
  for (const auto& [suffix, format] : kOthers)
    if (ext == suffix)
      throw InputError(mesh.string() + ": " + format +
                       " files are not read: Kappa reads OBJ (.obj) and glTF 2.0 (.gltf, .glb) meshes; convert it "
                       "(Blender exports both)");
}

}  // namespace

void load_mesh_file(const std::filesystem::path& mesh, Scene& scene, Warnings& warnings, TaskProgress* progress) {
  // Running out of memory while loading names the file (core/memory_need.h).
  const MemoryNeed need("loading '" + mesh.string() + "'", 0);
  if (is_gltf_file(mesh)) {
    load_gltf(mesh, scene, warnings);
    return;
  }
  refuse_other_mesh_formats(mesh);
  load_obj(mesh, scene, warnings, progress);
}

}  // namespace kappa
