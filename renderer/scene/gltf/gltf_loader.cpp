#include "renderer/scene/gltf/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "renderer/scene/gltf/gltf_accessor.h"
#include "renderer/scene/gltf/gltf_file.h"
#include "renderer/scene/gltf/gltf_material.h"
#include "renderer/scene/gltf/gltf_transform.h"
#include "renderer/scene/gltf/gltf_warnings.h"
#include "core/physical_memory.h"
#include "renderer/scene/obj/obj_limits.h"

namespace kappa {
namespace {

/// Photometric to radiometric, at the 683 lm/W of the extension's units
/// (and of Blender 3.4's glTF exporter): candela to W/sr, lux to W/m^2.
constexpr double kLumensPerWatt = 683.0;

struct Placed {
  int node;
  Affine world;
};

/// A node's own transform, its numbers checked.
Affine local_transform(const std::filesystem::path& file, const tinygltf::Node& n, const std::string& p,
                       GltfWarnings& warnings) {
  auto finite = [&](const std::vector<double>& v, const char* key, std::size_t size) {
    if (v.empty()) return false;
    if (v.size() != size) fail(file, 0, p + "/" + key + ": must be " + std::to_string(size) + " numbers");
    for (double x : v)
      if (!std::isfinite(x)) fail(file, 0, p + "/" + key + ": holds a NaN or infinite number");
    return true;
  };
  const bool has_matrix = finite(n.matrix, "matrix", 16);
  // (tinygltf reads no translation/rotation/scale beside a matrix.)
  const bool has_t = finite(n.translation, "translation", 3), has_r = finite(n.rotation, "rotation", 4),
             has_s = finite(n.scale, "scale", 3);
  if (has_matrix) {
    // Column-major: the bottom row is elements 3, 7, 11, 15. glTF's node
    // matrices are affine (decomposable into TRS).
    const double* m = n.matrix.data();
    if (std::abs(m[3]) > 1e-6 || std::abs(m[7]) > 1e-6 || std::abs(m[11]) > 1e-6 || std::abs(m[15] - 1) > 1e-6)
      fail(file, 0, p + "/matrix: its last row is not (0, 0, 0, 1): not an affine transform, which glTF requires");
    return Affine::from_column_major(m);
  }
  if (!has_t && !has_r && !has_s) return Affine{};
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
  if (has_t) std::copy(n.translation.begin(), n.translation.end(), t);
  if (has_s) std::copy(n.scale.begin(), n.scale.end(), s);
  if (has_r) {
    const double len = std::sqrt(n.rotation[0] * n.rotation[0] + n.rotation[1] * n.rotation[1] +
                                 n.rotation[2] * n.rotation[2] + n.rotation[3] * n.rotation[3]);
    if (!(len > 0)) fail(file, 0, p + "/rotation: the zero quaternion is no rotation");
    if (std::abs(len - 1) > 1e-3)
      warnings.once("rotation not unit", p + "/rotation", "not a unit quaternion (length " + std::to_string(len) + "): normalised");
    for (int k = 0; k < 4; ++k) q[k] = n.rotation[std::size_t(k)] / len;
  }
  return Affine::from_trs(t, q, s);
}

class GltfLoader {
 public:
  GltfLoader(GltfFile& gltf, Scene& scene, Warnings& warnings)
      : m_gltf(gltf), m_model(gltf.model), m_file(gltf.file), m_scene(scene), m_warnings(gltf.file, warnings),
        m_materials(gltf, scene, m_warnings) {}

  void load() {
    m_summary.file = m_file;
    m_summary.nodes = m_model.nodes.size();
    m_summary.meshes = m_model.meshes.size();
    m_summary.materials = m_model.materials.size();
    m_summary.images = m_model.images.size();
    const std::vector<Placed> placed = walk_nodes();
    check_triangle_budget(placed);
    for (const Placed& node : placed) {
      const tinygltf::Node& n = m_model.nodes[std::size_t(node.node)];
      const std::string p = json_pointer({"nodes", std::to_string(node.node)});
      if (n.mesh >= 0) add_mesh_instance(node, p);
      if (n.camera >= 0) add_camera(node, p);
      add_light(node, n, p);
      if (n.skin >= 0) m_warnings.once("skin", p + "/skin", "skins are not applied: the mesh is placed by its node alone");
      if (!n.weights.empty()) m_warnings.once("weights", p + "/weights", "morph target weights are not applied");
    }
    if (!m_model.animations.empty()) m_warnings.once("animations", "/animations", "animations are not played: the file's rest pose is rendered");
    if (m_zero_area > 0)
      m_warnings.once("zero area", "/meshes", std::to_string(m_zero_area) + " zero-area triangles dropped");
    if (m_too_small > 0)
      m_warnings.once("too small", "/meshes", std::to_string(m_too_small) +
                                                  " triangles smaller than 1e-15 across dropped: single-precision "
                                                  "intersection cannot hit them");
    m_scene.gltf_files.push_back(m_summary);
  }

