#include "renderer/io/exr_header.h"

#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"

namespace kappa {
namespace {

constexpr std::uint32_t kMagic = 20000630;         // 76 2f 31 01, little-endian
constexpr std::uint32_t kLongNames = 0x400;        // version flag: names and types up to 255 bytes
constexpr std::uint32_t kMultiPart = 0x1000;       // version flag: one header per part, then an empty one

std::uint32_t little_endian(const unsigned char* b) {
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

/// Bytes OpenEXR 3.1 reads for a value of a type whose reader takes a fixed
/// size whatever the attribute declares (Header::readFrom then goes on from
/// where that reader stopped, not from the declared end); 0 for the others.
std::uint64_t fixed_value_bytes(const std::string& type) {
  struct Fixed {
    const char* type;
    std::uint64_t bytes;
  };
  static constexpr Fixed kFixed[] = {
      {"box2i", 16},  {"box2f", 16},  {"chromaticities", 32}, {"compression", 1}, {"double", 8}, {"envmap", 1},
      {"float", 4},   {"int", 4},     {"keycode", 28},        {"lineOrder", 1},   {"m33f", 36},  {"m33d", 72},
      {"m44f", 64},   {"m44d", 128},  {"rational", 8},        {"tiledesc", 9},    {"timecode", 8}, {"v2i", 8},
      {"v2f", 8},     {"v2d", 16},    {"v3i", 12},            {"v3f", 12},        {"v3d", 24},   {"deepImageState", 1}};
  for (const Fixed& f : kFixed)
    if (type == f.type) return f.bytes;
  return 0;
}

std::int32_t signed_little_endian(const unsigned char* b) { return std::int32_t(little_endian(b)); }

}  // namespace

double ExrLayout::chunk_bytes() const {
  // A tiled file read as scanlines: OpenEXR caches a row of tiles.
  if (tile_width > 0 && tile_height > 0) return double(tile_height) * double(width) * double(pixel_bytes);
  // OpenEXR's scanlines a chunk: ZIP 16; PIZ, PXR24, B44, B44A, DWAA 32; DWAB 256.
  static constexpr int kLines[] = {1, 1, 1, 16, 32, 32, 32, 32, 32, 256};
  const int lines = compression >= 0 && compression < 10 ? kLines[compression] : 256;
  return double(lines) * double(width) * double(pixel_bytes);
}

ExrLayout check_exr_header(const std::filesystem::path& path) {
  ExrLayout layout;
  std::ifstream in(path, std::ios::binary);
  if (!in) return layout;  // the reader says why
  in.seekg(0, std::ios::end);
  const std::uint64_t size = std::uint64_t(in.tellg());
  in.seekg(0);
  unsigned char start[8];
  if (!in.read(reinterpret_cast<char*>(start), 8) || little_endian(start) != kMagic)
    fail(path, 0, "not an OpenEXR file (it does not start with OpenEXR's magic number 76 2f 31 01)");
  const std::uint32_t flags = little_endian(start + 4) & ~0xffu;
  const std::size_t longest = (flags & kLongNames) ? 255 : 31;
  const auto refuse = [&](const std::string& why) { fail(path, 0, "not a valid OpenEXR header: " + why); };
  const auto left = [&] { return size - std::uint64_t(in.tellg()); };
  // A null-terminated string of at most `most` bytes; empty at a header's end.
  const auto read_name = [&](const char* what, std::size_t most) {
    std::string s;
    for (char c; in.get(c);) {
      if (c == '\0') return s;
      if (s.size() == most) refuse(std::string("an attribute ") + what + " is longer than " + std::to_string(most) + " bytes");
      s += c;
    }
    refuse(std::string("the file ends inside an attribute ") + what);
    return s;
  };
  const auto read_int = [&](const std::string& what) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) refuse("the file ends in " + what);
    return std::int32_t(little_endian(b));
  };
  // Refuses a value that would run past the file's end (the check OpenEXR
  // leaves to its allocation of the declared size).
  const auto require = [&](std::uint64_t bytes, const std::string& what) {
    if (bytes > left()) refuse(what + " needs " + std::to_string(bytes) + " bytes, but " + std::to_string(left()) +
                               " are left in the file");
  };
  const auto skip = [&](std::uint64_t bytes, const std::string& what) {
    require(bytes, what);
    in.seekg(std::streamoff(std::uint64_t(in.tellg()) + bytes));
  };
  // `bytes` of a value that is kept, read in full or refused.
  const auto read_bytes = [&](unsigned char* out, std::uint64_t bytes, const std::string& what) {
    require(bytes, what);
    in.read(reinterpret_cast<char*>(out), std::streamsize(bytes));
  };
  bool first_header = true;
  // One attribute's value, consumed as OpenEXR 3.1's reader of its type does;
  // the first header's window, channels, compression and tiles kept.
  const auto read_value = [&](const std::string& name, const std::string& type, std::int32_t declared) {
    const std::string what = "attribute '" + name + "' (" + type + ")";
    if (declared < 0) refuse(what + " declares " + std::to_string(declared) + " bytes");
    unsigned char b[16];
    if (first_header && name == "dataWindow" && type == "box2i") {  // xMin, yMin, xMax, yMax
      read_bytes(b, 16, what);
      layout.width = std::int64_t(signed_little_endian(b + 8)) - signed_little_endian(b) + 1;
      layout.height = std::int64_t(signed_little_endian(b + 12)) - signed_little_endian(b + 4) + 1;
      return;
    }
    if (first_header && name == "compression" && type == "compression") {
      read_bytes(b, 1, what);
      layout.compression = b[0];
      return;
    }
    if (first_header && name == "tiles" && type == "tiledesc") {  // x size, y size, mode
      read_bytes(b, 9, what);
      layout.tile_width = little_endian(b);
      layout.tile_height = little_endian(b + 4);
      return;
    }
    if (const std::uint64_t fixed = fixed_value_bytes(type)) return skip(fixed, what);
    if (type == "chlist") {  // channels until an empty name, each a name and 16 bytes
      const bool keep = first_header && name == "channels";
      while (!read_name("channel name", 255).empty()) {
        read_bytes(b, 16, what);  // pixel type, linear, 3 reserved, x and y sampling
        if (!keep) continue;
        ++layout.channels;
        layout.pixel_bytes += little_endian(b) == 1 ? 2 : 4;  // HALF; UINT, FLOAT (OpenEXR refuses others)
      }
      return;
    }
    if (type == "preview") {  // width and height, then 4 bytes a pixel
      const std::uint64_t w = std::uint32_t(read_int(what)), h = std::uint32_t(read_int(what));
      return skip(w * h * 4, what);
    }
    if (type == "stringvector") {  // strings, each its length first, within the declared size
      std::uint64_t read = 0;
      while (read < std::uint64_t(declared)) {
        const std::int32_t length = read_int(what);
        if (length < 0) refuse(what + " holds a string of " + std::to_string(length) + " bytes");
        skip(std::uint64_t(length), what);
        read += 4 + std::uint64_t(length);
      }
      return;
    }
    skip(std::uint64_t(declared), what);  // string, floatvector, idmanifest, unknown (opaque): the declared size
  };
  for (;;) {
    // A header: attributes up to an empty name. A multi-part file lists
    // headers until an empty one; a single-part file has one.
    std::string name = read_name("name", longest);
    if (name.empty()) return layout;
    do {
      const std::string type = read_name("type", longest);
      read_value(name, type, read_int("the size of attribute '" + name + "'"));
      name = read_name("name", longest);
    } while (!name.empty());
    if (!(flags & kMultiPart)) return layout;
    first_header = false;
  }
}

}  // namespace kappa
