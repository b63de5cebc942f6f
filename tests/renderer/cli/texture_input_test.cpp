// Bad texture maps and environment images, through the `kappa` binary, one
// test per row of the texture table in docs/bad-input.md. Each test builds a
// tiny scene in a fresh temporary folder: x.obj (a quad facing the camera,
// with vt), x.mtl whose line 3 is the map statement under test, scene.json;
// then renders it at 8 x 8, 1 spp. A refusal is exit 2 and one line naming
// the MTL file and line (or scene.json) and the image, with no output and no
// temporary left behind; a warning renders (exit 0, a finite image) and says
// what became of the image.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "image_files.h"
#include "renderer/io/png_output.h"
#include "test_util.h"

namespace kappa::test {
namespace {

namespace fs = std::filesystem;

/// Seconds a run may take before coreutils' timeout ends it (exit 124): a
/// run that waits on a FIFO or reads gigabytes fails instead of hanging.
constexpr int kTimeoutS = 60;

fs::path textured_box() { return assets_dir() / "textured-box"; }

/// The quad: 4 v and 4 vt, faces on lines 11 and 12.
const char* const kQuadObj =
    "mtllib x.mtl\n"          // 1
    "usemtl tex\n"            // 2
    "v -1 -1 0\n"             // 3
    "v 1 -1 0\n"              // 4
    "v 1 1 0\n"               // 5
    "v -1 1 0\n"              // 6
    "vt 0 0\n"                // 7
    "vt 1 0\n"                // 8
    "vt 1 1\n"                // 9
    "vt 0 1\n"                // 10
    "f 1/1 2/2 3/3\n"         // 11
    "f 1/1 3/3 4/4\n";        // 12

/// Writes x.obj (`obj`), x.mtl (material `tex`; `map_line`, when given, is
/// its line 3) and scene.json (the camera on the quad, `environment` as
/// written, then `extra_fields`) into `dir`; returns scene.json's path.
fs::path write_scene(const fs::path& dir, const std::string& map_line, const std::string& environment = "[1, 1, 1]",
                     const std::string& extra_fields = "", const std::string& obj = kQuadObj) {
  write_file(dir / "x.obj", obj);
  write_file(dir / "x.mtl", "newmtl tex\nKd 0.8 0.8 0.8\n" + (map_line.empty() ? std::string() : map_line + "\n"));
  write_file(dir / "scene.json",
             "{\"meshes\": [\"x.obj\"], "
             "\"camera\": {\"eye\": [0, 0, 3], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0], \"vfov_deg\": 45}, "
             "\"environment\": " + environment + extra_fields + "}\n");
  return dir / "scene.json";
}

/// A FLOAT RGB EXR of width x height: `rgb` 3 values a pixel, row 0 at the top.
void write_rgb_exr(const fs::path& path, int width, int height, std::vector<float> rgb) {
  ASSERT_EQ(rgb.size(), 3 * std::size_t(width) * std::size_t(height));
  Imf::Header header(width, height);
  Imf::FrameBuffer frame;
  const char* names[] = {"R", "G", "B"};
  for (std::size_t c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), 3 * sizeof(float),
                                      3 * sizeof(float) * std::size_t(width)));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frame);
  file.writePixels(height);
}

/// width x height texels of one colour.
std::vector<float> flat_rgb(int width, int height, float r, float g, float b) {
  std::vector<float> rgb;
  for (int i = 0; i < width * height; ++i) rgb.insert(rgb.end(), {r, g, b});
  return rgb;
}

// ---------------------------------------------------------------------------
// A PNG's bytes, written by hand: a header may claim what no encoder writes.

/// CRC-32 (ISO 3309, as PNG's chunks and zlib's crc32 compute it).
std::uint32_t png_crc(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char ch : bytes) {
    crc ^= std::uint32_t(static_cast<unsigned char>(ch));
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

std::string big_endian(std::uint32_t v) {
  std::string s;
  for (int shift = 24; shift >= 0; shift -= 8) s.push_back(char((v >> shift) & 0xFFu));
  return s;
}

/// Length, type, data and the CRC of type and data.
std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(std::uint32_t(data.size())) + type + data + big_endian(png_crc(type + data));
}

