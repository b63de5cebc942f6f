// Hostile glTF files: each refusal is one line naming the file and the JSON pointer of the bad element.
#include "renderer/scene/scene_loader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "core/error.h"
#include "test_util.h"

namespace kappa {
namespace {

std::string base64(const std::string& bytes) {
  static const char* const k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  auto byte = [&](std::size_t at) { return std::uint32_t(static_cast<unsigned char>(bytes[at])); };
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
  }
  if (bytes.size() - i == 1) {
    const std::uint32_t v = byte(i) << 16;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += "==";
  } else if (bytes.size() - i == 2) {
    const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += k[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

/// Little-endian bytes of floats (and of 16-bit indices).
std::string float_bytes(std::initializer_list<float> values) {
  std::string s;
  for (float f : values) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) s += char((u >> (8 * k)) & 0xFF);
  }
  return s;
}
std::string u16_bytes(std::initializer_list<std::uint16_t> values) {
  std::string s;
  for (std::uint16_t v : values) {
    s += char(v & 0xFF);
    s += char(v >> 8);
  }
  return s;
}
std::string le32(std::uint32_t v) {
  std::string s;
  for (int k = 0; k < 4; ++k) s += char((v >> (8 * k)) & 0xFF);
  return s;
}

/// The one triangle's 36 bytes: (0,0,0) (1,0,0) (0,1,0).
std::string triangle_bytes() { return float_bytes({0, 0, 0, 1, 0, 0, 0, 1, 0}); }

std::string data_uri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

/// A valid one-triangle glTF, its parts JSON text to replace one at a time.
struct Doc {
  std::string more;  ///< further top-level members, each followed by ", "
  std::string scenes = R"([{"nodes": [0]}])";
  std::string nodes = R"([{"mesh": 0}])";
  std::string meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}}]}])";
  std::string accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}])";
  std::string buffer_views = R"([{"buffer": 0, "byteLength": 36}])";
  std::string buffers = R"([{"byteLength": 36, "uri": ")" + data_uri(triangle_bytes()) + R"("}])";

  std::string text() const {
    return R"({"asset": {"version": "2.0"}, )" + more + R"("scene": 0, "scenes": )" + scenes + R"(, "nodes": )" +
           nodes + R"(, "meshes": )" + meshes + R"(, "accessors": )" + accessors + R"(, "bufferViews": )" +
           buffer_views + R"(, "buffers": )" + buffers + "}\n";
  }
};

/// A GLB container of `json` (padded with spaces) and `bin` (with zeros; no BIN chunk when empty).
std::string glb(std::string json, std::string bin) {
  while (json.size() % 4 != 0) json += ' ';
  while (bin.size() % 4 != 0) bin += '\0';
  std::string body = le32(std::uint32_t(json.size())) + "JSON" + json;
  if (!bin.empty()) body += le32(std::uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  return "glTF" + le32(2) + le32(std::uint32_t(12 + body.size())) + body;
}

/// The one-triangle document as a GLB, its buffer in the BIN chunk.
std::string triangle_glb() {
  Doc d;
  d.buffers = R"([{"byteLength": 36}])";
  return glb(d.text(), triangle_bytes());
}

/// load_scene's InputError message for `file`; "" when it loads; another
/// exception's text, marked, so that a test fails on it without crashing.
std::string refusal(const std::filesystem::path& file) {
  try {
    Warnings w;
    load_scene(file, w);
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("<not an InputError> ") + e.what();
  }
  return "";
}

/// `file` is refused with one line naming it and holding each of `parts`
/// (the JSON pointer and a few words of the reason).
void expect_refused(const std::filesystem::path& file, std::initializer_list<std::string> parts) {
  const std::string message = refusal(file);
  SCOPED_TRACE(message);
  ASSERT_NE(message, "") << file << " loaded";
  EXPECT_EQ(message.rfind("<not an InputError>", 0), std::string::npos);
  EXPECT_NE(message.find(file.string()), std::string::npos) << "the message does not name " << file;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line";
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << "missing: " << part;
}

void expect_refused(const test::TempDir& dir, const Doc& doc, std::initializer_list<std::string> parts,
                    const std::string& name = "bad.gltf") {
  test::write_file(dir / name, doc.text());
  expect_refused(dir / name, parts);
}

// The documents the refusals below change one part of load as they are: a
// refusal is then the changed part's.
TEST(GltfBadInput, TheBaseDocumentsLoad) {
  test::TempDir dir;
  {
    test::write_file(dir / "data_uri.gltf", Doc().text());
    Warnings w;
    const Scene s = load_scene(dir / "data_uri.gltf", w);
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].v1, (Vec3f{1, 0, 0}));
  }
  {
    test::write_file(dir / "tri.bin", triangle_bytes());
    Doc d;
    d.buffers = R"([{"byteLength": 36, "uri": "tri.bin"}])";
    test::write_file(dir / "external.gltf", d.text());
    Warnings w;
    EXPECT_EQ(load_scene(dir / "external.gltf", w).triangles.size(), 1u);
  }
  {
    test::write_file(dir / "tri.glb", triangle_glb());
    Warnings w;
    EXPECT_EQ(load_scene(dir / "tri.glb", w).triangles.size(), 1u);
  }
  {
    // With indices (the index case's layout, in range).
    Doc d;
    d.accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}])";
    d.buffer_views = R"([{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}])";
    d.buffers = R"([{"byteLength": 44, "uri": ")" + data_uri(triangle_bytes() + u16_bytes({0, 1, 2, 0})) + R"("}])";
    d.meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}])";
    test::write_file(dir / "indexed.gltf", d.text());
    Warnings w;
    EXPECT_EQ(load_scene(dir / "indexed.gltf", w).triangles.size(), 1u);
  }
}

