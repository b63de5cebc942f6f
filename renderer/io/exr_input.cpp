#include "renderer/io/exr_input.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <exception>
#include <string>

#include "core/error.h"
#include "core/physical_memory.h"
#include "renderer/io/exr_header.h"

namespace kappa {
namespace {

std::string gib(double bytes) {
  char text[48];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(std::uint64_t(1) << 30));
  return text;
}

/// Bytes reading a width x height reference holds at once: the RGB and
/// variance kept (OpenEXR converts each channel to float as it decodes, into
/// them), and OpenEXR's one decoding buffer (Kappa starts no OpenEXR thread
/// pool), a chunk compressed and decompressed. In double: a header can
/// declare 2^32 x 2^32 pixels.
double reading_bytes(const ExrLayout& layout) {
  return double(layout.width) * double(layout.height) * 6 * sizeof(float) + 2 * layout.chunk_bytes();
}

}  // namespace

ReferenceImage read_reference(const std::filesystem::path& path, std::optional<FilmSize> film,
                              std::optional<std::uint64_t> max_bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, 0, "reference image not found");
  // From the header, before OpenEXR's open allocates what it declares.
  const ExrLayout layout = check_exr_header(path);
  // An inverted or empty data window (or none) would otherwise reach
  // OpenEXR's own sanity check only after it allocates for the header.
  if (layout.width <= 0 || layout.height <= 0)
    fail(path, 0, "not a 2D image: its data window is " + std::to_string(layout.width) + "x" +
                      std::to_string(layout.height));
  if (film && (layout.width != film->width || layout.height != film->height))
    fail(path, 0,
         "the reference is " + std::to_string(layout.width) + "x" + std::to_string(layout.height) + ", the film " +
             std::to_string(film->width) + "x" + std::to_string(film->height) + " (set --width and --height)");
  const std::uint64_t limit = max_bytes ? *max_bytes : physical_memory_bytes();
  if (const double needed = reading_bytes(layout); needed > double(limit))
    fail(path, 0,
         "the reference is " + std::to_string(layout.width) + "x" + std::to_string(layout.height) + " with " +
             std::to_string(layout.channels) + " channels: reading it needs " + gib(needed) + ", more than " +
             (max_bytes ? "the limit of " : "this machine's ") + gib(double(limit)));
  ReferenceImage image;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    // The walk read the same header: a disagreement would size the buffers
    // below from a window the checks above did not see.
    if (std::int64_t(window.max.x) - window.min.x + 1 != layout.width ||
        std::int64_t(window.max.y) - window.min.y + 1 != layout.height)
      fail(path, 0, "OpenEXR reads another data window than the header declares");
    const Imf::ChannelList& channels = header.channels();
    const auto has = [&](const char* name) {
      const Imf::Channel* c = channels.findChannel(name);
      if (c && (c->xSampling != 1 || c->ySampling != 1))
        fail(path, 0, std::string("channel ") + name + " of the reference image is subsampled");
      return c != nullptr;
    };
    if (!has("R") || !has("G") || !has("B")) fail(path, 0, "the reference image has no R, G and B channels");
    const bool variance = has("variance.R") && has("variance.G") && has("variance.B");
    image.width = int(layout.width);
    image.height = int(layout.height);
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    image.rgb.resize(3 * pixels);
    if (variance) image.variance.resize(3 * pixels);
    Imf::FrameBuffer frame;
    const auto take = [&](std::vector<float>& out, const char* r, const char* g, const char* b) {
      const char* names[3] = {r, g, b};
      for (int k = 0; k < 3; ++k)
        frame.insert(names[k], Imf::Slice::Make(Imf::FLOAT, out.data() + k, window, 3 * sizeof(float),
                                                3 * sizeof(float) * std::size_t(image.width)));
    };
    take(image.rgb, "R", "G", "B");
    if (variance) take(image.variance, "variance.R", "variance.G", "variance.B");
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, 0, std::string("cannot read the reference image: ") + e.what());
  }
  for (const std::vector<float>* values : {&image.rgb, &image.variance})
    for (std::size_t i = 0; i < values->size(); ++i)
      if (!std::isfinite((*values)[i]) || (*values)[i] < 0)
        fail(path, 0, "the reference image has a non-finite or negative value at pixel (" +
                          std::to_string(i / 3 % std::size_t(image.width)) + ", " +
                          std::to_string(i / 3 / std::size_t(image.width)) + ")");
  return image;
}

}  // namespace kappa