/// A PNG whose IHDR says width x height, 8-bit RGB, followed by an IDAT of
/// an empty zlib stream and IEND: a header any reader opens, a few dozen
/// bytes that declare gigabytes of texels.
std::string png_declaring(std::uint32_t width, std::uint32_t height) {
  std::string ihdr = big_endian(width) + big_endian(height);
  for (const int b : {8, 2, 0, 0, 0}) ihdr.push_back(char(b));  // depth, RGB, deflate, filter 0, no interlace
  const std::string empty_zlib("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", empty_zlib) +
         png_chunk("IEND", "");
}

// ---------------------------------------------------------------------------
// Running and checking

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::vector<std::string> folder_entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

struct Rendering {
  RunResult result;
  double seconds = 0;
  std::vector<std::string> before, after;  ///< the folder's entries around the run
  fs::path out;
};

/// `kappa render DIR/scene.json` at 8 x 8, 1 spp, quietly, into `out`
/// (DIR/out.exr unless given), with `extra` flags.
Rendering render(const TempDir& tmp, const std::vector<std::string>& extra = {}, const fs::path& out = {}) {
  Rendering run;
  run.out = out.empty() ? tmp / "out.exr" : out;
  std::vector<std::string> args = {"render", (tmp / "scene.json").string(), "--spp", "1", "--width", "8",
                                   "--height", "8", "--out", run.out.string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  run.before = folder_entries(tmp.path());
  const auto start = std::chrono::steady_clock::now();
  run.result = run_kappa(args, {}, kTimeoutS);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.after = folder_entries(tmp.path());
  return run;
}

/// Exit 2; exactly one line on stderr, the error, holding every fragment;
/// the folder as it was (no image, no temporary).
void expect_refused(const Rendering& run, const std::vector<std::string>& fragments) {
  const RunResult& r = run.result;
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  const std::vector<std::string> lines = r.err_lines();
  EXPECT_EQ(lines.size(), 1u) << "a refusal is exactly one line on stderr:\n" << r.std_err;
  const auto error =
      std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return starts_with(l, "kappa: error: "); });
  ASSERT_TRUE(error != lines.end()) << "no 'kappa: error: ' line:\n" << r.std_err;
  for (const std::string& f : fragments) EXPECT_TRUE(contains(*error, f)) << "does not say '" << f << "': " << *error;
  // No image, no temporary, no file replaced by another (the output is in
  // the folder too).
  EXPECT_EQ(run.after, run.before) << "a refusal leaves the folder as it was";
}

/// Exit 0 and a finite image; everything on stderr a warning (--quiet), one
/// of which holds every fragment.
void expect_warned(const Rendering& run, const std::vector<std::string>& fragments) {
  const RunResult& r = run.result;
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  const std::vector<std::string> lines = r.err_lines();
  for (const std::string& line : lines) EXPECT_TRUE(starts_with(line, "kappa: warning: ")) << line;
  const bool said = std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
    return std::all_of(fragments.begin(), fragments.end(), [&](const std::string& f) { return contains(line, f); });
  });
  EXPECT_TRUE(said) << "no warning says all of " << ::testing::PrintToString(fragments) << ":\n" << r.std_err;
  ASSERT_TRUE(fs::is_regular_file(run.out)) << r.std_err;
  const ExrFile image = read_exr_file(run.out);
  for (const char* channel : {"R", "G", "B"}) {
    ASSERT_GE(image.channel(channel), 0) << run.out << " has no channel " << channel;
    const std::vector<float> v = image.values(channel);
    EXPECT_FALSE(v.empty()) << channel;
    const auto bad = std::find_if(v.begin(), v.end(), [](float x) { return !std::isfinite(x); });
    if (bad != v.end()) ADD_FAILURE() << channel << " is " << *bad << " at pixel " << (bad - v.begin());
  }
}

// ---------------------------------------------------------------------------
// Texture maps: refused

TEST(TextureInput, AMissingTextureFileIsRefusedWithTheMtlLine) {
  TempDir tmp;
  write_scene(tmp.path(), "map_Kd nope.png");
  expect_refused(render(tmp), {"x.mtl:3: map_Kd: texture file 'nope.png' not found"});
}

TEST(TextureInput, ATextureThatIsADirectoryIsRefused) {
  TempDir tmp;
  fs::create_directory(tmp / "sub");
  write_scene(tmp.path(), "map_Kd sub");
  expect_refused(render(tmp), {"x.mtl:3: map_Kd: texture '", "sub' is not a regular file"});
}

