// Images the commands wrote, read back for tests with OpenEXR and libpng:
// an EXR's channels, pixels and attributes; a PNG's size and RGB bytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace kappa::test {

struct ExrFile {
  using Attribute = std::variant<std::string, int, float, double>;
  int width = 0, height = 0;
  std::vector<std::string> channels;  ///< OpenEXR's order: sorted by name
  std::vector<float> pixels;          ///< channels.size() a pixel, row 0 at the top
  std::map<std::string, Attribute> attributes;  ///< those of these four types

  /// The index of channel `name` in `channels`, or -1.
  int channel(const std::string& name) const;
  /// One channel's values, a pixel each (and a test failure without it).
  std::vector<float> values(const std::string& name) const;
  std::string string_attribute(const std::string& name, const std::string& otherwise = "") const;
  int int_attribute(const std::string& name, int otherwise = 0) const;
  float float_attribute(const std::string& name, float otherwise = 0) const;
  /// A double attribute, or nullptr when `name` is absent or of another type.
  const double* double_attribute(const std::string& name) const;
};

/// Every channel as float; a test failure (and an empty image) when OpenEXR
/// cannot read the file.
ExrFile read_exr_file(const std::filesystem::path& path);

struct PngFile {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 a pixel, row 0 at the top
};

/// A PNG decoded to 8-bit RGB; a test failure (and an empty image) when
/// libpng cannot read it.
PngFile read_png_file(const std::filesystem::path& path);

}  // namespace kappa::test
