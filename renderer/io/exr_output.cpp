#include "renderer/io/exr_output.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cerrno>
#include <ctime>
#include <exception>
#include <fstream>
#include <type_traits>

#include "core/check.h"
#include "core/error.h"

namespace kappa {
namespace {

/// The local time in capDate's form, "YYYY:MM:DD hh:mm:ss" (OpenEXR's
/// standard attribute; OpenImageIO, which wrote Kappa's EXRs before, added it).
std::string cap_date() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

}  // namespace

std::vector<std::string> exr_channel_names(const Film& film) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (!film.albedo.empty()) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
  if (!film.normal.empty()) names.insert(names.end(), {"normal.X", "normal.Y", "normal.Z"});
  if (!film.depth.empty()) names.push_back("depth.Z");
  if (!film.cost_cells.empty()) names.insert(names.end(), {"cost.cells", "cost.tests"});
  if (!film.variance.empty()) names.insert(names.end(), {"variance.R", "variance.G", "variance.B"});
  if (!film.spp.empty()) names.push_back("spp");
  return names;
}

void write_float_exr(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& names,
                     const std::vector<float>& pixels, const Metadata& metadata, const std::filesystem::path& shown) {
  const std::filesystem::path& name = shown.empty() ? path : shown;
  const std::size_t nc = names.size();
  KAPPA_CHECK_EQ(pixels.size(), std::size_t(width) * std::size_t(height) * nc);
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const std::string& channel : names) header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
  for (const auto& [key, value] : metadata) {
    std::visit(
        [&, k = key](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::string>) header.insert(k, Imf::StringAttribute(v));
          else if constexpr (std::is_same_v<T, int>) header.insert(k, Imf::IntAttribute(v));
          else if constexpr (std::is_same_v<T, float>) header.insert(k, Imf::FloatAttribute(v));
          else header.insert(k, Imf::DoubleAttribute(v));
        },
        value);
  }
  Imf::addCapDate(header, cap_date());
  Imf::FrameBuffer frame;
  const std::size_t x_stride = nc * sizeof(float), y_stride = x_stride * std::size_t(width);
  for (std::size_t c = 0; c < nc; ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(pixels.data() + c)),
                                      x_stride, y_stride));
  // OpenEXR reports a failed write in its own words; errno still holds the
  // system's reason (EFBIG, ENOSPC, EIO).
  errno = 0;
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  if (!stream) fail_output(name, "cannot write EXR", errno);
  try {
    Imf::StdOFStream exr_stream(stream, path.c_str());
    Imf::OutputFile file(exr_stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  } catch (const std::exception& e) {
    const int err = errno;
    fail_output(name, std::string("cannot write EXR (") + e.what() + ")", err);
  }
  // OutputFile's destructor writes the line offset table and swallows any
  // failure; the stream, ours, keeps it, and its close flushes the rest.
  errno = 0;
  stream.close();
  if (stream.fail()) fail_output(name, "cannot write EXR (its line offsets or last bytes)", errno);
}

void write_exr(const std::filesystem::path& path, const Film& film, const Metadata& metadata,
               const std::filesystem::path& shown) {
  const std::vector<std::string> names = exr_channel_names(film);
  const std::size_t nc = names.size();
  std::vector<float> pixels(film.pixels() * nc);
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    float* out = &pixels[i * nc];
    for (int c = 0; c < 3; ++c) *out++ = film.rgb[3 * i + std::size_t(c)];
    if (!film.albedo.empty())
      for (int c = 0; c < 3; ++c) *out++ = film.albedo[3 * i + std::size_t(c)];
    if (!film.normal.empty())
      for (int c = 0; c < 3; ++c) *out++ = film.normal[3 * i + std::size_t(c)];
    if (!film.depth.empty()) *out++ = film.depth[i];
    if (!film.cost_cells.empty()) {
      *out++ = film.cost_cells[i];
      *out++ = film.cost_tests[i];
    }
    if (!film.variance.empty())
      for (int c = 0; c < 3; ++c) *out++ = film.variance[3 * i + std::size_t(c)];
    if (!film.spp.empty()) *out++ = film.spp[i];
  }
  write_float_exr(path, film.width, film.height, names, pixels, metadata, shown);
}

}  // namespace kappa
