#include "renderer/scene/gltf/gltf_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "renderer/scene/json_scan.h"

namespace kappa {
namespace {

using nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

/// The extensions Kappa reads; a file that requires another is refused.
const std::set<std::string>& read_extensions() {
  static const std::set<std::string> known = {
      "KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
      "KHR_materials_specular", "KHR_lights_punctual"};
  return known;
}

std::uint32_t le32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + std::size_t(i)]);
  return v;
}

std::string hex32(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", v);
  return text;
}

/// The JSON chunk and the BIN chunk (empty without one) of a GLB container.
struct GlbChunks {
  std::string json;
  std::string bin;
  bool has_bin = false;
};

GlbChunks split_glb(const std::filesystem::path& file, const std::string& bytes, Warnings& warnings) {
  if (bytes.size() < 20) fail(file, 0, "binary glTF: " + std::to_string(bytes.size()) + " bytes, shorter than a GLB header and chunk header (20)");
  const std::uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
  if (version != 2) fail(file, 0, "binary glTF: container version " + std::to_string(version) + ", not 2");
  if (length != bytes.size())
    fail(file, 0, "binary glTF: its header gives a length of " + std::to_string(length) + " bytes, the file has " +
                      std::to_string(bytes.size()));
  GlbChunks chunks;
  std::size_t at = 12, unknown = 0;
  for (int index = 0; at < bytes.size(); ++index) {
    if (bytes.size() - at < 8) fail(file, 0, "binary glTF: chunk " + std::to_string(index) + " header cut off at byte " + std::to_string(at));
    const std::uint32_t size = le32(bytes, at), type = le32(bytes, at + 4);
    at += 8;
    if (size > bytes.size() - at)
      fail(file, 0, "binary glTF: chunk " + std::to_string(index) + " gives a length of " + std::to_string(size) +
                        " bytes, past the file's end (" + std::to_string(bytes.size() - at) + " left)");
    if (size % 4 != 0)
      fail(file, 0, "binary glTF: chunk " + std::to_string(index) + "'s length " + std::to_string(size) +
                        " is not a multiple of 4");
    if (index == 0) {
      if (type != kChunkJson)
        fail(file, 0, "binary glTF: the first chunk's type is " + hex32(type) + ", not JSON (0x4E4F534A)");
      chunks.json = bytes.substr(at, size);
    } else if (index == 1 && type == kChunkBin) {
      chunks.bin = bytes.substr(at, size);
      chunks.has_bin = true;
    } else if (type == kChunkJson) {
      fail(file, 0, "binary glTF: chunk " + std::to_string(index) + " is a second JSON chunk");
    } else if (type == kChunkBin) {
      fail(file, 0, "binary glTF: chunk " + std::to_string(index) + " is a BIN chunk, which may only be the second");
    } else {
      ++unknown;
    }
    at += size;
  }
  if (unknown > 0)
    warnings.push_back(located(file, 0, "binary glTF: " + std::to_string(unknown) +
                                            " chunk(s) of unknown type ignored, as the specification says"));
  return chunks;
}

json parse_json_text(const std::filesystem::path& file, const std::string& text) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail(file, 0, "empty glTF JSON");
  // Depth first, on the text: tinygltf's parser recurses on nesting.
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxGltfJsonDepth)
        fail(file, 0, "glTF JSON nests deeper than " + std::to_string(kMaxGltfJsonDepth) + " levels at " +
                          line_and_column(text, i));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    json root = json::parse(text);
    check_json_keys_and_numbers(file, text);
    return root;
  } catch (const json::out_of_range&) {
    check_json_keys_and_numbers(file, text);
    fail(file, 0, "a number does not fit a double");
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const std::size_t colon = what.find(": ", what.find("column"));
    if (colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(file.string() + ":" + line_and_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": JSON syntax error: " + what);
  }
}

bool base64_payload(const std::string& s) {
  if (s.size() % 4 != 0) return false;
  std::size_t pad = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '=') {
      ++pad;
      continue;
    }
    if (pad > 0) return false;  // '=' only at the end
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/')) return false;
  }
  return pad <= 2;
}

