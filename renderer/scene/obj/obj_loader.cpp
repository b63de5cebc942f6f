#include "renderer/scene/obj/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <istream>
#include <sstream>
#include <streambuf>

#include "renderer/scene/obj/mtl_material.h"
#include "renderer/scene/obj/mtl_scan.h"
#include "renderer/scene/obj/obj_limits.h"
#include "renderer/scene/obj/obj_scan.h"

namespace kappa {
namespace {

/// A polygon is convex when every turn has the same sign about its normal.
bool is_convex(const ObjPolygon& poly, const std::vector<Vec3d>& positions) {
  const std::size_t n = poly.vertices.size();
  Vec3d normal;  // Newell's method: robust for non-planar and concave polygons
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& a = positions[poly.vertices[i]];
    const Vec3d& b = positions[poly.vertices[(i + 1) % n]];
    normal += Vec3d{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  bool positive = false, negative = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d& a = positions[poly.vertices[i]];
    const Vec3d& b = positions[poly.vertices[(i + 1) % n]];
    const Vec3d& c = positions[poly.vertices[(i + 2) % n]];
    const double turn = dot(cross(b - a, c - b), normal);
    positive |= turn > 0;
    negative |= turn < 0;
  }
  return !(positive && negative);
}

Vec3f checked_colour(const tinyobj::real_t c[3], const std::string& material, const char* key, float hi,
                     const std::filesystem::path& obj, Warnings& warnings) {
  Vec3f v{float(c[0]), float(c[1]), float(c[2])};
  Vec3f fixed = v;
  for (float* x : {&fixed.x, &fixed.y, &fixed.z}) {
    if (!std::isfinite(*x) || *x < 0.0f) *x = 0.0f;
    if (*x > hi) *x = hi;
  }
  if (!(fixed == v)) {
    std::ostringstream msg;
    msg << "material '" << material << "': " << key << " " << v.x << " " << v.y << " " << v.z
        << " is outside its valid range, clamped to " << fixed.x << " " << fixed.y << " " << fixed.z;
    warnings.push_back(located(obj, 0, msg.str()));
  }
  return fixed;
}

std::uint32_t default_material(Scene& scene) {
  static const char* kName = "(default grey)";
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == kName) return std::uint32_t(i);
  scene.materials.push_back(Material{kName, {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  return std::uint32_t(scene.materials.size() - 1);
}

/// Serves the checked text to tinyobjloader a megabyte at a time, counting
/// each chunk as parsed: the parse's progress without touching its code.
class CountingTextBuffer : public std::streambuf {
 public:
  CountingTextBuffer(const std::string& text, TaskProgress* progress) : m_text(text), m_progress(progress) {}

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (m_next >= m_text.size()) return traits_type::eof();
    const std::size_t n = std::min(kChunk, m_text.size() - m_next);
    // std::streambuf wants char*; tinyobjloader only reads (no putback).
    char* begin = const_cast<char*>(m_text.data()) + m_next;
    setg(begin, begin, begin + n);
    m_next += n;
    advance(m_progress, n);
    return traits_type::to_int_type(*gptr());
  }

 private:
  static constexpr std::size_t kChunk = std::size_t(1) << 20;
  const std::string& m_text;
  TaskProgress* m_progress;
  std::size_t m_next = 0;
};

/// Hands tinyobjloader the text of the material libraries already read and
/// checked: all of them, in the order the OBJ names them, the first time it
/// asks for one. tinyobjloader reads only the first library of a `mtllib`
/// line; Blender's importer, whose reading Kappa follows, reads every one.
class CheckedMaterialReader : public tinyobj::MaterialReader {
 public:
  CheckedMaterialReader(const std::vector<std::string>& order, const std::map<std::string, std::string>& libraries)
      : m_order(order), m_libraries(libraries) {}
  bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* ids,
                  std::string* warn, std::string* err) override {
    if (m_served) return true;
    for (const std::string& name : m_order) {
      const auto it = m_libraries.find(name);
      if (it == m_libraries.end() || !m_read.insert(name).second) continue;  // missing (warned about) or read
      std::istringstream text(it->second);
      tinyobj::LoadMtl(ids, materials, &text, warn, err);
      m_served = true;
    }
    return m_served;
  }

 private:
  const std::vector<std::string>& m_order;
  const std::map<std::string, std::string>& m_libraries;
  std::set<std::string> m_read;
  bool m_served = false;
};

}  // namespace

void load_obj(const std::filesystem::path& obj, Scene& scene, Warnings& warnings, TaskProgress* progress) {
  const ObjScan scan = scan_obj(obj, warnings, progress);
  const std::filesystem::path dir = obj.parent_path();
  scene.inputs.push_back(obj);

  // Material libraries pass the same input check as every file, and
  // tinyobjloader gets their checked text, never a path to open itself.
  std::map<std::string, std::string> libraries;
  // Each material's statements with their lines, by name: the first
  // definition in the libraries' order (what tinyobjloader also keeps).
  std::map<std::string, std::pair<MtlRecord, std::filesystem::path>> records;
  for (const auto& lib : scan.mtllibs) {
    if (libraries.count(lib)) continue;  // named again: read once
    std::error_code ec;
    if (!std::filesystem::exists(dir / lib, ec)) {
      warnings.push_back(located(obj, 0, "material library '" + lib + "' not found; its materials use the default grey"));
      continue;
    }
    libraries[lib] = scan_mtl(dir / lib, read_input_file(dir / lib, "a material library (MTL)", InputContent::text));
    scene.inputs.push_back(dir / lib);
    for (MtlRecord& r : read_mtl_records(dir / lib, libraries[lib], warnings)) {
      const std::string name = r.name;
      const std::size_t line = r.line;
      const auto [first, inserted] = records.emplace(name, std::pair{std::move(r), dir / lib});
      if (!inserted)
        warnings.push_back(located(dir / lib, line, "material '" + name + "' is defined again; its first definition, at " +
                                                        first->second.second.string() + ":" +
                                                        std::to_string(first->second.first.line) + ", is used"));
    }
  }
  for (const ObjPolygon& poly : scan.polygons) {
    std::vector<std::size_t> distinct = poly.vertices;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (distinct.size() < poly.vertices.size()) {
      warnings.push_back(located(obj, poly.line,
                                 "polygon of " + std::to_string(poly.vertices.size()) + " vertex references has only " +
                                     std::to_string(distinct.size()) + " distinct vertices"));
    }
    if (!is_convex(poly, scan.positions))
      warnings.push_back(located(obj, poly.line,
                                 "concave polygon with " + std::to_string(poly.vertices.size()) +
                                     " vertices: its triangulation may not follow the outline"));
  }

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string tiny_warn, tiny_err;
  begin_phase(progress, "parsing " + obj.filename().string(), scan.text.size());
  CountingTextBuffer text_buffer(scan.text, progress);
  std::istream text(&text_buffer);
  CheckedMaterialReader mtl_reader(scan.mtllibs, libraries);
  // Problems tinyobjloader warns about were already reported by the scan, in
  // Kappa's words and with line numbers, so its own warning text is not repeated.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &tiny_warn, &tiny_err, &text, &mtl_reader, true, false)) {
    std::string first = tiny_err.substr(0, tiny_err.find('\n'));
    fail(obj, 0, "tinyobjloader: " + (first.empty() ? std::string("cannot parse") : first));
  }