TEST(GltfBadInput, AccessorPastItsBufferView) {
  test::TempDir dir;
  Doc d;
  d.accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}])";
  expect_refused(dir, d, {"/accessors/0", "/bufferViews/0", "run past"});
  d.accessors = R"([{"bufferView": 0, "byteOffset": 4, "componentType": 5126, "count": 3, "type": "VEC3"}])";
  expect_refused(dir, d, {"/accessors/0", "/bufferViews/0", "run past"});
}

TEST(GltfBadInput, BufferViewPastItsBuffer) {
  test::TempDir dir;
  Doc d;
  d.buffer_views = R"([{"buffer": 0, "byteLength": 48}])";
  expect_refused(dir, d, {"/bufferViews/0", "outside its buffer"});
  d.buffer_views = R"([{"buffer": 0, "byteOffset": 4, "byteLength": 36}])";
  expect_refused(dir, d, {"/bufferViews/0", "outside its buffer"});
}

TEST(GltfBadInput, IndexOutOfRange) {
  test::TempDir dir;
  Doc d;
  d.accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}])";
  d.buffer_views = R"([{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}])";
  d.buffers = R"([{"byteLength": 44, "uri": ")" + data_uri(triangle_bytes() + u16_bytes({0, 1, 7, 0})) + R"("}])";
  d.meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}])";
  expect_refused(dir, d, {"/accessors/1", "index 7", "out of range", "3 vertices"});
}

TEST(GltfBadInput, StrideShorterThanTheElement) {
  test::TempDir dir;
  Doc d;
  d.buffer_views = R"([{"buffer": 0, "byteLength": 36, "byteStride": 8}])";  // VEC3 FLOAT is 12 bytes
  expect_refused(dir, d, {"/bufferViews/0/byteStride", "/accessors/0", "less than"});
}

TEST(GltfBadInput, PositionOfTheWrongComponentType) {
  test::TempDir dir;
  Doc d;
  d.accessors = R"([{"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC3"}])";
  expect_refused(dir, d, {"/accessors/0/componentType", "UNSIGNED_SHORT", "POSITION", "must be FLOAT"});
}

TEST(GltfBadInput, PositionOfTheWrongType) {
  test::TempDir dir;
  Doc d;
  d.accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"}])";
  expect_refused(dir, d, {"/accessors/0/type", "VEC2", "POSITION", "must be VEC3"});
}

// Image URIs that leave the glTF file's folder, even when the file exists.
TEST(GltfBadInput, ImageUriLeavingTheFolder) {
  test::TempDir dir;
  std::filesystem::create_directory(dir / "sub");
  test::write_file(dir / "outside.png", "not read");
  for (const char* uri : {"../outside.png", "/etc/passwd", "%2E%2E/outside.png", "a/../../outside.png"}) {
    SCOPED_TRACE(uri);
    Doc d;
    d.more = R"("images": [{"uri": ")" + std::string(uri) + R"("}], )";
    test::write_file(dir / "sub" / "bad.gltf", d.text());
    expect_refused(dir / "sub" / "bad.gltf", {"/images/0/uri", "leaves the glTF file's folder"});
  }
}

TEST(GltfBadInput, MissingBufferFile) {
  test::TempDir dir;
  Doc d;
  d.buffers = R"([{"byteLength": 36, "uri": "missing.bin"}])";
  expect_refused(dir, d, {"/buffers/0/uri", "missing.bin", "not found"});
}

TEST(GltfBadInput, DataUriThatIsNotBase64) {
  test::TempDir dir;
  Doc d;
  d.buffers = R"([{"byteLength": 3, "uri": "data:application/octet-stream,abc"}])";
  expect_refused(dir, d, {"/buffers/0/uri", "not base64"});
  d.buffers = R"([{"byteLength": 3, "uri": "data:application/octet-stream;base64,@@@@"}])";
  expect_refused(dir, d, {"/buffers/0/uri", "not valid base64"});
}