/// A URI reference's scheme ("http" of "http://..."), or empty.
std::string uri_scheme(const std::string& uri) {
  std::size_t i = 0;
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return {};
  while (i < uri.size() && (std::isalnum(static_cast<unsigned char>(uri[i])) || uri[i] == '+' || uri[i] == '-' || uri[i] == '.'))
    ++i;
  return i < uri.size() && uri[i] == ':' ? uri.substr(0, i) : std::string();
}

/// What a "uri" names: a data URI (checked to be base64) or a file inside
/// the glTF file's folder (checked to be readable); refused otherwise.
struct UriTarget {
  bool data = false;
  std::filesystem::path path;  ///< a file's, resolved
};

UriTarget checked_uri(const std::filesystem::path& file, const json& value, const std::string& pointer, const char* kind) {
  if (!value.is_string()) fail(file, 0, pointer + ": must be a string");
  const std::string uri = value.get<std::string>();
  if (uri.empty()) fail(file, 0, pointer + ": empty URI");
  UriTarget target;
  if (uri.rfind("data:", 0) == 0) {
    const std::size_t comma = uri.find(',');
    const std::string header = uri.substr(0, comma);
    if (comma == std::string::npos || header.size() < 7 || header.compare(header.size() - 7, 7, ";base64") != 0)
      fail(file, 0, pointer + ": a data URI that is not base64 (Kappa reads data:...;base64,...)");
    if (!base64_payload(uri.substr(comma + 1)))
      fail(file, 0, pointer + ": the data URI's payload is not valid base64");
    // The media types tinygltf decodes (any other it would take for a file name).
    static const char* const kTypes[] = {"application/octet-stream", "application/gltf-buffer", "image/jpeg",
                                         "image/png", "image/bmp", "image/gif", "text/plain"};
    bool known = false;
    for (const char* t : kTypes) known |= header == std::string("data:") + t + ";base64";
    if (!known)
      fail(file, 0, pointer + ": data URI of media type '" + header.substr(5, header.size() - 12) +
                        "' not read (application/octet-stream, application/gltf-buffer, image/png, image/jpeg, "
                        "image/bmp, image/gif)");
    target.data = true;
    return target;
  }
  const std::string scheme = uri_scheme(uri);
  if (!scheme.empty())
    fail(file, 0, pointer + ": URI scheme '" + scheme + ":' not read (only file names relative to the glTF file, and data: URIs)");
  const std::string decoded = percent_decoded(uri);
  if (decoded.find('\0') != std::string::npos) fail(file, 0, pointer + ": the URI holds a NUL byte (%00)");
  const std::filesystem::path relative = std::filesystem::path(decoded).lexically_normal();
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory() ||
      (!relative.empty() && *relative.begin() == ".."))
    fail(file, 0, pointer + ": '" + uri + "' leaves the glTF file's folder (only files in it or below are read)");
  target.path = file.parent_path() / relative;
  try {
    check_input_file(target.path, kind);
  } catch (const InputError& e) {
    fail(file, 0, pointer + ": " + e.what());
  }
  return target;
}

/// Keys whose value is an index into one of the file's arrays (and arrays of
/// them): an integer in [0, 2^31 - 1], or tinygltf would truncate it or read
/// a negative one as "absent".
bool index_key(const std::string& key) {
  static const std::set<std::string> keys = {"scene",  "camera",   "skin",   "mesh",   "material", "indices",
                                             "bufferView", "buffer", "source", "sampler", "index", "light",
                                             "node",   "input",    "output", "skeleton", "inverseBindMatrices"};
  return keys.count(key) > 0;
}
bool index_array_key(const std::string& key) { return key == "nodes" || key == "children" || key == "joints"; }
/// Keys whose value is a byte count or offset, or a count of elements.
bool size_key(const std::string& key) {
  return key == "byteOffset" || key == "byteLength" || key == "byteStride" || key == "count" || key == "texCoord";
}

void check_index(const std::filesystem::path& file, const json& v, const std::string& pointer) {
  const double x = v.is_number() ? v.get<double>() : -1.0;
  if (!v.is_number_integer() && !(v.is_number_float() && x == std::floor(x)))
    fail(file, 0, pointer + ": must be an index (a whole number)");
  if (!(x >= 0) || x > 2147483647.0) fail(file, 0, pointer + ": index " + v.dump() + " is out of range");
}

