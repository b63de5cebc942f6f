// The reference reader (kappa converge --reference) refuses, from the header
// alone, an image it could not hold: a few bytes can declare 2^17 x 2^17.
#include "renderer/io/exr_input.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/half.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "renderer/io/exr_output.h"
#include "test_util.h"

namespace kappa {
namespace {

// A valid 4x4 EXR whose dataWindow (and displayWindow) attribute is rewritten
// to declare `size` x `size` pixels, followed by zeros enough for an offset
// table of one chunk a line: OpenEXR then opens it (a zero offset makes it
// rebuild the table by scanning), as it opens the fuzzer's small files that
// declare gigapixels; only reading the pixels would find them missing.
std::string exr_declaring(int width, int height) {
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
    const std::int32_t x_max = width - 1, y_max = height - 1;
    std::memcpy(&bytes[at + key.size() + 4 + 8], &x_max, 4);
    std::memcpy(&bytes[at + key.size() + 4 + 12], &y_max, 4);
  }
  bytes.append(8 * std::size_t(height), '\0');
  return bytes;
}
std::string exr_declaring(int size) { return exr_declaring(size, size); }

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
  Film film(4, 4, AovSelection{});
  write_exr(dir / "small.exr", film, {{"kappa:note", std::string("a string attribute")}});
  const std::string valid = test::read_file(dir / "small.exr");
  std::string bytes = valid;
  const std::string key = std::string("kappa:note") + '\0' + "string" + '\0';
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t huge = 0x7fffffff;
  std::memcpy(&bytes[at + key.size()], &huge, 4);
  test::write_file(dir / "huge_attribute.exr", bytes);
  const auto refused = [&](const std::string& file, const std::string& message) {
    try {
      read_reference(dir / file);
      ADD_FAILURE() << file << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file + ": not a valid OpenEXR header: " + message), std::string::npos)
          << e.what();
    }
  };
  refused("huge_attribute.exr", "attribute 'kappa:note' (string) needs 2147483647 bytes, but ");
  // A channel list is read up to its empty name, whatever size it declares
  // (OpenEXR goes on from there): one whose names never end is refused.
  bytes = valid;
  const std::string channels = std::string("channels") + '\0' + "chlist" + '\0';
  const std::size_t list = bytes.find(channels) + channels.size() + 4;
  for (std::size_t i = list; i < bytes.size(); ++i)
    if (bytes[i] == '\0') bytes[i] = 'x';  // no name ever ends
  test::write_file(dir / "endless_channels.exr", bytes);
  refused("endless_channels.exr", "an attribute channel name is longer than 255 bytes");
  // A name longer than OpenEXR allows without the long-names flag.
  bytes = valid;
  bytes.replace(bytes.find("kappa:note"), 10, std::string(40, 'c'));
  test::write_file(dir / "long_name.exr", bytes);
  refused("long_name.exr", "an attribute name is longer than 31 bytes");
  // The unpatched file passes the check and is read.
  EXPECT_EQ(read_reference(dir / "small.exr").width, 4);
}

TEST(Reference, AnImageOfAnotherFormatIsRefusedWhateverItsName) {
  // OpenImageIO's ImageInput::open, which read references before, handed a
  // file the OpenEXR reader refused to every other plugin (PPM, TIFF, libraw,
  // ffmpeg, ...): a PPM named .exr was read as a reference. Only OpenEXR may
  // see a reference's bytes.
  test::TempDir dir;
  const std::string ppm = std::string("P6\n2 2\n255\n") + std::string(12, '\x40');
  for (const char* name : {"image.exr", "image.ppm"}) {
    test::write_file(dir / name, ppm);
    try {
      read_reference(dir / name);
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string(name) + ": not an OpenEXR file"), std::string::npos)
          << e.what();
    }
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

TEST(Reference, AnEmptyOrInvertedDataWindowIsRefusedAsNot2D) {
  // xMax below xMin: no pixels, which OpenEXR's open would find only after
  // allocating for the header's other attributes.
  test::TempDir dir;
  for (const int width : {0, -3}) {
    const auto path = dir / ("flat" + std::to_string(-width) + ".exr");
    test::write_file(path, exr_declaring(width, 4));
    try {
      read_reference(path);
      ADD_FAILURE() << "a reference with a " << width << "x4 data window was read";
    } catch (const InputError& e) {
      const std::string expected =
          path.filename().string() + ": not a 2D image: its data window is " + std::to_string(width) + "x4";
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(Reference, AWideImageWhoseDecodingOutgrowsTheLimitIsRefusedBeforeOpenExrOpensIt) {
  // 5373955 x 3 pixels (the exr_reference fuzzer's, 1 kB): 0.4 GB of RGB and
  // variance, but a chunk of 16 ZIP scanlines is 1 GB, which OpenEXR's open
  // allocates compressed and not (47 s under ASan); OpenImageIO, which read
  // references before, also took 256 scanlines to convert them: 33 GB.
  test::TempDir dir;
  const auto path = dir / "wide.exr";
  test::write_file(path, exr_declaring(5373955, 3));
  try {
    read_reference(path, std::nullopt, std::uint64_t(1) << 30);
    FAIL() << "a reference whose reading needs several GB was read within 1 GiB";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("wide.exr: the reference is 5373955x3 with 3 channels: reading it needs"), std::string::npos)
        << what;
    EXPECT_NE(what.find("more than the limit of 1.0 GiB"), std::string::npos) << what;
  }
}

TEST(Reference, ChannelsOfEveryTypeAreReadAsFloat) {
  // OpenEXR converts each channel from the file's type as it reads: a
  // reference from another renderer is often HALF, with UINT or FLOAT beside.
  test::TempDir dir;
  const auto path = dir / "mixed.exr";
  const int width = 3, height = 2;
  const std::size_t pixels = std::size_t(width * height);
  std::vector<unsigned> id(pixels);
  std::vector<half> rgb(3 * pixels);
  std::vector<float> variance(3 * pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    id[i] = unsigned(i);
    for (std::size_t c = 0; c < 3; ++c) {
      rgb[3 * i + c] = half(float(c) + 0.25f * float(i));  // exact in HALF
      variance[3 * i + c] = 1e-5f * float(i + 1) + float(c);
    }
  }
  Imf::Header header(width, height);
  Imf::FrameBuffer frame;
  header.channels().insert("id", Imf::Channel(Imf::UINT));
  frame.insert("id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(id.data()), sizeof(unsigned), sizeof(unsigned) * width));
  const char* names[] = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  for (std::size_t c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::HALF));
    frame.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(rgb.data() + c), 3 * sizeof(half),
                                      3 * sizeof(half) * width));
    header.channels().insert(names[3 + c], Imf::Channel(Imf::FLOAT));
    frame.insert(names[3 + c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(variance.data() + c), 3 * sizeof(float),
                                          3 * sizeof(float) * width));
  }
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  const ReferenceImage image = read_reference(path, FilmSize{width, height});
  ASSERT_EQ(image.rgb.size(), 3 * pixels);
  ASSERT_EQ(image.variance.size(), 3 * pixels);
  for (std::size_t i = 0; i < 3 * pixels; ++i) {
    EXPECT_EQ(image.rgb[i], float(rgb[i])) << "value " << i;
    EXPECT_EQ(image.variance[i], variance[i]) << "value " << i;
  }
}

}  // namespace
}  // namespace kappa