TEST(GltfBadInput, NodeCycle) {
  test::TempDir dir;
  Doc d;
  d.nodes = R"([{"children": [1]}, {"children": [0], "mesh": 0}])";
  expect_refused(dir, d, {"/nodes/1/children/0", "cycle"});
}

TEST(GltfBadInput, NodeWithTwoParents) {
  test::TempDir dir;
  Doc d;
  d.scenes = R"([{"nodes": [0, 1]}])";
  d.nodes = R"([{"children": [2]}, {"children": [2]}, {"mesh": 0}])";
  expect_refused(dir, d, {"/nodes/1/children/0", "second parent"});
}

TEST(GltfBadInput, GlbWithTheWrongLengthInItsHeader) {
  test::TempDir dir;
  std::string bytes = triangle_glb();
  bytes.replace(8, 4, le32(std::uint32_t(bytes.size() + 4)));
  test::write_file(dir / "bad.glb", bytes);
  expect_refused(dir / "bad.glb", {"binary glTF", "header gives a length of " + std::to_string(bytes.size() + 4)});
}

TEST(GltfBadInput, GlbWhoseFirstChunkIsBin) {
  test::TempDir dir;
  std::string bytes = triangle_glb();
  bytes.replace(16, 4, std::string("BIN\0", 4));
  test::write_file(dir / "bad.glb", bytes);
  expect_refused(dir / "bad.glb", {"binary glTF", "first chunk", "not JSON"});
}

TEST(GltfBadInput, GlbChunkPastTheEnd) {
  test::TempDir dir;
  std::string bytes = triangle_glb();
  const std::uint32_t json_length = std::uint32_t(static_cast<unsigned char>(bytes[12])) |
                                    std::uint32_t(static_cast<unsigned char>(bytes[13])) << 8 |
                                    std::uint32_t(static_cast<unsigned char>(bytes[14])) << 16 |
                                    std::uint32_t(static_cast<unsigned char>(bytes[15])) << 24;
  bytes.replace(12, 4, le32(json_length + 1024));  // the header's total length stays right
  test::write_file(dir / "bad.glb", bytes);
  expect_refused(dir / "bad.glb", {"binary glTF", "chunk 0", "past the file's end"});
}

TEST(GltfBadInput, GlbWithoutTheMagic) {
  test::TempDir dir;
  std::string bytes = triangle_glb();
  bytes.replace(0, 4, "glTX");
  test::write_file(dir / "bad.glb", bytes);
  expect_refused(dir / "bad.glb", {"without the binary glTF magic"});
}

// JSON has no NaN: a number that does not fit a double is the non-finite
// number a file can hold (refused with its line, before any pointer exists).
TEST(GltfBadInput, MatrixNumberThatIsNotFinite) {
  test::TempDir dir;
  Doc d;
  d.nodes = R"([{"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e999, 0, 0, 1]}])";
  expect_refused(dir, d, {"1e999", "does not fit a double"});
}

TEST(GltfBadInput, MatrixOfFifteenNumbers) {
  test::TempDir dir;
  Doc d;
  d.nodes = R"([{"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]}])";
  expect_refused(dir, d, {"/nodes/0/matrix", "16 numbers"});
}

// Valid glTF: the hierarchy is walked without recursion, so a chain of a
// million nodes is a long loop, not a stack overflow.
TEST(GltfBadInput, MillionNodeChainLoads) {
  constexpr int kNodes = 1000000;
  std::string nodes;
  nodes.reserve(std::size_t(kNodes) * 24 + 16);
  nodes += '[';
  for (int i = 0; i + 1 < kNodes; ++i) {
    nodes += R"({"children": [)";
    nodes += std::to_string(i + 1);
    nodes += "]}, ";
  }
  nodes += R"({"mesh": 0}])";
  Doc d;
  d.nodes = std::move(nodes);
  test::TempDir dir;
  test::write_file(dir / "chain.gltf", d.text());
  Warnings w;
  Scene s;
  ASSERT_NO_THROW(s = load_scene(dir / "chain.gltf", w)) << refusal(dir / "chain.gltf");
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].v1, (Vec3f{1, 0, 0}));
  ASSERT_EQ(s.gltf_files.size(), 1u);
  EXPECT_EQ(s.gltf_files[0].nodes, std::uint64_t(kNodes));
  EXPECT_EQ(s.gltf_files[0].mesh_instances, 1u);
}

