// The reference reader (kappa converge --reference) refuses, from the header
// alone, an image it could not hold: a few bytes can declare 2^17 x 2^17.
#include "renderer/io/exr_input.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "renderer/io/exr_output.h"
#include "renderer/util/error.h"
#include "test_util.h"

namespace kappa {
namespace {

// A valid 4x4 EXR whose dataWindow (and displayWindow) attribute is rewritten
// to declare `size` x `size` pixels, followed by zeros enough for an offset
// table of one chunk a line: OpenEXR then opens it (a zero offset makes it
// rebuild the table by scanning), as it opens the fuzzer's small files that
// declare gigapixels; only reading the pixels would find them missing.
std::string exr_declaring(int size) {
  test::TempDir dir;
  Film film(4, 4, AovSelection{});
  for (float& v : film.rgb) v = 0.5f;
  write_exr(dir / "small.exr", film, {});
  std::string bytes = test::read_file(dir / "small.exr");
  for (const char* name : {"dataWindow", "displayWindow"}) {
    const std::string key = std::string(name) + '\0' + "box2i" + '\0';
    const std::size_t at = bytes.find(key);
    EXPECT_NE(at, std::string::npos) << name;
    if (at == std::string::npos) continue;
    // Then the attribute's size (16) and xMin, yMin, xMax, yMax (int32, little-endian).
    const std::int32_t max = size - 1;
    std::memcpy(&bytes[at + key.size() + 4 + 8], &max, 4);
    std::memcpy(&bytes[at + key.size() + 4 + 12], &max, 4);
  }
  bytes.append(8 * std::size_t(size), '\0');
  return bytes;
}

TEST(Reference, HeaderDeclaringMoreThanMemoryIsRefusedBeforeReading) {
  test::TempDir dir;
  const auto path = dir / "huge.exr";
  test::write_file(path, exr_declaring(1 << 17));  // 2^34 pixels: over 600 GB as floats
  try {
    read_reference(path);
    FAIL() << "a reference declaring 2^34 pixels was read";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("huge.exr: the reference is 131072x131072 with 3 channels: reading it needs"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("more than this machine's"), std::string::npos) << what;
  }
}

TEST(Reference, SizeOtherThanTheFilmIsRefusedFromTheHeader) {
  test::TempDir dir;
  const auto path = dir / "wide.exr";
  test::write_file(path, exr_declaring(1 << 17));
  try {
    read_reference(path, FilmSize{64, 64});
    FAIL() << "a reference of another size than the film was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wide.exr: the reference is 131072x131072, the film 64x64"),
              std::string::npos)
        << e.what();
  }
}

TEST(Reference, AnAttributeLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  // OpenEXR 3.1 resizes a string attribute to its declared size before it
  // reads: this 1 kB file would take 2 GB (the exr_reference fuzzer's timeout).
  test::TempDir dir;
  std::string bytes = exr_declaring(4);
  const std::string key = std::string("channels") + '\0' + "chlist" + '\0';
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t huge = 0x7fffffff;
  std::memcpy(&bytes[at + key.size()], &huge, 4);
  test::write_file(dir / "huge_attribute.exr", bytes);
  try {
    read_reference(dir / "huge_attribute.exr");
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("huge_attribute.exr: not a valid OpenEXR header: attribute 'channels' (chlist) "
                                         "declares 2147483647 bytes"),
              std::string::npos)
        << e.what();
  }
  // A name longer than OpenEXR allows without the long-names flag.
  bytes = exr_declaring(4);
  const std::size_t name_at = bytes.find("channels");
  bytes.replace(name_at, 8, std::string(40, 'c'));
  test::write_file(dir / "long_name.exr", bytes);
  try {
    read_reference(dir / "long_name.exr");
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("an attribute name is longer than 31 bytes"), std::string::npos) << e.what();
  }
}

TEST(Reference, TheUnpatchedImageIsRead) {
  test::TempDir dir;
  const auto path = dir / "small.exr";
  test::write_file(path, exr_declaring(4));  // the same bytes, the window rewritten to itself
  const ReferenceImage image = read_reference(path, FilmSize{4, 4});
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 4);
  ASSERT_EQ(image.rgb.size(), 48u);
  for (const float v : image.rgb) EXPECT_EQ(v, 0.5f);
}

}  // namespace
}  // namespace kappa
