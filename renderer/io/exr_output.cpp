#include "renderer/io/exr_output.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <type_traits>

#include "renderer/util/error.h"

namespace kappa {

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

void write_exr(const std::filesystem::path& path, const Film& film, const Metadata& metadata,
               const std::filesystem::path& shown) {
  const std::filesystem::path& name = shown.empty() ? path : shown;
  // OpenEXR reports a failed write in its own words; errno still holds the
  // system's reason (EFBIG, ENOSPC, EIO).
  const auto failed = [&](const std::string& what) {
    const int err = errno;
    fail_output(name, "cannot write EXR (" + what + ")", err);
  };
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

  OIIO::ImageSpec spec(film.width, film.height, int(nc), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  const auto z = std::find(names.begin(), names.end(), "depth.Z");
  spec.z_channel = z == names.end() ? -1 : int(z - names.begin());
  spec.attribute("compression", "zip");
  for (const auto& [key, value] : metadata) {
    std::visit(
        [&, k = key](const auto& v) {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>) spec.attribute(k, OIIO::TypeDesc::DOUBLE, &v);
          else spec.attribute(k, v);
        },
        value);
  }

  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) fail(path, 0, "OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
  errno = 0;
  if (!out->open(path.string(), spec)) failed(out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) failed(out->geterror());
  if (!out->close()) failed(out->geterror());
}

}  // namespace kappa
