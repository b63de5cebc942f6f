#include "renderer/io/exr_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "accel/physical_memory.h"
#include "renderer/io/exr_header.h"
#include "renderer/util/error.h"

namespace kappa {
namespace {

int channel_index(const OIIO::ImageSpec& spec, const char* name) {
  const auto& names = spec.channelnames;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

std::string gib(double bytes) {
  char text[48];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(std::uint64_t(1) << 30));
  return text;
}

/// Bytes reading a width x height reference holds at once: every pixel in
/// the file's own channel types (read so, OpenImageIO keeps no conversion
/// buffer: its 256 scanlines of a wide image were 33 GB for a 1 kB file
/// declaring 5373955 x 3 pixels), the RGB and variance kept, and OpenEXR's
/// decoding buffers, which its open allocates: two a thread of its pool, each
/// a chunk compressed and decompressed. In double: a header can declare
/// 2^32 x 2^32 pixels.
double reading_bytes(double width, double height, double pixel_bytes, double chunk_bytes) {
  const double threads = std::max(1u, std::thread::hardware_concurrency());
  return width * height * (pixel_bytes + 6 * sizeof(float)) + 2 * threads * 2 * chunk_bytes;
}

}  // namespace

ReferenceImage read_reference(const std::filesystem::path& path, std::optional<FilmSize> film,
                              std::optional<std::uint64_t> max_bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, 0, "reference image not found");
  // From the header, before OpenEXR's open allocates what it declares.
  const ExrLayout layout = check_exr_header(path);
  const std::uint64_t limit = max_bytes ? *max_bytes : physical_memory_bytes();
  const auto refuse_size = [&](std::int64_t width, std::int64_t height) {
    if (film && (width != film->width || height != film->height))
      fail(path, 0,
           "the reference is " + std::to_string(width) + "x" + std::to_string(height) + ", the film " +
               std::to_string(film->width) + "x" + std::to_string(film->height) + " (set --width and --height)");
  };
  const auto refuse_memory = [&](std::int64_t width, std::int64_t height, int channels, double needed) {
    if (needed > double(limit))
      fail(path, 0,
           "the reference is " + std::to_string(width) + "x" + std::to_string(height) + " with " +
               std::to_string(channels) + " channels: reading it needs " + gib(needed) + ", more than " +
               (max_bytes ? "the limit of " : "this machine's ") + gib(double(limit)));
  };
  refuse_size(layout.width, layout.height);
  refuse_memory(layout.width, layout.height, layout.channels,
                reading_bytes(double(layout.width), double(layout.height), double(layout.pixel_bytes),
                              layout.chunk_bytes()));
  // OpenEXR's reader only: ImageInput::open would hand a file its reader
  // refuses to every other plugin in turn (TIFF, libraw, ffmpeg, ...), whose
  // parsers a reference never needs (a PPM named .exr was read as one).
  auto in = OIIO::ImageInput::create("openexr");
  OIIO::ImageSpec opened;
  if (!in || !in->open(path.string(), opened))
    fail(path, 0, "cannot read the reference image: " + (in ? in->geterror() : OIIO::geterror()));
  const OIIO::ImageSpec spec = in->spec();
  const int r = channel_index(spec, "R"), g = channel_index(spec, "G"), b = channel_index(spec, "B");
  if (r < 0 || g < 0 || b < 0) fail(path, 0, "the reference image has no R, G and B channels");
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) fail(path, 0, "the reference image is not a 2D image");
  // Again from what OpenEXR read, which sizes the buffers below.
  refuse_size(spec.width, spec.height);
  const std::uint64_t pixels = std::uint64_t(spec.width) * std::uint64_t(spec.height);
  const std::uint64_t native_pixel = spec.pixel_bytes(true);  // every channel in its file type
  refuse_memory(spec.width, spec.height, spec.nchannels,
                reading_bytes(spec.width, spec.height, double(native_pixel), 0));
  const int vr = channel_index(spec, "variance.R"), vg = channel_index(spec, "variance.G"),
            vb = channel_index(spec, "variance.B");
  const bool has_variance = vr >= 0 && vg >= 0 && vb >= 0;
  // Not value-initialised: OpenImageIO writes every byte it returns true for.
  const std::unique_ptr<unsigned char[]> native(new unsigned char[pixels * native_pixel]);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, native.get()))
    fail(path, 0, "cannot read the reference image: " + in->geterror());
  in->close();

  ReferenceImage image;
  image.width = spec.width;
  image.height = spec.height;
  // Channels c0, c1, c2 as float, three a pixel, each checked.
  const auto take = [&](std::vector<float>& out, int c0, int c1, int c2) {
    out.resize(3 * pixels);
    const int cs[3] = {c0, c1, c2};
    for (int k = 0; k < 3; ++k) {
      const int c = cs[k];
      const OIIO::stride_t native_row = OIIO::stride_t(native_pixel) * spec.width;
      if (!OIIO::convert_image(1, spec.width, spec.height, 1, native.get() + spec.pixel_bytes(0, c, true),
                               spec.channelformat(c), OIIO::stride_t(native_pixel), native_row, OIIO::AutoStride,
                               out.data() + k, OIIO::TypeDesc::FLOAT, 3 * sizeof(float),
                               OIIO::stride_t(3 * sizeof(float)) * spec.width, OIIO::AutoStride))
        fail(path, 0, "cannot convert channel " + spec.channelnames[std::size_t(c)] + " of the reference image");
    }
    for (std::uint64_t i = 0; i < 3 * pixels; ++i)
      if (!std::isfinite(out[i]) || out[i] < 0)
        fail(path, 0, "the reference image has a non-finite or negative value at pixel (" +
                          std::to_string(i / 3 % std::uint64_t(spec.width)) + ", " +
                          std::to_string(i / 3 / std::uint64_t(spec.width)) + ")");
  };
  take(image.rgb, r, g, b);
  if (has_variance) take(image.variance, vr, vg, vb);
  return image;
}

}  // namespace kappa