  // Materials: referenced by index, offset by what earlier meshes added.
  const auto base = static_cast<std::uint32_t>(scene.materials.size());
  std::set<std::string> defined;
  std::map<std::filesystem::path, std::set<std::string>> warned;  // per MTL file, the kinds warned about
  for (const tinyobj::material_t& m : materials) {
    // tinyobjloader gives the names and their order (the faces' material
    // ids); the mapping reads the statements themselves (mtl_material.h).
    const auto r = records.find(m.name);
    Material mat;
    if (r != records.end()) {
      mat = material_from_mtl(r->second.first, r->second.second, warnings, warned[r->second.second], scene.texture_maps);
      for (std::int32_t k : mat.maps)
        if (k >= 0) scene.inputs.push_back(scene.texture_maps[std::size_t(k)].file);
    } else {
      mat.name = m.name;
      mat.albedo = checked_colour(m.diffuse, m.name, "Kd", 1.0f, obj, warnings);
      mat.emission = checked_colour(m.emission, m.name, "Ke", 1e30f, obj, warnings);
    }
    scene.materials.push_back(mat);
    defined.insert(m.name);
  }
  for (const auto& use : scan.material_uses) {
    if (!defined.count(use.name))
      warnings.push_back(located(obj, use.line, "material '" + use.name + "' is not defined; using the default grey"));
  }

