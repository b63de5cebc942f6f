#include "renderer/scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "renderer/scene/json_scan.h"
#include "renderer/scene/mesh_file.h"
#include "renderer/scene/obj/obj_limits.h"
#include "renderer/scene/scene_images.h"

namespace kappa {
namespace {

using nlohmann::json;

constexpr int kMaxFilmSide = 1 << 15;

json parse_json(const std::filesystem::path& file, const std::string& text) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail(file, 0, "empty scene file");
  try {
    json root = json::parse(text);
    check_json_keys_and_numbers(file, text);  // what the parser accepts silently
    return root;
  } catch (const json::out_of_range&) {
    // A number that overflows a double: the parser says so without a
    // position; the scan finds its line.
    check_json_keys_and_numbers(file, text);
    fail(file, 0, "a number does not fit a double");
  } catch (const json::parse_error& e) {
    // e.byte is one past the offending character.
    const std::string at = line_and_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    const std::size_t colon = what.find(": ", what.find("column"));
    if (colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(file.string() + ":" + at + ": JSON syntax error: " + what);
  }
}

class FieldReader {
 public:
  explicit FieldReader(const std::filesystem::path& file) : m_file(file) {}

  [[noreturn]] void bad(const std::string& field, const std::string& expected) const {
    fail(m_file, 0, "field '" + field + "' must be " + expected);
  }

  Vec3f vec3(const json& j, const std::string& field, bool non_negative = false) const {
    const char* expected = non_negative ? "an array of 3 finite non-negative numbers" : "an array of 3 finite numbers";
    if (!j.is_array() || j.size() != 3) bad(field, expected);
    double v[3];
    for (int i = 0; i < 3; ++i) {
      if (!j[i].is_number()) bad(field, expected);
      v[i] = j[i].get<double>();
      if (!std::isfinite(v[i]) || (non_negative && v[i] < 0)) bad(field, expected);
      if (std::abs(v[i]) > kMaxCoordinate) {  // finite, but past what single-precision intersection takes
        char limit[32];
        std::snprintf(limit, sizeof limit, "%.3g", kMaxCoordinate);
        fail(m_file, 0, "field '" + field + "': " + j[i].dump() + " exceeds Kappa's limit of " + limit);
      }
    }
    return {float(v[0]), float(v[1]), float(v[2])};
  }

  double number(const json& j, const std::string& field, double lo, double hi, const std::string& expected) const {
    if (!j.is_number()) bad(field, expected);
    const double v = j.get<double>();
    if (!(v > lo && v < hi)) bad(field, expected);
    return v;
  }

  int film_side(const json& j, const std::string& field) const {
    const std::string expected = "a positive integer of at most " + std::to_string(kMaxFilmSide);
    if (!j.is_number_integer()) bad(field, expected);
    const auto v = j.get<long long>();
    if (v < 1 || v > kMaxFilmSide) bad(field, expected);
    return int(v);
  }

  void unknown_keys(const json& obj, std::initializer_list<const char*> known, const std::string& prefix,
                    Warnings& warnings) const {
    for (const auto& [key, value] : obj.items()) {
      bool ok = false;
      for (const char* k : known) ok |= key == k;
      if (!ok) warnings.push_back(located(m_file, 0, "unknown field '" + prefix + key + "' ignored"));
    }
  }