 private:
  /// The nodes of the scene to render, each with its world transform, in
  /// depth-first order (children in their listed order).
  std::vector<Placed> walk_nodes() {
    const std::size_t n = m_model.nodes.size();
    std::vector<int> roots;
    int scene = m_model.defaultScene;
    if (scene >= 0 && std::size_t(scene) >= m_model.scenes.size())
      fail(m_file, 0, "/scene: " + std::to_string(scene) + " does not exist (" + std::to_string(m_model.scenes.size()) + " scenes)");
    if (scene < 0 && !m_model.scenes.empty()) scene = 0;
    if (m_model.scenes.size() > 1)
      m_warnings.once("scenes", "/scenes", std::to_string(m_model.scenes.size()) + " scenes: only scene " +
                                               std::to_string(scene) + " (the default) is rendered");
    if (scene >= 0) {
      std::vector<int> parent(n, -1);
      for (std::size_t i = 0; i < n; ++i)
        for (int c : m_model.nodes[i].children)
          if (c >= 0 && std::size_t(c) < n) parent[std::size_t(c)] = int(i);
      const std::vector<int>& list = m_model.scenes[std::size_t(scene)].nodes;
      for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string sp = json_pointer({"scenes", std::to_string(scene), "nodes", std::to_string(k)});
        if (list[k] < 0 || std::size_t(list[k]) >= n)
          fail(m_file, 0, sp + ": node " + std::to_string(list[k]) + " does not exist (" + std::to_string(n) + " nodes)");
        if (const int up = parent[std::size_t(list[k])]; up >= 0) {
          // Its own ancestor (a cycle), or below a root: either way not a root.
          int at = up;
          for (std::size_t step = 0; at >= 0 && at != list[k] && step < n; ++step) at = parent[std::size_t(at)];
          const std::vector<int>& siblings = m_model.nodes[std::size_t(up)].children;
          const auto slot = std::size_t(std::find(siblings.begin(), siblings.end(), list[k]) - siblings.begin());
          if (at == list[k])
            fail(m_file, 0, json_pointer({"nodes", std::to_string(up), "children", std::to_string(slot)}) + ": node " +
                                std::to_string(list[k]) + " is its own ancestor (a cycle): glTF's nodes form trees");
          fail(m_file, 0, sp + ": node " + std::to_string(list[k]) + " is not a root (node " + std::to_string(up) +
                              " is its parent): a scene lists roots");
        }
        roots.push_back(list[k]);
      }
    } else {
      // No scene: the specification leaves it to the application; every root.
      std::vector<bool> child(n, false);
      for (const tinygltf::Node& node : m_model.nodes)
        for (int c : node.children)
          if (c >= 0 && std::size_t(c) < n) child[std::size_t(c)] = true;
      for (std::size_t i = 0; i < n; ++i)
        if (!child[i]) roots.push_back(int(i));
      if (!roots.empty()) m_warnings.once("no scene", "/scenes", "no scene: every root node is rendered");
    }
    std::vector<char> seen(n, 0);
    std::vector<Placed> out;
    std::vector<Placed> stack;  // explicit: no recursion on the file's depth
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, Affine{}});
    // Roots are placed with the identity; a node reached twice is refused.
    while (!stack.empty()) {
      Placed top = stack.back();
      stack.pop_back();
      const std::size_t i = std::size_t(top.node);
      const std::string p = json_pointer({"nodes", std::to_string(i)});
      if (seen[i]) fail(m_file, 0, p + ": reached twice from the scene (a cycle, a second parent, or listed twice): glTF's nodes form trees");
      seen[i] = 1;
      const tinygltf::Node& node = m_model.nodes[i];
      const Affine local = local_transform(m_file, node, p, m_warnings);
      top.world = top.world.identity() ? local : local.identity() ? top.world : top.world * local;
      out.push_back(top);
      for (std::size_t k = node.children.size(); k-- > 0;) {
        const int c = node.children[k];
        if (c < 0 || std::size_t(c) >= n)
          fail(m_file, 0, p + "/children/" + std::to_string(k) + ": node " + std::to_string(c) + " does not exist (" +
                              std::to_string(n) + " nodes)");
        if (seen[std::size_t(c)])
          fail(m_file, 0, p + "/children/" + std::to_string(k) + ": node " + std::to_string(c) +
                              " is its own ancestor or has a second parent (a cycle): glTF's nodes form trees");
        stack.push_back({c, top.world});
      }
    }
    return out;
  }

  /// Refuses, before a triangle is copied, a file whose instances would
  /// make more triangles than Kappa's 32-bit ids or this machine's memory
  /// hold: a mesh reused by many nodes, or accessors reused by many
  /// primitives, cost the file a few bytes each.
  void check_triangle_budget(const std::vector<Placed>& placed) const {
    const double bytes_per_triangle = double(sizeof(Triangle) + sizeof(std::uint32_t) + sizeof(TriangleNormals) +
                                             sizeof(TriangleUVs));
    const double memory = double(physical_memory_bytes());
    double total = double(m_scene.triangles.size());
    for (const Placed& node : placed) {
      const int mesh = m_model.nodes[std::size_t(node.node)].mesh;
      if (mesh < 0 || std::size_t(mesh) >= m_model.meshes.size()) continue;  // refused when placed
      for (const tinygltf::Primitive& prim : m_model.meshes[std::size_t(mesh)].primitives) {
        int accessor = prim.indices;
        if (accessor < 0) {
          const auto it = prim.attributes.find("POSITION");
          accessor = it == prim.attributes.end() ? -1 : it->second;
        }
        if (accessor < 0 || std::size_t(accessor) >= m_model.accessors.size()) continue;
        total += double(m_model.accessors[std::size_t(accessor)].count);  // at most one triangle a vertex
      }
      if (total >= double(kNoTriangle) || (memory > 0 && total / 3.0 * bytes_per_triangle > memory))
        fail(m_file, 0, json_pointer({"nodes", std::to_string(node.node)}) + ": the scene's mesh instances up to here " +
                            "make up to " + std::to_string(std::uint64_t(total)) + " triangles, more than Kappa's " +
                            "32-bit triangle ids or this machine's memory hold (meshes are copied per node)");
    }
  }

  void add_mesh_instance(const Placed& node, const std::string& p) {
    const tinygltf::Node& n = m_model.nodes[std::size_t(node.node)];
    if (std::size_t(n.mesh) >= m_model.meshes.size())
      fail(m_file, 0, p + "/mesh: " + std::to_string(n.mesh) + " does not exist (" + std::to_string(m_model.meshes.size()) + " meshes)");
    const tinygltf::Mesh& mesh = m_model.meshes[std::size_t(n.mesh)];
    ++m_summary.mesh_instances;
    for (std::size_t k = 0; k < mesh.primitives.size(); ++k)
      add_primitive(mesh.primitives[k], json_pointer({"meshes", std::to_string(n.mesh), "primitives", std::to_string(k)}),
                    node.world);
  }

  void add_primitive(const tinygltf::Primitive& prim, const std::string& p, const Affine& world) {
    ++m_summary.primitives;
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP) {
      m_warnings.once("mode " + std::to_string(mode), p + "/mode",
                      std::string(mode == TINYGLTF_MODE_POINTS ? "points" : "lines") +
                          " are not rendered (Kappa renders triangles): the primitive is skipped");
      return;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      fail(m_file, 0, p + "/mode: " + std::to_string(mode) + " is not a glTF primitive mode (0 to 6)");
    if (!prim.targets.empty()) m_warnings.once("targets", p + "/targets", "morph targets are not applied");
    if (prim.attributes.count("COLOR_0"))
      m_warnings.once("COLOR_0", p + "/attributes/COLOR_0", "vertex colours are not modelled: ignored");
    const auto attr = [&](const char* name) {
      const auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attr("POSITION") < 0) fail(m_file, 0, p + "/attributes: no POSITION");
    const AccessorReader positions(m_gltf, attr("POSITION"), p + "/attributes", "POSITION", TINYGLTF_TYPE_VEC3,
                                   {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const std::size_t count = positions.count();
    std::vector<Vec3f> world_positions(count);
    const bool identity = world.identity();
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3d v = identity ? positions.vec3(i) : world.point(positions.vec3(i));
      for (double c : {v.x, v.y, v.z})
        if (!std::isfinite(c) || std::abs(c) > kMaxCoordinate)
          fail(m_file, 0, positions.pointer() + ": vertex " + std::to_string(i) + " lies at " +
                              std::to_string(c) + " in world space: NaN, infinite or past Kappa's limit of 1e12");
      world_positions[i] = Vec3f(v);
    }
    std::vector<std::uint32_t> corners;  // vertex indices, three a triangle
    std::vector<std::uint32_t> order;    // the primitive's vertex order
    if (prim.indices >= 0) {
      const AccessorReader indices(m_gltf, prim.indices, p, "indices", TINYGLTF_TYPE_SCALAR,
                                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      order.resize(indices.count());
      for (std::size_t i = 0; i < indices.count(); ++i) {
        order[i] = indices.index(i);
        if (order[i] >= count)
          fail(m_file, 0, indices.pointer() + ": index " + std::to_string(order[i]) + " (element " + std::to_string(i) +
                              ") is out of range: " + p + " has " + std::to_string(count) + " vertices");
      }
    } else {
      order.resize(count);
      for (std::size_t i = 0; i < count; ++i) order[i] = std::uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (order.size() % 3 != 0)
        m_warnings.once("partial triangle", p, std::to_string(order.size()) + " vertices is not a multiple of 3: the last " +
                                                   std::to_string(order.size() % 3) + " are ignored");
      corners.assign(order.begin(), order.begin() + std::ptrdiff_t(order.size() / 3 * 3));
    } else if (order.size() >= 3) {
      // The specification's orders (3.7.2.1): strip triangle i is
      // (i, i + 1 + i % 2, i + 2 - i % 2), which keeps the winding; fan
      // triangle i is (i + 1, i + 2, 0).
      for (std::size_t i = 0; i + 2 < order.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
          corners.insert(corners.end(), {order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]});
        } else {
          corners.insert(corners.end(), {order[i + 1], order[i + 2], order[0]});
        }
      }
    }

    const int normal_attr = attr("NORMAL"), uv_attr = attr("TEXCOORD_0");
    std::vector<Vec3f> normals;
    if (normal_attr >= 0) {
      const AccessorReader r(m_gltf, normal_attr, p + "/attributes", "NORMAL", TINYGLTF_TYPE_VEC3,
                             {TINYGLTF_COMPONENT_TYPE_FLOAT});
      if (r.count() != count) fail(m_file, 0, r.pointer() + "/count: " + std::to_string(r.count()) + " normals for " + std::to_string(count) + " positions");
      normals.resize(count);
      for (std::size_t i = 0; i < count; ++i) {
        const Vec3d n = identity ? r.vec3(i) : world.normal(r.vec3(i));
        const double len = length(n);
        normals[i] = len > 0 && std::isfinite(len) ? Vec3f(n / len) : Vec3f{0, 0, 0};
        if (normals[i] == Vec3f{0, 0, 0})
          m_warnings.once("bad normal", r.pointer(), "a normal that is zero, NaN or infinite (element " +
                                                         std::to_string(i) + "): its triangles are shaded flat");
      }
    }
    std::vector<Vec2f> uvs;
    if (uv_attr >= 0) {
      const AccessorReader r(m_gltf, uv_attr, p + "/attributes", "TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                             {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                             /*normalized_integers=*/true);
      if (r.count() != count) fail(m_file, 0, r.pointer() + "/count: " + std::to_string(r.count()) + " texture coordinates for " + std::to_string(count) + " positions");
      uvs.resize(count);
      for (std::size_t i = 0; i < count; ++i) {
        const Vec2f t = r.vec2(i);
        if (!std::isfinite(t.u) || !std::isfinite(t.v))
          fail(m_file, 0, r.pointer() + ": element " + std::to_string(i) + " is NaN or infinite");
        // glTF's v runs down the image, an OBJ's up: stored as an OBJ's.
        uvs[i] = {t.u, float(1.0 - double(t.v))};
      }
    }
    const std::uint32_t material = m_materials.material(prim.material, p);
    // A mirroring transform turns the winding: swap two corners so the
    // front stays the side the file's counter-clockwise order faces.
    const bool mirrored = world.determinant() < 0;
    // Once any primitive gives normals (texture coordinates), every triangle
    // has an entry: the earlier ones "none", as the OBJ loader does.
    const bool keep_normals = !normals.empty() || !m_scene.normals.empty();
    const bool keep_uvs = !uvs.empty() || !m_scene.uvs.empty();
    if (keep_normals) m_scene.normals.resize(m_scene.triangles.size());
    if (keep_uvs) m_scene.uvs.resize(m_scene.triangles.size());
    for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
      std::uint32_t c[3] = {corners[t], corners[t + 1], corners[t + 2]};
      if (mirrored) std::swap(c[1], c[2]);
      const Triangle tri{world_positions[c[0]], world_positions[c[1]], world_positions[c[2]]};
      if (!(double_area(tri) > 0.0)) {
        ++m_zero_area;
        continue;
      }
      const double longest = std::max({length(Vec3d(tri.v1) - Vec3d(tri.v0)), length(Vec3d(tri.v2) - Vec3d(tri.v1)),
                                       length(Vec3d(tri.v0) - Vec3d(tri.v2))});
      if (longest < kMinTriangleSize) {
        ++m_too_small;
        continue;
      }
      m_scene.triangles.push_back(tri);
      m_scene.material_of.push_back(material);
      ++m_summary.triangles;
      if (keep_normals) {
        TriangleNormals tn;
        if (!normals.empty()) {
          tn = {{normals[c[0]], normals[c[1]], normals[c[2]]}};
          if (tn.n[0] == Vec3f{0, 0, 0} || tn.n[1] == Vec3f{0, 0, 0} || tn.n[2] == Vec3f{0, 0, 0}) tn = TriangleNormals{};
        }
        m_scene.normals.push_back(tn);
      }
      if (keep_uvs) {
        TriangleUVs tu;
        if (!uvs.empty()) tu = {{uvs[c[0]], uvs[c[1]], uvs[c[2]]}};
        m_scene.uvs.push_back(tu);
      }
    }
  }

  void add_camera(const Placed& node, const std::string& p) {
    const int index = m_model.nodes[std::size_t(node.node)].camera;
    if (std::size_t(index) >= m_model.cameras.size())
      fail(m_file, 0, p + "/camera: " + std::to_string(index) + " does not exist (" + std::to_string(m_model.cameras.size()) + " cameras)");
    const tinygltf::Camera& cam = m_model.cameras[std::size_t(index)];
    const std::string cp = json_pointer({"cameras", std::to_string(index)});
    ++m_summary.cameras;
    if (cam.type != "perspective") {
      m_warnings.once("camera " + cam.type, cp + "/type", "'" + cam.type + "' cameras are not modelled: skipped");
      return;
    }
    const double yfov = cam.perspective.yfov;
    if (!(yfov > 0 && yfov < 3.14159265358979)) fail(m_file, 0, cp + "/perspective/yfov: must be in (0, pi) radians");
    const double aspect = cam.perspective.aspectRatio;
    if (!(aspect >= 0) || !std::isfinite(aspect)) fail(m_file, 0, cp + "/perspective/aspectRatio: must be a finite number > 0");
    // The camera looks down its node's -Z, +Y up, from its node's origin.
    const Vec3d eye = node.world.point({0, 0, 0});
    const Vec3d forward = node.world.vector({0, 0, -1}), up = node.world.vector({0, 1, 0});
    if (!(length(forward) > 0) || !(length(cross(forward, up)) > 0))
      fail(m_file, 0, p + ": the camera's transform is degenerate (scale 0)");
    for (double c : {eye.x, eye.y, eye.z})
      if (!(std::abs(c) <= kMaxCoordinate))
        fail(m_file, 0, p + ": the camera lies at " + std::to_string(c) + ", past Kappa's coordinate limit of 1e12");
    NamedCamera named;
    named.name = cam.name.empty() ? "camera " + std::to_string(index) : cam.name;
    named.file_index = index;
    named.spec.eye = Vec3f(eye);
    // A point ahead far enough that single precision tells it from the eye.
    const double ahead = std::max({1.0, std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
    named.spec.look_at = Vec3f(eye + normalize(forward) * ahead);
    named.spec.up = Vec3f(normalize(up));
    const Vec3f view = named.spec.look_at - named.spec.eye;
    if (!(length(cross(view, named.spec.up)) > 0))
      fail(m_file, 0, p + ": the camera's transform is degenerate (its view and up directions are parallel)");
    named.spec.vfov_deg = float(yfov * 180.0 / 3.14159265358979323846);
    named.aspect = float(aspect);
    m_scene.cameras.push_back(std::move(named));
  }

  void add_light(const Placed& node, const tinygltf::Node& n, const std::string& p) {
    const auto ext = n.extensions.find("KHR_lights_punctual");
    if (ext == n.extensions.end()) return;
    const std::string ep = p + "/extensions/KHR_lights_punctual/light";
    if (!ext->second.Has("light") || !ext->second.Get("light").IsInt())
      fail(m_file, 0, ep + ": must be the index of a light");
    const int index = ext->second.Get("light").GetNumberAsInt();
    if (index < 0 || std::size_t(index) >= m_model.lights.size())
      fail(m_file, 0, ep + ": light " + std::to_string(index) + " does not exist (" + std::to_string(m_model.lights.size()) + " lights)");
    const tinygltf::Light& l = m_model.lights[std::size_t(index)];
    const std::string lp = json_pointer({"extensions", "KHR_lights_punctual", "lights", std::to_string(index)});
    ++m_summary.lights;
    PunctualLight light;
    light.name = l.name.empty() ? "light " + std::to_string(index) : l.name;
    Vec3d colour{1, 1, 1};
    if (!l.color.empty()) {
      if (l.color.size() != 3) fail(m_file, 0, lp + "/color: must be 3 numbers");
      colour = {l.color[0], l.color[1], l.color[2]};
      for (double c : {colour.x, colour.y, colour.z})
        if (!(c >= 0) || !std::isfinite(c)) fail(m_file, 0, lp + "/color: must be finite and non-negative");
    }
    if (!(l.intensity >= 0) || !std::isfinite(l.intensity)) fail(m_file, 0, lp + "/intensity: must be finite and non-negative");
    light.intensity = Vec3f(colour * (l.intensity / kLumensPerWatt));
    if (!std::isfinite(light.intensity.x + light.intensity.y + light.intensity.z) ||
        !(std::max({light.intensity.x, light.intensity.y, light.intensity.z}) < 1e30f))
      fail(m_file, 0, lp + ": color x intensity does not fit single precision (Kappa's radiance)");
    if (l.range != 0) {
      light.range = float(l.range);
      m_warnings.once("light range", lp + "/range", "a light's range is not modelled: it lights without a cut-off");
    }
    const Vec3d position = node.world.point({0, 0, 0});
    for (double c : {position.x, position.y, position.z})
      if (!(std::abs(c) <= kMaxCoordinate))
        fail(m_file, 0, p + ": the light lies at " + std::to_string(c) + ", past Kappa's coordinate limit of 1e12");
    light.position = Vec3f(position);
    const Vec3d d = node.world.vector({0, 0, -1});
    if (l.type != "point") {
      if (!(length(d) > 0)) fail(m_file, 0, p + ": the light's transform is degenerate (scale 0)");
      light.direction = Vec3f(normalize(d));
    }
    if (l.type == "point") {
      light.type = PunctualLight::Type::point;
    } else if (l.type == "directional") {
      light.type = PunctualLight::Type::directional;
    } else if (l.type == "spot") {
      light.type = PunctualLight::Type::spot;
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(inner >= 0) || !(outer > inner) || !(outer <= 3.14159265358979323846 / 2))
        fail(m_file, 0, lp + "/spot: needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
      light.cos_inner = float(std::cos(inner));
      light.cos_outer = float(std::cos(outer));
    } else {
      fail(m_file, 0, lp + "/type: '" + l.type + "' is not point, spot or directional");
    }
    m_scene.punctual_lights.push_back(std::move(light));
  }

  GltfFile& m_gltf;
  const tinygltf::Model& m_model;
  const std::filesystem::path& m_file;
  Scene& m_scene;
  GltfWarnings m_warnings;
  GltfMaterials m_materials;
  GltfSummary m_summary;
  std::size_t m_zero_area = 0, m_too_small = 0;
};

}  // namespace

void load_gltf(const std::filesystem::path& file, Scene& scene, Warnings& warnings) {
  GltfFile gltf = read_gltf(file, warnings);
  scene.inputs.push_back(file);
  for (const auto& f : gltf.external_files)
    if (std::find(scene.inputs.begin(), scene.inputs.end(), f) == scene.inputs.end()) scene.inputs.push_back(f);
  GltfLoader(gltf, scene, warnings).load();
}

}  // namespace kappa
