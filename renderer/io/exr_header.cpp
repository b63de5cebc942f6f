#include "renderer/io/exr_header.h"

#include <cstdint>
#include <fstream>
#include <string>

#include "renderer/util/error.h"

namespace kappa {
namespace {

constexpr std::uint32_t kMagic = 20000630;         // 76 2f 31 01, little-endian
constexpr std::uint32_t kLongNames = 0x400;        // version flag: names and types up to 255 bytes
constexpr std::uint32_t kMultiPart = 0x1000;       // version flag: one header per part, then an empty one

std::uint32_t little_endian(const unsigned char* b) {
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

}  // namespace

void check_exr_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // the reader says why
  in.seekg(0, std::ios::end);
  const std::uint64_t size = std::uint64_t(in.tellg());
  in.seekg(0);
  unsigned char start[8];
  if (!in.read(reinterpret_cast<char*>(start), 8) || little_endian(start) != kMagic) return;
  const std::uint32_t flags = little_endian(start + 4) & ~0xffu;
  const std::size_t longest = (flags & kLongNames) ? 255 : 31;
  const auto refuse = [&](const std::string& why) { fail(path, 0, "not a valid OpenEXR header: " + why); };
  // A null-terminated string of at most `longest` bytes; empty at a header's end.
  const auto read_name = [&](const char* what) {
    std::string s;
    for (char c; in.get(c);) {
      if (c == '\0') return s;
      if (s.size() == longest) refuse(std::string("an attribute ") + what + " is longer than " + std::to_string(longest) + " bytes");
      s += c;
    }
    refuse(std::string("the file ends inside an attribute ") + what);
    return s;
  };
  for (;;) {
    // A header: attributes up to an empty name. A multi-part file lists
    // headers until an empty one; a single-part file has one.
    std::string name = read_name("name");
    if (name.empty()) return;
    do {
      const std::string type = read_name("type");
      unsigned char b[4];
      if (!in.read(reinterpret_cast<char*>(b), 4)) refuse("the file ends in the size of attribute '" + name + "'");
      const std::int32_t declared = std::int32_t(little_endian(b));
      const std::uint64_t at = std::uint64_t(in.tellg());
      if (declared < 0 || std::uint64_t(declared) > size - at)
        refuse("attribute '" + name + "' (" + type + ") declares " + std::to_string(declared) + " bytes, but " +
               std::to_string(size - at) + " are left in the file");
      in.seekg(std::streamoff(at + std::uint64_t(declared)));
      name = read_name("name");
    } while (!name.empty());
    if (!(flags & kMultiPart)) return;
  }
}

}  // namespace kappa