TEST(TextureInput, ATextureThatIsAFifoIsRefusedWithoutWaitingOnIt) {
  TempDir tmp;
  ASSERT_EQ(::mkfifo((tmp / "fifo.png").c_str(), 0600), 0);
  write_scene(tmp.path(), "map_Kd fifo.png");
  const Rendering run = render(tmp);
  EXPECT_NE(run.result.exit_code, 124) << "timed out after " << kTimeoutS << " s: it waited on the FIFO";
  expect_refused(run, {"x.mtl:3: map_Kd: texture '", "fifo.png' is not a regular file"});
}

TEST(TextureInput, ATruncatedPngIsRefusedWithTheMtlLineAndItsName) {
  TempDir tmp;
  const std::string png = read_file(textured_box() / "floor_checker.png");
  ASSERT_GT(png.size(), 64u);
  write_file(tmp / "half.png", png.substr(0, png.size() / 2));  // its header whole, its IDAT cut
  write_scene(tmp.path(), "map_Kd half.png");
  expect_refused(render(tmp), {"x.mtl:3: map_Kd '", "half.png'"});
}

TEST(TextureInput, AFileThatIsNotAnImageIsRefused) {
  TempDir tmp;
  write_file(tmp / "tex.png", "this is not an image, whatever its name says\n");
  write_scene(tmp.path(), "map_Kd tex.png");
  expect_refused(render(tmp), {"x.mtl:3: map_Kd '", "tex.png': cannot read it as an image"});
}

TEST(TextureInput, APngDeclaring65536SquaredTexelsIsRefusedFromItsHeader) {
  TempDir tmp;
  write_file(tmp / "huge.png", png_declaring(65536, 65536));
  write_scene(tmp.path(), "map_Kd huge.png");
  const Rendering run = render(tmp);
  // Its texels (12 GiB as 8-bit, 48 GiB as float) are never allocated: the
  // header alone refuses it, at once.
  EXPECT_NE(run.result.exit_code, 124) << "timed out after " << kTimeoutS << " s";
  EXPECT_LT(run.seconds, 30.0) << "a refusal from the header takes well under a second";
  expect_refused(run, {"x.mtl:3: map_Kd '", "huge.png' is 65536x65536: more than Kappa's limit"});
}

// ---------------------------------------------------------------------------
// Texture maps: warned

TEST(TextureInput, AOneByOneTextureIsWarnedAboutAsAConstant) {
  TempDir tmp;
  kappa::write_png(tmp / "one.png", 1, 1, {200, 100, 50});
  write_scene(tmp.path(), "map_Kd one.png");
  expect_warned(render(tmp), {"x.mtl:3: map_Kd '", "one.png' is 1x1: a constant over the surface"});
}

TEST(TextureInput, AnOpacityMapWithoutAlphaIsWarnedAboutAndStaysOpaque) {
  TempDir tmp;
  fs::copy_file(textured_box() / "floor_checker.png", tmp / "rgb.png");  // 8-bit RGB, no alpha
  write_scene(tmp.path(), "map_d rgb.png");
  expect_warned(render(tmp), {"x.mtl:3: map_d '", "rgb.png' has no alpha channel"});
}