  const std::size_t vertex_count = attrib.vertices.size() / 3;
  auto position = [&](int index) {
    return Vec3f{attrib.vertices[3 * std::size_t(index)], attrib.vertices[3 * std::size_t(index) + 1],
                 attrib.vertices[3 * std::size_t(index) + 2]};
  };
  // Vertex normals and texture coordinates, kept per triangle once the file
  // has any (a scene without them keeps no array): what the shading point
  // interpolates. A reference tinyobjloader could not resolve (-1, or past
  // the end) is none.
  const std::size_t normal_count = attrib.normals.size() / 3, uv_count = attrib.texcoords.size() / 2;
  auto normal = [&](int index, Vec3f& out) {
    if (index < 0 || std::size_t(index) >= normal_count) return false;
    const Vec3f n{attrib.normals[3 * std::size_t(index)], attrib.normals[3 * std::size_t(index) + 1],
                  attrib.normals[3 * std::size_t(index) + 2]};
    const float len = length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return false;
    out = n / len;
    return true;
  };
  auto uv = [&](int index, Vec2f& out) {
    if (index < 0 || std::size_t(index) >= uv_count) return false;
    out = {attrib.texcoords[2 * std::size_t(index)], attrib.texcoords[2 * std::size_t(index) + 1]};
    return std::isfinite(out.u) && std::isfinite(out.v);
  };
  const bool keep_normals = normal_count > 0, keep_uvs = uv_count > 0;
  // Meshes before this one without the attribute get the "none" value.
  if (keep_normals) scene.normals.resize(scene.triangles.size());
  if (keep_uvs) scene.uvs.resize(scene.triangles.size());
  std::size_t zero_area = 0, too_small = 0, before = scene.triangles.size();
  // Triangles of a smoothing group (`s N`, N > 0) that give no normals of
  // their own: smooth-shaded with the normals of their group's faces
  // averaged at each shared vertex (by area), as Blender shades them.
  struct Smoothed {
    std::size_t triangle;
    int vertex[3];
    unsigned group;
  };
  std::vector<Smoothed> smoothed;
  for (const tinyobj::shape_t& shape : shapes) {
    const auto& idx = shape.mesh.indices;
    std::size_t offset = 0;
    for (std::size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
      const std::size_t fv = shape.mesh.num_face_vertices[face];
      const std::size_t f = offset;
      offset += fv;
      if (fv != 3 || offset > idx.size()) continue;  // triangulation leaves only triangles
      const int a = idx[f].vertex_index, b = idx[f + 1].vertex_index, c = idx[f + 2].vertex_index;
      if (a < 0 || b < 0 || c < 0 || std::size_t(std::max({a, b, c})) >= vertex_count)
        fail(obj, 0, "face index out of range after triangulation");  // the scan makes this unreachable
      const Triangle tri{position(a), position(b), position(c)};
      if (!(double_area(tri) > 0.0)) {
        ++zero_area;
        continue;
      }
      const double longest = std::max({length(Vec3d(tri.v1) - Vec3d(tri.v0)), length(Vec3d(tri.v2) - Vec3d(tri.v1)),
                                       length(Vec3d(tri.v0) - Vec3d(tri.v2))});
      if (longest < kMinTriangleSize) {
        ++too_small;
        continue;
      }
      const int mat = face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
      scene.triangles.push_back(tri);
      bool given = false;
      if (keep_normals) {
        TriangleNormals n;
        given = normal(idx[f].normal_index, n.n[0]) && normal(idx[f + 1].normal_index, n.n[1]) &&
                normal(idx[f + 2].normal_index, n.n[2]);
        if (!given) n = TriangleNormals{};  // all three, or none
        scene.normals.push_back(n);
      }
      const unsigned group = face < shape.mesh.smoothing_group_ids.size() ? shape.mesh.smoothing_group_ids[face] : 0;
      if (!given && group != 0) smoothed.push_back({scene.triangles.size() - 1, {a, b, c}, group});
      if (keep_uvs) {
        TriangleUVs t;
        if (!(uv(idx[f].texcoord_index, t.uv[0]) && uv(idx[f + 1].texcoord_index, t.uv[1]) &&
              uv(idx[f + 2].texcoord_index, t.uv[2])))
          t = TriangleUVs{};
        scene.uvs.push_back(t);
      }
      scene.material_of.push_back(mat >= 0 && std::size_t(mat) < materials.size() ? base + std::uint32_t(mat)
                                                                                   : default_material(scene));
    }
  }
  if (!smoothed.empty()) {
    std::map<std::pair<int, unsigned>, Vec3d> sums;  // (vertex, group) -> area-weighted normal
    for (const Smoothed& t : smoothed) {
      const Triangle& tri = scene.triangles[t.triangle];
      const Vec3d n = cross(Vec3d(tri.v1) - Vec3d(tri.v0), Vec3d(tri.v2) - Vec3d(tri.v0));
      for (int v : t.vertex) sums[{v, t.group}] += n;
    }
    scene.normals.resize(scene.triangles.size());
    for (const Smoothed& t : smoothed) {
      TriangleNormals n;
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const Vec3d& sum = sums[{t.vertex[k], t.group}];
        const double len = length(sum);
        ok = ok && len > 0 && std::isfinite(len);
        if (ok) n.n[k] = Vec3f(sum / len);
      }
      scene.normals[t.triangle] = ok ? n : TriangleNormals{};
    }
  }
  // A mesh after one with normals or UVs, without its own, gets "none".
  if (!scene.normals.empty()) scene.normals.resize(scene.triangles.size());
  if (!scene.uvs.empty()) scene.uvs.resize(scene.triangles.size());
  if (zero_area > 0)
    warnings.push_back(located(obj, 0, std::to_string(zero_area) + " zero-area triangles dropped"));
  if (too_small > 0)
    warnings.push_back(located(obj, 0, std::to_string(too_small) +
                                           " triangles smaller than 1e-15 across dropped: single-precision "
                                           "intersection cannot hit them"));
  if (scene.triangles.size() == before)
    warnings.push_back(located(obj, 0,
                               "no triangles (" + std::to_string(scan.positions.size()) + " vertices, " +
                                   std::to_string(scan.face_count) + " faces)"));
}

}  // namespace kappa