/// Every index and size in the document is a whole number in range (extras,
/// the user's own data, aside). The depth is bounded (kMaxGltfJsonDepth).
void check_integers(const std::filesystem::path& file, const json& root) {
  struct Item {
    const json* value;
    std::string pointer;
  };
  std::vector<Item> stack = {{&root, ""}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const json& v = *item.value;
    if (v.is_object()) {
      for (const auto& [key, child] : v.items()) {
        const std::string p = item.pointer + "/" + key;
        if (key == "extras") continue;
        if (item.pointer.size() >= 11 && item.pointer.compare(item.pointer.size() - 11, 11, "/attributes") == 0) {
          check_index(file, child, p);  // attribute name -> accessor
          continue;
        }
        if (index_key(key) && child.is_number()) check_index(file, child, p);
        else if (index_key(key) && !child.is_object() && !child.is_array()) check_index(file, child, p);
        // (The top level's "nodes" is the array of nodes, a scene's its roots.)
        if (index_array_key(key) && child.is_array() && !item.pointer.empty())
          for (std::size_t k = 0; k < child.size(); ++k) check_index(file, child[k], p + "/" + std::to_string(k));
        if (size_key(key)) {
          const double x = child.is_number() ? child.get<double>() : -1.0;
          if (!child.is_number() || !(x >= 0) || x != std::floor(x) || x > 9007199254740992.0)
            fail(file, 0, p + ": must be a whole number from 0 to 2^53");
        }
        if (child.is_structured()) stack.push_back({&child, p});
      }
    } else if (v.is_array()) {
      for (std::size_t k = 0; k < v.size(); ++k)
        if (v[k].is_structured()) stack.push_back({&v[k], item.pointer + "/" + std::to_string(k)});
    }
  }
}

/// The bytes a data URI holds (its base64 payload decoded).
std::size_t data_uri_size(const std::string& uri) {
  const std::size_t comma = uri.find(',');
  const std::size_t n = uri.size() - comma - 1;
  std::size_t pad = 0;
  for (std::size_t k = uri.size(); k > comma + 1 && uri[k - 1] == '='; --k) ++pad;
  return n / 4 * 3 - pad;
}

/// Every buffer view lies inside its buffer (whose real size `sizes` gives):
/// tinygltf hands an image's buffer view to the image loader unchecked.
void check_buffer_views(const std::filesystem::path& file, const json& root, const std::vector<std::size_t>& sizes) {
  if (!root.contains("bufferViews")) return;
  const json& views = root["bufferViews"];
  if (!views.is_array()) fail(file, 0, "/bufferViews: must be an array");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string p = json_pointer({"bufferViews", std::to_string(i)});
    const json& v = views[i];
    if (!v.is_object() || !v.contains("buffer") || !v.contains("byteLength"))
      fail(file, 0, p + ": needs buffer and byteLength");
    const double b = v["buffer"].get<double>();
    if (b >= double(sizes.size())) fail(file, 0, p + "/buffer: " + v["buffer"].dump() + " does not exist");
    const std::size_t size = sizes[std::size_t(b)];
    const double offset = v.contains("byteOffset") ? v["byteOffset"].get<double>() : 0.0;
    const double length = v["byteLength"].get<double>();
    if (offset + length > double(size))
      fail(file, 0, p + ": bytes " + std::to_string(std::uint64_t(offset)) + " to " +
                        std::to_string(std::uint64_t(offset + length)) + " lie outside its buffer's " +
                        std::to_string(size) + " bytes");
    if (length > 2147483647.0) fail(file, 0, p + "/byteLength: over 2^31 - 1 bytes (tinygltf's limit for a view)");
  }
}

/// The files tinygltf asks for, served from memory: every external buffer is
/// read (after checked_uri) by read_gltf itself and renamed in the JSON to a
/// token, so tinygltf never opens a file or searches the working folder.
struct ServedBuffers {
  std::map<std::string, std::vector<unsigned char>> bytes;  ///< token -> content
};