TEST(TextureInput, NaNAndNegativeTexelsAreWarnedAboutAndReadAsZero) {
  TempDir tmp;
  std::vector<float> rgb = flat_rgb(4, 4, 0.5f, 0.5f, 0.5f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  rgb[0] = rgb[1] = rgb[2] = nan;  // texel 0: NaN in all three channels
  rgb[3 * 5] = -0.25f;             // texel 5: a negative red
  write_rgb_exr(tmp / "nan.exr", 4, 4, rgb);
  write_scene(tmp.path(), "map_Kd nan.exr");
  expect_warned(render(tmp), {"x.mtl:3: map_Kd '", "nan.exr' has 3 NaN, 0 infinite and 1 negative texel values"});
}

// ---------------------------------------------------------------------------
// Environment images

TEST(TextureInput, AMissingEnvironmentImageIsRefusedNamingTheScene) {
  TempDir tmp;
  write_scene(tmp.path(), "", "\"sky.hdr\"");
  expect_refused(render(tmp), {"scene.json: environment image '", "sky.hdr' not found"});
}

TEST(TextureInput, AnEnvironmentImageThatIsNotTwoToOneIsWarnedAbout) {
  TempDir tmp;
  write_rgb_exr(tmp / "env.exr", 8, 8, flat_rgb(8, 8, 0.5f, 0.5f, 0.5f));
  write_scene(tmp.path(), "", "\"env.exr\"");
  expect_warned(render(tmp), {"scene.json: environment image '", "env.exr' is 8x8, not 2:1"});
}

TEST(TextureInput, NaNInfiniteAndNegativeEnvironmentValuesAreWarnedAboutAndReadAsZero) {
  TempDir tmp;
  std::vector<float> rgb = flat_rgb(16, 8, 0.5f, 0.5f, 0.5f);  // 2:1: no other warning
  rgb[0] = std::numeric_limits<float>::quiet_NaN();           // texel 0, red
  rgb[3 * 9 + 1] = -1.0f;                                       // texel 9, green
  rgb[3 * 40 + 2] = std::numeric_limits<float>::infinity();     // texel 40, blue
  write_rgb_exr(tmp / "env.exr", 16, 8, rgb);
  write_scene(tmp.path(), "", "\"env.exr\"");
  expect_warned(render(tmp), {"scene.json: environment image '",
                              "env.exr' has 3 NaN, infinite or negative values: read as 0"});
}

TEST(TextureInput, ARotationOfAConstantEnvironmentIsWarnedAboutAndIgnored) {
  TempDir tmp;
  write_scene(tmp.path(), "", "[0.5, 0.5, 0.5]", ", \"environment_rotation_deg\": 90");
  expect_warned(render(tmp), {"scene.json: environment_rotation_deg ignored"});
}

// ---------------------------------------------------------------------------
// Outputs over the images a scene reads

TEST(TextureInput, AnOutputOverATextureIsRefusedAndTheTextureKept) {
  {
    SCOPED_TRACE("--out over an EXR map_Kd");
    TempDir tmp;
    write_rgb_exr(tmp / "tex.exr", 4, 4, flat_rgb(4, 4, 0.2f, 0.4f, 0.6f));
    const std::string bytes = read_file(tmp / "tex.exr");
    write_scene(tmp.path(), "map_Kd tex.exr");
    expect_refused(render(tmp, {}, tmp / "tex.exr"), {"tex.exr: is the input file '", "refusing to overwrite an input"});
    EXPECT_EQ(read_file(tmp / "tex.exr"), bytes) << "the texture changed";
  }
  {
    SCOPED_TRACE("--report over a PNG map_Kd");
    TempDir tmp;
    fs::copy_file(textured_box() / "floor_checker.png", tmp / "tex.png");
    const std::string bytes = read_file(tmp / "tex.png");
    write_scene(tmp.path(), "map_Kd tex.png");
    expect_refused(render(tmp, {"--report", (tmp / "tex.png").string()}),
                   {"tex.png: is the input file '", "refusing to overwrite an input"});
    EXPECT_EQ(read_file(tmp / "tex.png"), bytes) << "the texture changed";
  }
}

TEST(TextureInput, AnOutputOverTheEnvironmentImageIsRefusedAndTheImageKept) {
  TempDir tmp;
  write_rgb_exr(tmp / "env.exr", 16, 8, flat_rgb(16, 8, 0.5f, 0.5f, 0.5f));
  const std::string bytes = read_file(tmp / "env.exr");
  write_scene(tmp.path(), "", "\"env.exr\"");
  expect_refused(render(tmp, {}, tmp / "env.exr"), {"env.exr: is the input file '", "refusing to overwrite an input"});
  EXPECT_EQ(read_file(tmp / "env.exr"), bytes) << "the environment image changed";
}

// ---------------------------------------------------------------------------
// Texture coordinates

TEST(TextureInput, AFaceVtIndexOutOfRangeIsRefusedWithItsLine) {
  // Line 11 names vt 99 of 4: tinyobjloader only warns (Kappa drops its
  // words), and the triangle would render with no texture coordinates.
  TempDir tmp;
  std::string obj = kQuadObj;
  const std::string face = "f 1/1 2/2 3/3\n";
  obj.replace(obj.find(face), face.size(), "f 1/99 2/99 3/99\n");
  fs::copy_file(textured_box() / "floor_checker.png", tmp / "tex.png");
  write_scene(tmp.path(), "map_Kd tex.png", "[1, 1, 1]", "", obj);
  const Rendering run = render(tmp);
  expect_refused(run, {"x.obj:11: "});
  // The message after the location names the index and says it is a vt.
  const std::string& err = run.result.std_err;
  const std::size_t at = err.find("x.obj:11: ");
  ASSERT_NE(at, std::string::npos) << err;
  const std::string message = err.substr(at + 10);
  EXPECT_TRUE(contains(message, "99")) << message;
  EXPECT_TRUE(contains(message, "vt")) << message;
}

}  // namespace
}  // namespace kappa::test
