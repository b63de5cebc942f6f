#include "renderer/io/exr_input.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <string>

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

std::string gib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(std::uint64_t(1) << 30));
  return text;
}

}  // namespace

ReferenceImage read_reference(const std::filesystem::path& path, std::optional<FilmSize> film) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, 0, "reference image not found");
  check_exr_header(path);  // before OpenEXR allocates what a header declares
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
  if (film && (spec.width != film->width || spec.height != film->height))
    fail(path, 0,
         "the reference is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", the film " +
             std::to_string(film->width) + "x" + std::to_string(film->height) + " (set --width and --height)");
  const std::size_t nc = std::size_t(spec.nchannels);
  const std::size_t pixels = std::size_t(spec.width) * std::size_t(spec.height);
  // Every channel as read, then RGB and variance kept: 4 bytes each. Both
  // factors are below 2^31, so the product fits 64 bits.
  const std::uint64_t needed = std::uint64_t(pixels) * (std::uint64_t(nc) + 6) * sizeof(float);
  if (needed > physical_memory_bytes())
    fail(path, 0,
         "the reference is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " with " +
             std::to_string(nc) + " channels: reading it needs " + gib(needed) + ", more than this machine's " +
             gib(physical_memory_bytes()));
  // Not value-initialised: OpenImageIO writes every value it returns true for.
  const std::unique_ptr<float[]> all(new float[pixels * nc]);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.get()))
    fail(path, 0, "cannot read the reference image: " + in->geterror());
  in->close();

  ReferenceImage image;
  image.width = spec.width;
  image.height = spec.height;
  const auto take = [&](std::vector<float>& out, int c0, int c1, int c2) {
    out.resize(3 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      const int cs[3] = {c0, c1, c2};
      for (int c = 0; c < 3; ++c) {
        const float v = all[i * nc + std::size_t(cs[c])];
        if (!std::isfinite(v) || v < 0)
          fail(path, 0, "the reference image has a non-finite or negative value at pixel (" +
                            std::to_string(i % std::size_t(spec.width)) + ", " +
                            std::to_string(i / std::size_t(spec.width)) + ")");
        out[3 * i + std::size_t(c)] = v;
      }
    }
  };
  take(image.rgb, r, g, b);
  const int vr = channel_index(spec, "variance.R"), vg = channel_index(spec, "variance.G"),
            vb = channel_index(spec, "variance.B");
  if (vr >= 0 && vg >= 0 && vb >= 0) take(image.variance, vr, vg, vb);
  return image;
}

}  // namespace kappa