std::string token_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool served_exists(const std::string& path, void* user) {
  return static_cast<ServedBuffers*>(user)->bytes.count(token_of(path)) > 0;
}
std::string served_expand(const std::string& path, void*) { return path; }
bool served_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& served = static_cast<ServedBuffers*>(user)->bytes;
  const auto it = served.find(token_of(path));
  if (it == served.end()) {
    if (err) *err = "not a buffer of this file";
    return false;
  }
  *out = std::move(it->second);
  served.erase(it);
  return true;
}
bool served_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "Kappa writes no glTF files";
  return false;
}

/// Keeps an image's bytes as they are (decoded later through OpenImageIO).
bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
  if (size <= 0 || !bytes) return false;
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

/// tinygltf's first error line.
std::string first_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const std::size_t nl = text.find('\n');
  return nl == std::string::npos ? text : text.substr(0, nl);
}

}  // namespace

std::string json_pointer(std::initializer_list<std::string> parts) {
  std::string p;
  for (const std::string& s : parts) p += "/" + s;
  return p;
}

std::string percent_decoded(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

GltfFile read_gltf(const std::filesystem::path& file, Warnings& warnings) {
  const std::string bytes = read_input_file(file, "a glTF file");
  GltfFile out;
  out.file = file;
  const bool binary = bytes.size() >= 4 && le32(bytes, 0) == kGlbMagic;
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".glb" && !binary) fail(file, 0, "a .glb file without the binary glTF magic 'glTF' at its start");
  GlbChunks chunks;
  if (binary) chunks = split_glb(file, bytes, warnings);
  const std::string& text = binary ? chunks.json : bytes;
  json root = parse_json_text(file, text);
  if (!root.is_object()) fail(file, 0, "the glTF JSON must be an object");

  const json* asset = root.contains("asset") ? &root["asset"] : nullptr;
  if (!asset || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
    fail(file, 0, "/asset/version: missing (a glTF 2.0 file names its version)");
  const std::string version = (*asset)["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) fail(file, 0, "/asset/version: '" + version + "', not glTF 2.x");

  check_integers(file, root);
  if (root.contains("extensionsUsed") && root["extensionsUsed"].is_array()) {
    // What no other warning names: an extension used somewhere Kappa does not
    // look (a node's EXT_mesh_gpu_instancing, a mesh's compression, ...).
    static const std::set<std::string> warned_where_used = {
        "KHR_texture_transform", "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_volume",
        "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_unlit", "KHR_materials_dispersion",
        "KHR_materials_variants", "KHR_texture_basisu", "EXT_texture_webp", "MSFT_texture_dds"};
    for (const json& name : root["extensionsUsed"])
      if (name.is_string() && !read_extensions().count(name.get<std::string>()) &&
          !warned_where_used.count(name.get<std::string>()))
        warnings.push_back(located(file, 0, "/extensionsUsed: " + name.get<std::string>() +
                                                " is not read: what it adds is ignored"));
  }
  if (root.contains("extensionsRequired")) {
    const json& required = root["extensionsRequired"];
    if (!required.is_array()) fail(file, 0, "/extensionsRequired: must be an array of names");
    for (std::size_t k = 0; k < required.size(); ++k) {
      if (!required[k].is_string()) fail(file, 0, json_pointer({"extensionsRequired", std::to_string(k)}) + ": must be a name");
      const std::string name = required[k].get<std::string>();
      if (!read_extensions().count(name))
        fail(file, 0, json_pointer({"extensionsRequired", std::to_string(k)}) + ": the file requires " + name +
                          ", which Kappa does not read");
    }
  }

  // Buffers: external ones read here and served to tinygltf from memory.
  ServedBuffers served;
  std::vector<std::size_t> buffer_sizes;
  if (root.contains("buffers")) {
    json& buffers = root["buffers"];
    if (!buffers.is_array()) fail(file, 0, "/buffers: must be an array");
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      const std::string pointer = json_pointer({"buffers", std::to_string(i)});
      json& b = buffers[i];
      if (!b.is_object()) fail(file, 0, pointer + ": must be an object");
      if (!b.contains("uri")) {
        if (!(binary && i == 0 && chunks.has_bin))
          fail(file, 0, pointer + ": no uri, and it is not a binary glTF's first buffer with a BIN chunk");
        buffer_sizes.push_back(chunks.bin.size());
        continue;
      }
      const UriTarget target = checked_uri(file, b["uri"], pointer + "/uri", "a glTF buffer");
      if (target.data) {
        buffer_sizes.push_back(data_uri_size(b["uri"].get<std::string>()));
        continue;
      }
      const std::string content = read_input_file(target.path, "a glTF buffer");
      buffer_sizes.push_back(content.size());
      const std::string token = "kappa-buffer-" + std::to_string(i);
      served.bytes[token].assign(content.begin(), content.end());
      b["uri"] = token;
      out.external_files.push_back(target.path);
    }
  }
  // Each buffer's declared byteLength may not exceed what it holds (tinygltf
  // checks an external file's exactly), and views lie within the real size.
  for (std::size_t i = 0; i < buffer_sizes.size(); ++i) {
    const json& b = root["buffers"][i];
    if (b.contains("byteLength") && b["byteLength"].is_number() && b["byteLength"].get<double>() < double(buffer_sizes[i]))
      buffer_sizes[i] = std::size_t(b["byteLength"].get<double>());
  }
  check_buffer_views(file, root, buffer_sizes);
  std::vector<std::filesystem::path> image_files;
  if (root.contains("images")) {
    const json& images = root["images"];
    if (!images.is_array()) fail(file, 0, "/images: must be an array");
    image_files.resize(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
      const std::string pointer = json_pointer({"images", std::to_string(i)});
      if (!images[i].is_object()) fail(file, 0, pointer + ": must be an object");
      if (!images[i].contains("uri")) continue;
      const UriTarget target = checked_uri(file, images[i]["uri"], pointer + "/uri", "a glTF image");
      if (!target.data) {
        image_files[i] = target.path;
        out.external_files.push_back(target.path);
      }
    }
  }

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&served_exists, &served_expand, &served_read, &served_write, &served});
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  std::string err, warn;
  const std::string base_dir = file.parent_path().empty() ? std::string(".") : file.parent_path().string();
  bool ok;
  if (binary) {
    // The JSON chunk with external buffers renamed, the BIN chunk as it was.
    std::string json_text = root.dump();
    while (json_text.size() % 4 != 0) json_text += ' ';
    std::string glb(12, '\0');
    auto put32 = [](std::string& s, std::size_t at, std::uint32_t v) {
      for (int k = 0; k < 4; ++k) s[at + std::size_t(k)] = char((v >> (8 * k)) & 0xFF);
    };
    std::string json_header(8, '\0'), bin_header(8, '\0');
    put32(json_header, 0, std::uint32_t(json_text.size()));
    put32(json_header, 4, kChunkJson);
    glb += json_header + json_text;
    if (chunks.has_bin) {
      put32(bin_header, 0, std::uint32_t(chunks.bin.size()));
      put32(bin_header, 4, kChunkBin);
      glb += bin_header + chunks.bin;
    }
    put32(glb, 0, kGlbMagic);
    put32(glb, 4, 2);
    put32(glb, 8, std::uint32_t(glb.size()));
    ok = loader.LoadBinaryFromMemory(&out.model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                     unsigned(glb.size()), base_dir, tinygltf::REQUIRE_VERSION);
  } else {
    const std::string json_text = root.dump();
    ok = loader.LoadASCIIFromString(&out.model, &err, &warn, json_text.data(), unsigned(json_text.size()), base_dir,
                                    tinygltf::REQUIRE_VERSION);
  }
  if (!ok) fail(file, 0, "glTF: " + first_line(err.empty() ? std::string("tinygltf could not read it") : err));

  out.embedded_images.resize(out.model.images.size());
  for (std::size_t i = 0; i < out.model.images.size(); ++i) {
    tinygltf::Image& image = out.model.images[i];
    if (i < image_files.size() && !image_files[i].empty()) {
      image.uri = image_files[i].string();  // resolved, checked
      continue;
    }
    if (image.image.empty())
      fail(file, 0, json_pointer({"images", std::to_string(i)}) + ": no image data (an empty buffer view or data URI)");
    out.embedded_images[i] = std::make_shared<const std::vector<unsigned char>>(std::move(image.image));
    image.image.clear();
  }
  return out;
}

}  // namespace kappa