 private:
  const std::filesystem::path& m_file;
};

void check_camera(const std::filesystem::path& file, const CameraSpec& c) {
  const Vec3d forward = Vec3d(c.look_at) - Vec3d(c.eye);
  if (!(length(forward) > 0)) fail(file, 0, "camera: 'eye' and 'look_at' are the same point");
  if (!(length(Vec3d(c.up)) > 0)) fail(file, 0, "camera: 'up' is the zero vector");
  const Vec3d right = cross(normalize(forward), normalize(Vec3d(c.up)));
  if (!(length(right) > 1e-6)) fail(file, 0, "camera: 'up' is parallel to the viewing direction");
}

/// A film of `aspect` (width / height) whose longer side is the default's.
void film_of_aspect(Scene& scene, float aspect) {
  if (!(aspect > 0)) return;
  const int side = std::max(scene.width, scene.height);
  if (aspect >= 1) {
    scene.width = side;
    scene.height = std::clamp(int(std::lround(double(side) / double(aspect))), 1, kMaxFilmSide);
  } else {
    scene.height = side;
    scene.width = std::clamp(int(std::lround(double(side) * double(aspect))), 1, kMaxFilmSide);
  }
}

/// Refuses a file name no file can have: one holding a NUL (JSON's \u0000),
/// which the system would cut there and open another file.
void refuse_unnameable(const std::filesystem::path& file, const std::string& what, const std::string& name) {
  if (name.find('\0') != std::string::npos)
    fail(file, 0, what + " name '" + printable_line(name.substr(0, name.find('\0'))) +
                      "\\u0000...' holds a NUL character, which no file name can");
}

Scene load_json_scene(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress) {
  const std::string text = read_input_file(file, "a scene file", InputContent::utf8);
  const json root = parse_json(file, text);
  const FieldReader field(file);
  if (!root.is_object()) fail(file, 0, "the scene must be a JSON object");
  field.unknown_keys(root, {"meshes", "camera", "environment", "environment_rotation_deg", "film"}, "", warnings);

  Scene scene;
  scene.source = file;
  scene.inputs.push_back(file);
  scene.name = scene_name(file);

  if (!root.contains("meshes")) fail(file, 0, "missing field 'meshes' (a list of OBJ or glTF files)");
  const json& meshes = root["meshes"];
  if (!meshes.is_array() || meshes.empty()) field.bad("meshes", "a non-empty array of OBJ or glTF file names");
  std::vector<std::filesystem::path> mesh_paths;
  for (const json& m : meshes) {
    if (!m.is_string() || m.get<std::string>().empty()) field.bad("meshes", "a non-empty array of OBJ or glTF file names");
    refuse_unnameable(file, "mesh", m.get<std::string>());
    mesh_paths.push_back(file.parent_path() / m.get<std::string>());
  }

  bool has_camera = false;
  if (root.contains("camera")) {
    const json& cam = root["camera"];
    if (!cam.is_object()) field.bad("camera", "an object {eye, look_at, up, vfov_deg}");
    field.unknown_keys(cam, {"eye", "look_at", "up", "vfov_deg"}, "camera.", warnings);
    for (const char* k : {"eye", "look_at", "up", "vfov_deg"})
      if (!cam.contains(k)) fail(file, 0, std::string("missing field 'camera.") + k + "'");
    scene.camera.eye = field.vec3(cam["eye"], "camera.eye");
    scene.camera.look_at = field.vec3(cam["look_at"], "camera.look_at");
    scene.camera.up = field.vec3(cam["up"], "camera.up");
    check_camera(file, scene.camera);
    scene.camera.vfov_deg =
        float(field.number(cam["vfov_deg"], "camera.vfov_deg", 0.0, 180.0, "a number of degrees in (0, 180)"));
    has_camera = true;
  }
  if (root.contains("environment")) {
    const json& env = root["environment"];
    if (env.is_string()) {
      // A latitude-longitude image (renderer/render/environment_map.h), read
      // by load_scene_images; the constant is its mean until then.
      if (env.get<std::string>().empty()) field.bad("environment", "[r, g, b] or an image file name");
      refuse_unnameable(file, "environment image", env.get<std::string>());
      scene.environment_file = file.parent_path() / env.get<std::string>();
      std::error_code ec;
      if (!std::filesystem::is_regular_file(scene.environment_file, ec))
        fail(file, 0, "environment image '" + scene.environment_file.string() + "' not found or not a regular file");
      scene.inputs.push_back(scene.environment_file);
    } else {
      scene.environment = field.vec3(env, "environment", true);
    }
  }
  if (root.contains("environment_rotation_deg")) {
    scene.environment_rotation_deg = float(field.number(root["environment_rotation_deg"], "environment_rotation_deg",
                                                        -360.0, 360.0, "a number of degrees in [-360, 360]"));
    if (scene.environment_file.empty())
      warnings.push_back(located(file, 0, "environment_rotation_deg ignored: the environment is not an image"));
  }
  const bool has_film = root.contains("film");
  scene.film_given = has_film;
  if (has_film) {
    const json& film = root["film"];
    if (!film.is_object()) field.bad("film", "an object {width, height}");
    field.unknown_keys(film, {"width", "height"}, "film.", warnings);
    if (film.contains("width")) scene.width = field.film_side(film["width"], "film.width");
    if (film.contains("height")) scene.height = field.film_side(film["height"], "film.height");
  }

  // A mesh listed twice is loaded twice: its emitters would count double.
  for (std::size_t a = 0; a < mesh_paths.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      std::error_code ec;
      if (mesh_paths[a] == mesh_paths[b] || std::filesystem::equivalent(mesh_paths[a], mesh_paths[b], ec)) {
        warnings.push_back(located(file, 0, "mesh '" + mesh_paths[a].string() +
                                                "' is listed twice: its triangles, and any emitters, count twice"));
        break;
      }
    }
  for (const auto& mesh : mesh_paths) {
    std::error_code ec;
    // What else the path may be (a FIFO, a device) is refused by the OBJ
    // reader's input check, naming the mesh.
    // What the path is (missing, a loop of links, behind a folder that
    // cannot be searched, a FIFO) is said naming the scene file and the mesh.
    try {
      check_input_file(mesh, "a mesh file");
    } catch (const InputError& e) {
      std::string why = e.what();
      if (why.rfind(mesh.string() + ": ", 0) == 0) why.erase(0, mesh.string().size() + 2);
      fail(file, 0, "mesh '" + mesh.string() + (why == "file not found" ? "' not found" : "': " + why));
    }
    load_mesh_file(mesh, scene, warnings, progress);
  }
  if (has_camera) {
    // The scene file's camera wins; --camera cannot pick a glTF one then.
    if (!scene.cameras.empty())
      warnings.push_back(located(file, 0, "its 'camera' is used, not the " + std::to_string(scene.cameras.size()) +
                                              " camera(s) of its glTF files"));
    scene.cameras.clear();
  } else if (!scene.cameras.empty()) {
    // No camera of its own: its glTF files' first, as for a bare glTF file.
    scene.camera = scene.cameras.front().spec;
    scene.camera_index = 0;
    if (!has_film) film_of_aspect(scene, scene.cameras.front().aspect);
  } else {
    scene.camera = framing_camera(scene.bounds(), 39.3077f, float(scene.width) / float(scene.height));
    scene.camera_framed = true;
  }
  return scene;
}

/// A bare glTF file: lit as a bare OBJ is (environment 1) besides its own
/// lights; its first perspective camera, whose aspect sets the film, or the
/// framing camera.
Scene load_gltf_scene(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress) {
  Scene scene;
  scene.source = file;
  scene.name = scene_name(file);
  scene.environment = {1, 1, 1};
  load_mesh_file(file, scene, warnings, progress);
  if (!scene.cameras.empty()) {
    scene.camera = scene.cameras.front().spec;
    scene.camera_index = 0;
    film_of_aspect(scene, scene.cameras.front().aspect);
  } else if (!scene.triangles.empty()) {
    scene.camera = framing_camera(scene.bounds(), 39.3077f, float(scene.width) / float(scene.height));
    scene.camera_framed = true;
  }
  return scene;
}

Scene load_obj_scene(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress) {
  Scene scene;
  scene.source = file;
  scene.name = scene_name(file);
  scene.environment = {1, 1, 1};
  load_mesh_file(file, scene, warnings, progress);
  if (!scene.triangles.empty()) {
    scene.camera = framing_camera(scene.bounds(), 39.3077f, float(scene.width) / float(scene.height));
    scene.camera_framed = true;
  }
  return scene;
}

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

void apply_view(Scene& scene, const std::string& camera, int width, int height) {
  if (!camera.empty()) {
    std::string names;
    int index = -1;
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
      names += std::string(names.empty() ? "" : ", ") + std::to_string(scene.cameras[i].file_index) + " '" +
               scene.cameras[i].name + "'";
      if (index < 0 && scene.cameras[i].name == camera) index = int(i);
    }
    if (index < 0 && camera.find_first_not_of("0123456789") == std::string::npos && camera.size() < 10)
      for (std::size_t i = 0; i < scene.cameras.size(); ++i)
        if (scene.cameras[i].file_index == std::stoi(camera)) index = int(i);
    if (scene.cameras.empty())
      throw InputError("--camera " + camera + ": the scene defines no cameras (a glTF file given as the scene does)");
    if (index < 0)
      throw InputError("--camera " + camera + ": no perspective camera of that name or index (the scene's: " + names + ")");
    scene.camera = scene.cameras[std::size_t(index)].spec;
    scene.camera_index = index;
    scene.camera_framed = false;
    if (!scene.film_given) {
      scene.width = scene.height = std::max(scene.width, scene.height);
      film_of_aspect(scene, scene.cameras[std::size_t(index)].aspect);
    }
  }
  const float aspect =
      scene.camera_index >= 0 && !scene.film_given ? scene.cameras[std::size_t(scene.camera_index)].aspect : 0.0f;
  if (width > 0) scene.width = width;
  if (height > 0) scene.height = height;
  if (aspect > 0 && (width > 0) != (height > 0)) {
    // One side given: the other from the camera's aspect.
    if (width > 0) scene.height = std::clamp(int(std::lround(double(width) / double(aspect))), 1, kMaxFilmSide);
    else scene.width = std::clamp(int(std::lround(double(height) * double(aspect))), 1, kMaxFilmSide);
  }
  if (scene.camera_framed)  // frame again for the film's final aspect ratio
    scene.camera = framing_camera(scene.bounds(), scene.camera.vfov_deg, float(scene.width) / float(scene.height));
}

std::string scene_name(const std::filesystem::path& file) {
  const std::string stem = file.stem().string();
  if (stem == "scene") {
    const std::string dir = std::filesystem::absolute(file).parent_path().filename().string();
    if (!dir.empty()) return dir;
  }
  return stem.empty() ? std::string("scene") : stem;
}

Scene load_scene(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress) {
  const auto start = std::chrono::steady_clock::now();
  Warnings pending;  // printed only if the scene loads: a refusal is one line
  check_input_file(file, "a scene file");
  const std::string ext = lower_extension(file);
  Scene scene;
  if (ext == ".json") {
    scene = load_json_scene(file, pending, progress);
  } else if (ext == ".obj") {
    scene = load_obj_scene(file, pending, progress);
  } else if (ext == ".gltf" || ext == ".glb") {
    scene = load_gltf_scene(file, pending, progress);
  } else {
    fail(file, 0, "unsupported scene format '" + ext + "' (expected .json, .obj, .gltf or .glb)");
  }
  if (scene.triangles.empty()) fail(file, 0, "the scene has no triangles: nothing to render");
  if (scene.triangles.size() >= std::size_t(kNoTriangle))
    fail(file, 0, "more than 2^32 - 1 triangles; Kappa uses 32-bit triangle ids");
  // Texture maps and the environment image: only a scene that names one
  // loads the OpenImageIO module.
  load_scene_images(scene, pending);
  warnings.insert(warnings.end(), pending.begin(), pending.end());
  scene.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return scene;
}

}  // namespace kappa