// tinygltf's parser recurses on nesting: deep JSON is refused before it.
TEST(GltfBadInput, DeeplyNestedExtras) {
  test::TempDir dir;
  std::string extras;
  for (int i = 0; i < 100; ++i) extras += R"({"a": )";
  extras += "1";
  for (int i = 0; i < 100; ++i) extras += "}";
  Doc d;
  d.nodes = R"([{"mesh": 0, "extras": )" + extras + "}]";
  expect_refused(dir, d, {"nests deeper"});
}

TEST(GltfBadInput, RequiredExtensionKappaDoesNotRead) {
  test::TempDir dir;
  Doc d;
  d.more = R"("extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"], )";
  expect_refused(dir, d, {"/extensionsRequired/0", "KHR_draco_mesh_compression"});
}

TEST(GltfBadInput, UriWithAScheme) {
  test::TempDir dir;
  for (const char* uri : {"http://example.com/a.bin", "https://example.com/a.bin", "file:///etc/passwd"}) {
    SCOPED_TRACE(uri);
    Doc d;
    d.buffers = R"([{"byteLength": 36, "uri": ")" + std::string(uri) + R"("}])";
    const std::string scheme = std::string(uri).substr(0, std::string(uri).find(':'));
    expect_refused(dir, d, {"/buffers/0/uri", "scheme '" + scheme + ":'"});
  }
}

// An accessor's count so large that its last element's end, plus its
// byteOffset, wraps past 2^64 to within the buffer view: refused as input
// (not an allocation failure). 12 * (count - 1) + 12 + 4 = 2^64.
TEST(GltfBadInput, AccessorCountThatWrapsTheBoundsArithmetic) {
  test::TempDir dir;
  Doc d;
  d.accessors =
      R"([{"bufferView": 0, "byteOffset": 4, "componentType": 5126, "count": 1537228672809129301, "type": "VEC3"}])";
  expect_refused(dir, d, {"/accessors/0"});
}

// An image whose buffer view lies past its buffer: tinygltf hands such a view
// to the image loader unchecked, so the reader checks every view first.
TEST(GltfBadInput, ImageBufferViewPastItsBuffer) {
  test::TempDir dir;
  Doc d;
  d.buffer_views = R"([{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 30, "byteLength": 1000}])";
  d.more = R"("images": [{"bufferView": 1, "mimeType": "image/png"}], )";
  expect_refused(dir, d, {"/bufferViews/1", "outside its buffer"});
}

// Indices tinygltf would truncate (2^32 reads as 0) or take for "absent"
// (a negative one), or a fraction: refused, never read as another element.
TEST(GltfBadInput, IndicesOutOfRangeNegativeOrFractional) {
  test::TempDir dir;
  for (const char* nodes : {R"([{"mesh": 4294967296}])", R"([{"mesh": -2}])", R"([{"mesh": 0.5}])",
                            R"([{"mesh": "0"}])"}) {
    SCOPED_TRACE(nodes);
    Doc d;
    d.nodes = nodes;
    expect_refused(dir, d, {"/nodes/0/mesh", "index"});
  }
  Doc d;
  d.meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": -2}]}])";
  expect_refused(dir, d, {"/meshes/0/primitives/0/indices", "index"});
  Doc c;
  c.scenes = R"([{"nodes": [2147483648]}])";
  expect_refused(dir, c, {"/scenes/0/nodes/0", "out of range"});
}

TEST(GltfBadInput, ASceneListingANodeThatIsNotARoot) {
  test::TempDir dir;
  Doc d;
  d.nodes = R"([{"children": [1]}, {"mesh": 0}])";
  d.scenes = R"([{"nodes": [1]}])";
  expect_refused(dir, d, {"/scenes/0/nodes/0", "not a root"});
}

TEST(GltfBadInput, AMatrixThatIsNotAffine) {
  test::TempDir dir;
  Doc d;
  d.nodes = R"([{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0.5, 0,0,0,1]}])";
  expect_refused(dir, d, {"/nodes/0/matrix", "affine"});
}

TEST(GltfBadInput, ADataUriOfAMediaTypeTinygltfDoesNotDecode) {
  test::TempDir dir;
  Doc d;
  d.buffers = R"([{"byteLength": 36, "uri": "data:image/webp;base64,)" + base64(triangle_bytes()) + R"("}])";
  expect_refused(dir, d, {"/buffers/0/uri", "image/webp"});
}

// Instances cost the file a few bytes each and the scene their triangles:
// counted before any is copied, refused past Kappa's 32-bit triangle ids.
TEST(GltfBadInput, InstancesBeyondTheTriangleLimitAreRefusedBeforeCopying) {
  test::TempDir dir;
  Doc d;
  d.accessors = R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 0, "componentType": 5125, "count": 5000000001, "type": "SCALAR"}])";
  d.meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}])";
  expect_refused(dir, d, {"/nodes/0", "32-bit triangle ids"});
}

}  // namespace
}  // namespace kappa
