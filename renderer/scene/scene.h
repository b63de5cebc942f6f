// A loaded scene, whatever format it came from: flat triangle arrays with a
// material each and the vertex normals and texture coordinates their files
// gave, materials, camera, environment, film size. Loading lives in
// scene_loader (scene.json, or a bare mesh) and one loader per mesh format
// behind mesh_file.h (obj/ today); the accelerator sees only `triangles`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "accel/triangle.h"
#include "core/vec2.h"
#include "core/vec3.h"
#include "renderer/scene/material.h"
#include "renderer/scene/texture_map.h"

namespace kappa {

/// The normals a mesh file gives at a triangle's three vertices (OBJ `vn`),
/// unit length; all three zero where it gives none.
struct TriangleNormals {
  Vec3f n[3];
  bool given() const { return !(n[0] == Vec3f{0, 0, 0}); }
};

/// The texture coordinates at a triangle's three vertices (OBJ `vt`); where
/// the file gives none, pbrt's (0, 0), (1, 0), (1, 1).
struct TriangleUVs {
  Vec2f uv[3] = {{0, 0}, {1, 0}, {1, 1}};
};

/// An environment image's texels: linear RGB radiance, row 0 straight up.
struct EnvironmentImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< 3 floats a texel, row by row
};

struct CameraSpec {
  Vec3f eye{0, 0, 1};
  Vec3f look_at{0, 0, 0};
  Vec3f up{0, 1, 0};
  float vfov_deg = 39.3077f;
};

/// A camera the scene file defines (a glTF perspective camera), which
/// --camera NAME|INDEX picks.
struct NamedCamera {
  std::string name;
  int file_index = 0;  ///< its index in the file's cameras (what --camera INDEX names)
  CameraSpec spec;
  float aspect = 0;  ///< width / height the file gives; 0 when it gives none
};

/// A light no ray can hit (glTF's KHR_lights_punctual): found only by
/// next-event estimation. Intensities are in Kappa's units (see
/// docs/scene-format.md): point and spot lights in W sr^-1 (candela / 683),
/// directional lights in W m^-2 (lux / 683), the conversion Blender 3.4's glTF exporter makes.
struct PunctualLight {
  enum class Type : unsigned char { point, spot, directional };
  Type type = Type::point;
  std::string name;
  Vec3f position{0, 0, 0};     ///< point and spot
  Vec3f direction{0, 0, -1};   ///< spot and directional: the way the light travels (unit)
  Vec3f intensity{0, 0, 0};    ///< colour x intensity, converted
  float cos_inner = 1, cos_outer = 0;  ///< spot: the cone's cosines (full inside inner, 0 outside outer)
  float range = 0;             ///< the file's range (0: none); not modelled, warned
};

/// What a glTF file held, for the report.
struct GltfSummary {
  std::filesystem::path file;
  std::uint64_t nodes = 0, meshes = 0, mesh_instances = 0, primitives = 0, triangles = 0;
  std::uint64_t cameras = 0, lights = 0, materials = 0, images = 0;
};

struct Scene {
  std::string name;                    ///< used for the default output file name
  std::filesystem::path source;        ///< the file it was loaded from
  /// Every file read to make it: the scene file, each OBJ and each MTL (what
  /// no output of the run may overwrite).
  std::vector<std::filesystem::path> inputs;
  std::vector<Triangle> triangles;     ///< indexed by 32-bit TriangleId
  std::vector<std::uint32_t> material_of;  ///< per triangle, index into materials
  /// Per triangle, once any mesh gave vertex normals (else empty: no memory
  /// for a scene without them); indexed like `triangles`.
  std::vector<TriangleNormals> normals;
  /// Per triangle, once any mesh gave texture coordinates (else empty).
  std::vector<TriangleUVs> uvs;
  std::vector<Material> materials;
  /// The texture maps materials name (Material::maps indexes them).
  std::vector<TextureMap> texture_maps;
  /// The opacity maps' texels, for the cut-out test (TextureMap::mask).
  std::vector<OpacityMask> opacity_masks;
  CameraSpec camera;
  /// The cameras the scene file defines (glTF), in its order; `camera` is
  /// the first unless --camera picks another.
  std::vector<NamedCamera> cameras;
  /// The index in `cameras` of the camera `camera` is, or -1 (a scene file's
  /// camera, or the framing camera).
  int camera_index = -1;
  /// glTF's punctual lights, in world space.
  std::vector<PunctualLight> punctual_lights;
  /// The glTF files read (empty for OBJ only).
  std::vector<GltfSummary> gltf_files;
  bool camera_framed = false;  ///< the camera frames the bounds (no camera given): re-frame if the film changes
  Vec3f environment{0, 0, 0};  ///< constant radiance of rays that escape (an image's mean, with one)
  /// A latitude-longitude environment image (scene.json "environment": FILE),
  /// read by load_scene_images; empty for a constant environment.
  std::filesystem::path environment_file;
  float environment_rotation_deg = 0;  ///< about +y, counter-clockwise seen from above
  std::shared_ptr<const EnvironmentImage> environment_image;
  int width = 512;
  int height = 512;
  bool film_given = false;  ///< the scene file gives the film: a camera's aspect does not change it
  /// Seconds load_scene took to read, check and parse the files (reported
  /// apart from the accelerator's build and the render).
  double load_s = 0;

  Bounds3f bounds() const;
  /// Some material is not Material::lambertian(): the frame runs the general
  /// BSDF and counts bounce rays by lobe.
  bool has_materials() const;
  /// Some material is cut out somewhere (Material::cut_out): queries take
  /// the cut-out filter, and Embree needs its callback (AccelOptions::filtered).
  bool has_cutouts() const;
};

/// Camera framing a bounding box from the front (+z) and slightly above, far
/// enough that the bounding sphere fits the vertical field of view.
CameraSpec framing_camera(const Bounds3f& box, float vfov_deg, float aspect);

}  // namespace kappa
